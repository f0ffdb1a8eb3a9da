"""How long snakemake takes to plan the workflow: the dry run against a one-rule workflow
(``make bench``, not tests).

Each figure is the wall time of a whole ``snakemake -n --quiet rules`` process (the
environment's own snakemake, in ``root``), over ``runs`` runs after one run not counted:

* ``dry_run``: the workflow in ``root``, which checks the whole configuration and every job's
  resources at each start;
* ``one_rule``: a workflow of one rule that touches a file, in a temporary directory: what
  snakemake itself takes to start and plan, whatever the workflow.

* ``sweep_plan_{n}`` (with ``--sweep-points n ...``): the dry run of one ``sem`` sweep of n
  points alone (its table the target), in a copy of the workflow and configuration whose only
  built set is that sweep: the configuration check of every point, its cost estimate and the
  job graph; one run each, with the process's peak memory.

``python -m rodimpact.tools.bench_planning [--root .] [--runs 7] [--sweep-points 100 10000 100000]
[--csv results/benchmarks/planning.csv]`` writes one row per figure: ``runs``, ``median_s``,
``min_s``, ``max_s``, ``max_rss_mib`` (the sweeps' only).
"""

from __future__ import annotations

import argparse
import csv
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import yaml

from rodimpact.storage.atomic import atomic_output

__all__ = ["SWEEP_SET", "Timing", "main", "sweep_plan_project", "time_dry_runs", "time_sweep_plans", "write_timings"]

_ONE_RULE = 'rule all:\n    output:\n        "a.txt",\n    shell:\n        "touch {output}"\n'


@dataclass(frozen=True)
class Timing:
    """Wall times of one kind of dry run, s."""

    name: str
    seconds: tuple[float, ...]
    max_rss_mib: float | None = None

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


#: The case set of the planned sweep, and its case (one steel ball on the Model's rod, its mass swept).
SWEEP_SET = "planning_sweep"
_SWEEP_CASE = {
    "id": "planning_sweep",
    "description": "A steel ball on the Model's rod, its mass swept: how long a large sweep takes to plan",
    "impactor": {"mass_kg": 1.0e-3, "radius_m": 3.0e-3, "velocity_m_s": 0.5, "material": "steel"},
    "rod": {"length_m": 0.5, "area_m2": 5.0e-5, "material": "steel", "far_end": "fixed"},
    "methods": ["sem"],
}


def sweep_plan_project(root: str | Path, points: int, folder: str | Path) -> Path:
    """A copy of the workflow and configuration of ``root`` in ``folder`` whose only built set is
    one ``sem`` sweep of ``points`` points: masses from 1 g to 100 g (log-spaced), and above 1000
    points ``points / 100`` masses times 100 velocities from 0.1 to 2 m/s; returns ``folder``.

    Raises
    ------
    ValueError
        ``points`` above 1000 and not a multiple of 100.
    """
    root, folder = Path(root), Path(folder)
    for name in ("workflow", "config", "profiles"):
        shutil.copytree(root / name, folder / name)
    shutil.copy2(root / "Snakefile", folder / "Snakefile")
    (folder / "src").symlink_to((root / "src").resolve())  # the rules' code digests read it
    # a parameter takes at most 1000 values: beyond, the masses times 100 velocities
    if points > 1000 and points % 100:
        raise ValueError(f"points: above 1000, a multiple of 100 (masses x 100 velocities), got {points}")
    masses = points if points <= 1000 else points // 100
    parameters = {"mass_kg": {"start": 1.0e-3, "stop": 1.0e-1, "num": masses, "spacing": "log"}}
    if points > 1000:
        parameters["velocity_m_s"] = {"start": 0.1, "stop": 2.0, "num": 100, "spacing": "log"}
    sweep = {"description": "mass (and velocity)", "methods": ["sem"], "parameters": parameters}
    case_file = {"set": SWEEP_SET, "description": "A large sweep to plan.", "cases": [{**_SWEEP_CASE, "sweep": sweep}]}
    (folder / "config" / "cases" / f"{SWEEP_SET}.yaml").write_text(yaml.safe_dump(case_file, sort_keys=False))
    config_file = folder / "config" / "config.yaml"
    config = yaml.safe_load(config_file.read_text())
    config["targets"]["sets"] = [SWEEP_SET]
    config_file.write_text(yaml.safe_dump(config, sort_keys=False))
    return folder


def time_sweep_plans(root: str | Path, sizes: Sequence[int]) -> list[Timing]:
    """One timed dry run (with its peak memory) of a sweep of each of ``sizes`` points alone
    (:func:`sweep_plan_project`).

    Raises
    ------
    subprocess.CalledProcessError
        A dry run failed.
    """
    timings = []
    for points in sizes:
        with tempfile.TemporaryDirectory() as folder:
            project = sweep_plan_project(root, points, folder)
            command = [_snakemake(), f"results/tables/sweep_{SWEEP_SET}.csv", "-n", "--quiet", "rules"]
            with open(project / "plan.log", "w", encoding="utf-8") as log:
                started = time.perf_counter()
                process = subprocess.Popen(command, cwd=project, stdout=log, stderr=subprocess.STDOUT)
                _, status, usage = os.wait4(process.pid, 0)
                seconds = time.perf_counter() - started
            process.returncode = os.waitstatus_to_exitcode(status)
            if process.returncode:
                raise subprocess.CalledProcessError(process.returncode, command, (project / "plan.log").read_text())
            # ru_maxrss is in KiB on Linux
            timings.append(Timing(f"sweep_plan_{points}", (seconds,), usage.ru_maxrss / 1024.0))
    return timings


def write_timings(timings: Sequence[Timing], path: str | Path) -> Path:
    """The timings as a CSV (``name``, ``runs``, ``median_s``, ``min_s``, ``max_s``), written whole."""
    with atomic_output(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(["name", "runs", "median_s", "min_s", "max_s", "max_rss_mib"])
        for timing in timings:
            row = [timing.median_s, min(timing.seconds), max(timing.seconds)]
            memory = "" if timing.max_rss_mib is None else f"{timing.max_rss_mib:.1f}"
            writer.writerow([timing.name, len(timing.seconds), *(f"{value:.4f}" for value in row), memory])
    return Path(path)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m rodimpact.tools.bench_planning", description=__doc__.split("\n")[0]
    )
    parser.add_argument("--root", type=Path, default=Path("."), help="the workflow's directory (default: .)")
    parser.add_argument("--runs", type=int, default=7, help="counted runs of each kind (default: 7)")
    parser.add_argument("--csv", type=Path, default=Path("results/benchmarks/planning.csv"))
    parser.add_argument(
        "--sweep-points", type=int, nargs="*", default=[], help="also plan a sem sweep of each of these sizes alone"
    )
    args = parser.parse_args(argv)
    timings = time_dry_runs(args.root, args.runs) + time_sweep_plans(args.root, args.sweep_points)
    write_timings(timings, args.csv)
    for timing in timings:
        memory = "" if timing.max_rss_mib is None else f", {timing.max_rss_mib:.0f} MiB at most"
        print(f"{timing.name}: median {timing.median_s:.2f} s of {len(timing.seconds)} runs{memory}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
