"""A synthetic force history, labelled as one: a method's computed force, sampled as an
oscilloscope would sample it, plus stated noise (the worked example of a comparison).

It is not a measurement, and the files it writes say so in their names and in the case's
``measured`` block. It runs one method on one case and samples the contact force every
``sample_us`` µs from ``pretrigger_us`` before the contact to ``posttrigger_us`` after its
end (zero outside the contact). It multiplies the force by ``gain`` (a sensor's calibration
error) and adds Gaussian noise of standard deviation ``noise`` times the peak, drawn from
``seed``. The times are shifted by ``trigger_us`` (the trigger's place in the record). The
same arguments give the same file, byte for byte.

``python -m rodimpact.tools.synthetic_history --case-file config/cases/worked_example.yaml --case ID
--method fem1d --out config/cases/example/ID.synthetic.csv [--noise 0.01 --seed 1 ...]``
"""

from __future__ import annotations

import argparse
import logging
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from rodimpact.jobs.runner import run_case
from rodimpact.storage.atomic import atomic_output

__all__ = ["SyntheticRecord", "synthetic_history", "write_synthetic_history"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class SyntheticRecord:
    """How a synthetic history is made from a run (see the module docstring); times in µs."""

    method: str = "fem1d"
    noise: float = 0.01
    gain: float = 1.0
    seed: int = 1
    sample_us: float = 1.0
    pretrigger_us: float = 20.0
    posttrigger_us: float = 40.0
    trigger_us: float = 100.0


def synthetic_history(case: Mapping[str, Any], record: SyntheticRecord) -> tuple[np.ndarray, np.ndarray, dict]:
    """Times (µs) and forces (N) of the synthetic record of ``case``, and what the run gave
    (``contact_time_us``, ``peak_force_n``, ``rebound_velocity_m_s``: the values a drop test's
    record would be read for)."""
    case = {**case, "methods": [record.method]}
    result = run_case(case, record.method)
    t, force = np.asarray(result.time, float), np.asarray(result.contact_force, float)
    end = float(result.contact_end_s[-1]) if len(result.contact_end_s) else float(t[-1])
    samples = np.arange(-record.pretrigger_us, 1e6 * end + record.posttrigger_us, record.sample_us)
    clean = np.interp(1e-6 * samples, t, force, left=0.0, right=0.0)
    peak = float(force.max())
    noisy = record.gain * clean + np.random.default_rng(record.seed).normal(0.0, record.noise * peak, len(samples))
    facts = {
        "contact_time_us": 1e6 * float(result.contact_time_s),
        "peak_force_n": peak,
        "rebound_velocity_m_s": -float(result.rebound_velocity_m_s),
    }
    return samples + record.trigger_us, noisy, facts


def write_synthetic_history(case: Mapping[str, Any], record: SyntheticRecord, out: str | Path) -> dict:
    """Write :func:`synthetic_history` as a CSV (``time_us,force_N``, atomically); returns its facts."""
    times, forces, facts = synthetic_history(case, record)
    lines = ["time_us,force_N", *(f"{t:.3f},{f:.6g}" for t, f in zip(times, forces))]
    with atomic_output(out) as tmp:
        tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
    log.info("wrote %d samples to %s: %s", len(times), out, facts)
    return facts


def main(argv: Sequence[str] | None = None) -> int:
    from rodimpact.config.load import load_case_file, load_global_config

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case-file", required=True)
    parser.add_argument("--case", required=True, help="the case's id")
    parser.add_argument("--out", required=True, help="the CSV to write")
    parser.add_argument("--root", default=".")
    defaults = SyntheticRecord()
    for name in ("method", "noise", "gain", "seed", "sample_us", "pretrigger_us", "posttrigger_us", "trigger_us"):
        value = getattr(defaults, name)
        parser.add_argument(f"--{name.replace('_', '-')}", type=type(value), default=value)
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(message)s")
    config = load_global_config(Path(args.root) / "config" / "config.yaml")
    cases = load_case_file(args.case_file, config, args.root)
    record = SyntheticRecord(**{k: getattr(args, k) for k in SyntheticRecord.__dataclass_fields__})
    facts = write_synthetic_history(cases[args.case], record, args.out)
    print(", ".join(f"{k} = {v:.6g}" for k, v in facts.items()))  # noqa: T201 (a command's answer)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
