"""How long snakemake takes to plan the workflow: the dry run against a one-rule workflow
(``make bench``, not tests).

Each figure is the wall time of a whole ``snakemake -n --quiet rules`` process (the
environment's own snakemake, in ``root``), over ``runs`` runs after one run not counted:

* ``dry_run``: the workflow in ``root``, which checks the whole configuration and every job's
  resources at each start;
* ``one_rule``: a workflow of one rule that touches a file, in a temporary directory: what
  snakemake itself takes to start and plan, whatever the workflow.

``python -m rodimpact.tools.bench_planning [--root .] [--runs 7] [--csv results/benchmarks/planning.csv]``
writes one row per figure: ``runs``, ``median_s``, ``min_s``, ``max_s``.
"""

from __future__ import annotations

import argparse
import csv
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from rodimpact.storage.atomic import atomic_output

__all__ = ["Timing", "main", "time_dry_runs", "write_timings"]

_ONE_RULE = 'rule all:\n    output:\n        "a.txt",\n    shell:\n        "touch {output}"\n'


@dataclass(frozen=True)
class Timing:
    """Wall times of one kind of dry run, s."""

    name: str
    seconds: tuple[float, ...]

    @property
    def median_s(self) -> float:
        return statistics.median(self.seconds)


def _snakemake() -> str:
    """The snakemake of the environment this runs in (beside its Python)."""
    return str(Path(sys.executable).parent / "snakemake")


def _timed(root: Path, runs: int) -> tuple[float, ...]:
    command = [_snakemake(), "-n", "--quiet", "rules"]
    seconds = []
    for index in range(runs + 1):  # the first run is not counted (files cached)
        started = time.perf_counter()
        subprocess.run(command, cwd=root, check=True, capture_output=True)
        if index:
            seconds.append(time.perf_counter() - started)
    return tuple(seconds)


def time_dry_runs(root: str | Path, runs: int) -> list[Timing]:
    """The two timings of the module's docstring, ``runs`` runs each.

    Raises
    ------
    ValueError
        ``runs`` is below 1.
    subprocess.CalledProcessError
        A dry run failed (a broken configuration, say).
    """
    if runs < 1:
        raise ValueError(f"runs: must be at least 1, got {runs}")
    timings = [Timing("dry_run", _timed(Path(root), runs))]
    with tempfile.TemporaryDirectory() as folder:
        (Path(folder) / "Snakefile").write_text(_ONE_RULE, encoding="utf-8")
        (Path(folder) / "a.txt").touch()
        timings.append(Timing("one_rule", _timed(Path(folder), runs)))
    return timings


def write_timings(timings: Sequence[Timing], path: str | Path) -> Path:
    """The timings as a CSV (``name``, ``runs``, ``median_s``, ``min_s``, ``max_s``), written whole."""
    with atomic_output(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(["name", "runs", "median_s", "min_s", "max_s"])
        for timing in timings:
            row = [timing.median_s, min(timing.seconds), max(timing.seconds)]
            writer.writerow([timing.name, len(timing.seconds), *(f"{value:.4f}" for value in row)])
    return Path(path)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m rodimpact.tools.bench_planning", description=__doc__.split("\n")[0]
    )
    parser.add_argument("--root", type=Path, default=Path("."), help="the workflow's directory (default: .)")
    parser.add_argument("--runs", type=int, default=7, help="counted runs of each kind (default: 7)")
    parser.add_argument("--csv", type=Path, default=Path("results/benchmarks/planning.csv"))
    args = parser.parse_args(argv)
    timings = time_dry_runs(args.root, args.runs)
    write_timings(timings, args.csv)
    for timing in timings:
        print(f"{timing.name}: median {timing.median_s:.2f} s of {len(timing.seconds)} runs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
