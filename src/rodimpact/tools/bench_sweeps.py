"""How a large sweep spreads: its jobs, its files and its wall time on one core and on two
(``make bench``, not tests).

For each size, a copy of the workflow and configuration whose only built set is one ``sem``
sweep of that many points (:func:`rodimpact.tools.bench_planning.sweep_plan_project`) is
planned (``snakemake -n``: the jobs, the sweep's parts among them, and the planning time), then
built from nothing with ``-j1`` and again from nothing with ``-j2`` (its sweep table the target;
the two builds one after the other, paired), and once more as one part (``batch.target_s`` set
above the sweep's cost: the sweep unsplit). A row records the points, the jobs and the parts, the
files under ``results/sweeps/``, the planning time, the two wall times and their ratio, and
whether the ``-j1``, ``-j2`` and unsplit builds' tables are identical byte for byte.

With ``--point-split n`` it also times where a point's time goes in its job: ``n`` points of the
sweep solved (:func:`rodimpact.jobs.runner.solve_run`) and stored
(:meth:`rodimpact.storage.runs.RunsWriter.add`, in one file of runs), each timed apart; the row
of ``sweep_point.csv`` gives the milliseconds a point of each.

``python -m rodimpact.tools.bench_sweeps [--root .] [--points 100 1000 10000]
[--csv results/benchmarks/sweep_scaling.csv] [--point-split 1000] [--keep DIR]`` (``--keep``: each
size's project and its builds are left in ``DIR/points{n}``).
"""

from __future__ import annotations

import argparse
import csv
import filecmp
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass, fields
from pathlib import Path

import yaml

from rodimpact.storage.atomic import atomic_output
from rodimpact.tools.bench_planning import SWEEP_SET, sweep_plan_project

__all__ = ["PointSplit", "SweepScaling", "main", "measure_sweep", "split_point_time", "write_scaling", "write_split"]

#: The table each build makes (the sweep's whole output).
TABLE = f"results/tables/sweep_{SWEEP_SET}.csv"


@dataclass(frozen=True)
class SweepScaling:
    """One sweep size, planned and built twice (times in s)."""

    points: int
    jobs: int
    parts: int
    files: int
    plan_s: float
    wall_j1_s: float
    wall_j2_s: float
    tables_identical: bool
    one_part_identical: bool

    @property
    def ratio(self) -> float:
        """Wall time with ``-j2`` over ``-j1``."""
        return self.wall_j2_s / self.wall_j1_s


def _snakemake() -> str:
    """The snakemake of the environment this runs in (beside its Python)."""
    return str(Path(sys.executable).parent / "snakemake")


def _counts(summary: str) -> tuple[int, int]:
    """(all jobs, solve_sweep jobs) of a ``snakemake -n --quiet rules`` summary."""
    total = re.search(r"^total\s+(\d+)", summary, re.M)
    parts = re.search(r"^solve_sweep\s+(\d+)", summary, re.M)
    if total is None or parts is None:
        raise RuntimeError(f"no job counts in the dry run's summary:\n{summary[-2000:]}")
    return int(total.group(1)), int(parts.group(1))


def _build(project: Path, cores: int, name: str) -> float:
    """Build the sweep's table from nothing with ``-j{cores}`` (its log ``build_{name}.log``);
    its wall time, s."""
    for folder in ("results", "logs", ".snakemake"):
        shutil.rmtree(project / folder, ignore_errors=True)
    command = [_snakemake(), f"-j{cores}", TABLE]
    with open(project / f"build_{name}.log", "w", encoding="utf-8") as log:
        started = time.perf_counter()
        subprocess.run(command, cwd=project, stdout=log, stderr=subprocess.STDOUT, check=True)
        return time.perf_counter() - started


def _one_part(project: Path) -> None:
    """Set the project's ``batch.target_s`` above any sweep's cost: every sweep one part."""
    path = project / "config" / "config.yaml"
    config = yaml.safe_load(path.read_text(encoding="utf-8"))
    config["batch"] = {"target_s": 1.0e9}
    path.write_text(yaml.safe_dump(config, sort_keys=False), encoding="utf-8")


def measure_sweep(root: str | Path, points: int, folder: str | Path) -> SweepScaling:
    """Plan and build, with ``-j1`` and then ``-j2``, a ``sem`` sweep of ``points`` points in
    ``folder`` (the module's docstring); the ``-j2`` build is left there.

    Raises
    ------
    subprocess.CalledProcessError
        A dry run or a build failed (its log is in ``folder``).
    """
    project = sweep_plan_project(root, points, folder)
    started = time.perf_counter()
    plan = subprocess.run(
        [_snakemake(), TABLE, "-n", "--quiet", "rules"], cwd=project, capture_output=True, text=True, check=True
    )
    plan_s = time.perf_counter() - started
    jobs, parts = _counts(plan.stdout + plan.stderr)
    wall_j1 = _build(project, 1, "j1")
    shutil.copy2(project / TABLE, project / "table_j1.csv")
    wall_j2 = _build(project, 2, "j2")
    files = sum(1 for p in (project / "results" / "sweeps").rglob("*") if p.is_file())
    identical = filecmp.cmp(project / "table_j1.csv", project / TABLE, shallow=False)
    shutil.copy2(project / TABLE, project / "table_j2.csv")
    _one_part(project)
    _build(project, 2, "one_part")
    unsplit = filecmp.cmp(project / "table_j2.csv", project / TABLE, shallow=False)
    return SweepScaling(points, jobs, parts, files, plan_s, wall_j1, wall_j2, identical, unsplit)


