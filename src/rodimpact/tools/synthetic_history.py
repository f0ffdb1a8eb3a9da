"""A synthetic record, labelled as one: a method's computed contact force, or strain at a
gauge, sampled as an oscilloscope would sample it, plus stated noise (the worked examples of a
comparison and of a calibration).

It is not a measurement, and the files it writes say so in their names and in the case's
``measured`` block. It runs one method on one case, with any of the case's settings changed
first (``--set rod.material.youngs_modulus_pa=2.05e11``: the "true" constants a calibration
should recover), and samples the signal every ``sample_us`` µs:

* the force (``--gauge`` not given), from ``pretrigger_us`` before the contact to
  ``posttrigger_us`` after its end (zero outside the contact), its times shifted by
  ``trigger_us`` (the trigger's place in the record);
* the axial strain at a gauge (``--gauge STATION_M[,LENGTH_M]``), from ``pretrigger_us``
  before the impact to ``posttrigger_us`` after the end of the contact's wave at the gauge
  (x/c after the contact's end), on the impact's clock (``trigger_us`` is not added: the
  arrival of the first wave is read on that clock).

It multiplies the signal by ``gain`` (a sensor's calibration error) and adds Gaussian noise of
standard deviation ``noise`` times its largest |value|, drawn from ``seed``. The same arguments
give the same file, byte for byte.

``python -m rodimpact.tools.synthetic_history --case-file config/cases/worked_example.yaml --case ID
--method fem1d --out config/cases/example/ID.synthetic.csv [--noise 0.01 --seed 1 --gauge 0.25,0.005
--set impactor.velocity_m_s=1.05 ...]``
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
    #: the gauge's (station_m, gauge_length_m) for a strain record; None for a force record
    gauge: tuple[float, float] | None = None


def synthetic_history(case: Mapping[str, Any], record: SyntheticRecord) -> tuple[np.ndarray, np.ndarray, dict]:
    """Times (µs) and values (force, N; or strain, 1) of the synthetic record of ``case``, and
    what the run gave (for a force: ``contact_time_us``, ``peak_force_n``,
    ``rebound_velocity_m_s``, the values a drop test's record would be read for)."""
    case = {**case, "methods": [record.method]}
    if record.gauge is not None:
        gauge = {"station_m": float(record.gauge[0]), "gauge_length_m": float(record.gauge[1])}
        case = {**case, "gauges": [gauge], "outputs": [*case["outputs"], "gauge_strain"]}
    result = run_case(case, record.method)
    t, force = np.asarray(result.time, float), np.asarray(result.contact_force, float)
    end = float(result.contact_end_s[-1]) if len(result.contact_end_s) else float(t[-1])
    rng = np.random.default_rng(record.seed)
    if record.gauge is not None:
        material = case["rod"]["material"]
        transit = record.gauge[0] / np.sqrt(material["youngs_modulus_pa"] / material["density_kg_m3"])
        samples = np.arange(-record.pretrigger_us, 1e6 * (end + transit) + record.posttrigger_us, record.sample_us)
        strain = np.asarray(result.series(["gauge_strain"])["gauge_strain"][0], float).reshape(len(t), -1)[:, 0]
        clean = np.interp(1e-6 * samples, t, strain, left=0.0, right=float(strain[-1]))
        largest = float(np.max(np.abs(strain)))
        noisy = record.gain * clean + rng.normal(0.0, record.noise * largest, len(samples))
        return samples, noisy, {"peak_strain": float(strain[np.argmax(np.abs(strain))])}
    samples = np.arange(-record.pretrigger_us, 1e6 * end + record.posttrigger_us, record.sample_us)
    clean = np.interp(1e-6 * samples, t, force, left=0.0, right=0.0)
    peak = float(force.max())
    noisy = record.gain * clean + rng.normal(0.0, record.noise * peak, len(samples))
    facts = {
        "contact_time_us": 1e6 * float(result.contact_time_s),
        "peak_force_n": peak,
        "rebound_velocity_m_s": -float(result.rebound_velocity_m_s),
    }
    return samples + record.trigger_us, noisy, facts


def write_synthetic_history(case: Mapping[str, Any], record: SyntheticRecord, out: str | Path) -> dict:
    """Write :func:`synthetic_history` as a CSV (``time_us,force_N`` or
    ``time_us,strain_microstrain``, atomically); returns its facts."""
    times, values, facts = synthetic_history(case, record)
    if record.gauge is None:
        lines = ["time_us,force_N", *(f"{t:.3f},{f:.6g}" for t, f in zip(times, values, strict=True))]
    else:
        lines = ["time_us,strain_microstrain", *(f"{t:.3f},{1e6 * f:.6g}" for t, f in zip(times, values, strict=True))]
    with atomic_output(out) as tmp:
        tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
    log.info("wrote %d samples to %s: %s", len(times), out, facts)
    return facts


def main(argv: Sequence[str] | None = None) -> int:
    from rodimpact.config.load import load_case_file, load_global_config
    from rodimpact.config.paths import with_setting

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case-file", required=True)
    parser.add_argument("--case", required=True, help="the case's id")
    parser.add_argument("--out", required=True, help="the CSV to write")
    parser.add_argument("--root", default=".")
    parser.add_argument("--gauge", help="a strain record at this gauge: STATION_M[,LENGTH_M]")
    parser.add_argument(
        "--set", action="append", default=[], metavar="PATH=VALUE", help="change a setting of the case first"
    )
    defaults = SyntheticRecord()
    for name in ("method", "noise", "gain", "seed", "sample_us", "pretrigger_us", "posttrigger_us", "trigger_us"):
        value = getattr(defaults, name)
        parser.add_argument(f"--{name.replace('_', '-')}", type=type(value), default=value)
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(message)s")
    config = load_global_config(Path(args.root) / "config" / "config.yaml")
    cases = load_case_file(args.case_file, config, args.root)
    gauge = None
    if args.gauge:
        station, _, length = args.gauge.partition(",")
        gauge = (float(station), float(length or 0.0))
    fields = {k: getattr(args, k) for k in SyntheticRecord.__dataclass_fields__ if k != "gauge"}
    record = SyntheticRecord(**fields, gauge=gauge)
    case = cases[args.case]
    for assignment in args.set:
        path, _, value = assignment.partition("=")
        case = with_setting(case, path, float(value))
    facts = write_synthetic_history(case, record, args.out)
    print(", ".join(f"{k} = {v:.6g}" for k, v in facts.items()))  # noqa: T201 (a command's answer)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