@dataclass(frozen=True)
class PointSplit:
    """Where a sweep point's time goes in its job, ms a point (means over ``points``)."""

    points: int
    solve_ms: float
    store_ms: float
    total_ms: float

    @property
    def other_ms(self) -> float:
        """Neither solving nor storing: the batch's own bookkeeping."""
        return self.total_ms - self.solve_ms - self.store_ms


def split_point_time(root: str | Path, points: int, folder: str | Path) -> PointSplit:
    """Solve and store ``points`` points of the planning sweep (of ``points`` points) in one file
    of runs, as a part's job does, timing the solves and the stores apart.

    Raises
    ------
    ValueError
        As :func:`rodimpact.tools.bench_planning.sweep_plan_project`.
    """
    from rodimpact.analysis.sweeps import sweep_point_case, sweep_points
    from rodimpact.config.load import load_project
    from rodimpact.jobs.runner import solve_run
    from rodimpact.storage.provenance import code_version
    from rodimpact.storage.runs import write_runs

    project = sweep_plan_project(root, points, folder)
    config = yaml.safe_load((project / "config" / "config.yaml").read_text(encoding="utf-8"))
    (sweep,) = load_project(config, root=project).sweeps_in(SWEEP_SET)
    version = code_version()
    solve = store = 0.0
    started = time.perf_counter()
    with write_runs(project / "part.h5") as writer:
        for index, point in enumerate(sweep_points(sweep["sweep"])):
            name = f"p{index}"
            case = sweep_point_case(sweep, point, name)
            study = {"name": "sweep", "sweep": sweep["id"], "point": name}
            before = time.perf_counter()
            solved = solve_run(case, "sem", study=study, code_version=version)
            between = time.perf_counter()
            writer.add(name, **solved.arguments())
            solve, store = solve + between - before, store + time.perf_counter() - between
    total = time.perf_counter() - started
    return PointSplit(points, 1e3 * solve / points, 1e3 * store / points, 1e3 * total / points)


def write_scaling(rows: Sequence[SweepScaling], path: str | Path) -> Path:
    """The rows as a CSV (the fields, then ``ratio``), written whole."""
    names = [f.name for f in fields(SweepScaling)]
    with atomic_output(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow([*names, "ratio"])
        for row in rows:
            values = [getattr(row, name) for name in names]
            writer.writerow([f"{v:.2f}" if isinstance(v, float) else v for v in values] + [f"{row.ratio:.3f}"])
    return Path(path)


def write_split(split: PointSplit, path: str | Path) -> Path:
    """The point's split as a one-row CSV (ms a point), written whole."""
    with atomic_output(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(["points", "solve_ms", "store_ms", "other_ms", "total_ms"])
        values = (split.solve_ms, split.store_ms, split.other_ms, split.total_ms)
        writer.writerow([split.points, *(f"{v:.2f}" for v in values)])
    return Path(path)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m rodimpact.tools.bench_sweeps", description=__doc__.split("\n")[0])
    parser.add_argument("--root", type=Path, default=Path("."), help="the workflow's directory (default: .)")
    parser.add_argument("--points", type=int, nargs="*", default=[100, 1000, 10000], help="the sweeps' sizes")
    parser.add_argument("--csv", type=Path, default=Path("results/benchmarks/sweep_scaling.csv"))
    parser.add_argument("--keep", type=Path, default=None, help="leave each size's project and build here")
    parser.add_argument("--point-split", type=int, default=0, help="also time where a point's time goes, on n points")
    args = parser.parse_args(argv)
    if args.point_split:
        with tempfile.TemporaryDirectory() as scratch:
            split = split_point_time(args.root, args.point_split, Path(scratch) / "split")
        write_split(split, args.csv.with_name("sweep_point.csv"))
        print(
            f"a point of {split.points}: {split.total_ms:.1f} ms, of which solve {split.solve_ms:.1f} ms, "
            f"store {split.store_ms:.1f} ms, other {split.other_ms:.1f} ms"
        )
    rows = []
    for points in args.points:
        with tempfile.TemporaryDirectory() as scratch:
            folder = Path(scratch) / f"points{points}" if args.keep is None else args.keep / f"points{points}"
            if folder.exists():
                shutil.rmtree(folder)
            row = measure_sweep(args.root, points, folder)
        rows.append(row)
        print(
            f"{points} points: {row.jobs} jobs ({row.parts} parts), {row.files} files under results/sweeps, "
            f"planned in {row.plan_s:.1f} s; -j1 {row.wall_j1_s:.1f} s, -j2 {row.wall_j2_s:.1f} s "
            f"(ratio {row.ratio:.2f}); tables {'identical' if row.tables_identical else 'DIFFER'}, "
            f"unsplit {'identical' if row.one_part_identical else 'DIFFERS'}"
        )
    if rows:
        write_scaling(rows, args.csv)
    return 0 if all(row.tables_identical and row.one_part_identical for row in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
