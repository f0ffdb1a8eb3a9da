"""The build's own timing, from snakemake's job records: where a build's time goes.

snakemake keeps a record per output file under ``.snakemake/metadata/`` (the file name is the
output's path, URL-safe base64, split into 255-byte parts): the ``rule`` that made it, the
job's ``starttime`` (when snakemake marked the outputs incomplete, before the job started)
and ``endtime`` (the output's modification time, set when snakemake accepted the output).
The records of one job share its rule, its ``job_hash`` and its end. :func:`build_stats`
groups them into jobs, and for each rule sums

* ``job_s``: the jobs' times, end minus start: everything a job costs (snakemake's work on
  it, the Python process, the imports, the solves, the writing);
* ``solver_s``: the solver times stored in the job's HDF5 runs (its outputs, the files in its
  output directory for a batch, each run of a file of runs; ``wall_time_s``; a timed run stores
  the median of its repeats, counted ``wall_time_repeats`` times);
* ``overhead_s = job_s - solver_s``, its median per job and its share per run file.

``wall_s`` is the span from the first start to the last end: of a rule's jobs, and, in the
``total`` row, of the whole build. The records describe the jobs that made the files that
exist now: after ``make paper`` from an empty ``results/``, one build.

``python -m rodimpact.tools.build_stats [--root .] [--csv results/benchmarks/build.csv]``
writes the table (``make bench`` runs it).
"""

from __future__ import annotations

import argparse
import base64
import binascii
import csv
import json
import logging
import statistics
import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from rodimpact.storage.atomic import atomic_output

__all__ = ["COLUMNS", "Job", "RuleStats", "build_stats", "main", "read_jobs", "write_build_stats"]

log = logging.getLogger(__name__)

#: Columns of ``build.csv``, in order (times in seconds).
COLUMNS = (
    "rule",
    "jobs",
    "runs",
    "solver_s",
    "job_s",
    "overhead_s",
    "median_job_s",
    "median_overhead_s",
    "overhead_per_run_s",
    "wall_s",
)
#: Outputs a build's table leaves out: the benchmarks (``make bench`` times its own runs).
EXCLUDED = ("results/benchmarks/",)
#: Records of one job end within this many seconds of each other (snakemake touches its outputs
#: one after another).
_SAME_END_S = 1.0


@dataclass(frozen=True)
class Job:
    """One job of a build.

    Attributes
    ----------
    rule : str
        The rule that ran it.
    start, end : float
        Seconds since the epoch (its outputs' earliest start and latest end).
    outputs : tuple of str
        Its output files (paths relative to the working directory).
    solver_s : float
        Solver time stored in its HDF5 runs, s (0 when it wrote none).
    runs : int
        Its HDF5 runs (files that store a solver time).
    """

    rule: str
    start: float
    end: float
    outputs: tuple[str, ...]
    solver_s: float = 0.0
    runs: int = 0

    @property
    def seconds(self) -> float:
        return self.end - self.start


@dataclass(frozen=True)
class RuleStats:
    """One row of the table (see :data:`COLUMNS`)."""

    rule: str
    jobs: int
    runs: int
    solver_s: float
    job_s: float
    overhead_s: float
    median_job_s: float
    median_overhead_s: float
    overhead_per_run_s: float | None
    wall_s: float

    def row(self) -> dict[str, object]:
        return {name: getattr(self, name) for name in COLUMNS}


def _output_of(record_path: Path, metadata: Path) -> str | None:
    """The output path a record file stands for (None for a name that is not one)."""
    parts = record_path.relative_to(metadata).parts
    encoded = "".join(part[1:] if part.startswith("@") else part for part in parts)
    try:
        return base64.urlsafe_b64decode(encoded).decode()
    except (binascii.Error, UnicodeDecodeError, ValueError):
        return None


def _solver_seconds(path: Path) -> list[float]:
    """Solver time of each run a file holds, s: ``wall_time_s`` times ``summary/wall_time_repeats``
    (1 when absent), of the file's root, or of each run's group in a file of runs; none for a file
    that stores none (not an HDF5 run)."""
    import h5py  # only the HDF5 outputs need it

    def seconds(group: h5py.Group) -> float:
        repeats = group["summary"].attrs.get("wall_time_repeats", 1) if "summary" in group else 1
        return float(group.attrs["wall_time_s"]) * float(repeats)

    try:
        with h5py.File(path, "r") as h5:
            if "wall_time_s" in h5.attrs:
                return [seconds(h5)]
            return [seconds(g) for g in h5.values() if isinstance(g, h5py.Group) and "wall_time_s" in g.attrs]
    except (OSError, KeyError, TypeError, ValueError):
        return []


def read_jobs(root: str | Path = ".", exclude: Sequence[str] = EXCLUDED) -> list[Job]:
    """The jobs that made the outputs that exist under ``root``, from ``root/.snakemake/metadata``.

    Parameters
    ----------
    root : path
        The workflow's working directory.
    exclude : sequence of str
        Leave out the outputs whose path starts with one of these.

    Returns
    -------
    list of Job
        Sorted by start; empty when there are no records.
    """
    root = Path(root)
    metadata = root / ".snakemake" / "metadata"
    records: dict[tuple[str, object], list[tuple[float, float, str]]] = {}
    for path in sorted(p for p in metadata.rglob("*") if p.is_file()) if metadata.is_dir() else []:
        output = _output_of(path, metadata)
        if output is None or output.startswith(tuple(exclude)) or not (root / output).exists():
            continue
        try:
            record = json.loads(path.read_text(encoding="utf-8"))
            start, end, rule = float(record["starttime"]), float(record["endtime"]), str(record["rule"])
        except (OSError, ValueError, KeyError, TypeError):
            log.debug("skipping record %s (no times)", path)
            continue
        records.setdefault((rule, record.get("job_hash")), []).append((end, start, output))
    jobs = []
    for (rule, _), entries in records.items():
        entries.sort()
        group: list[tuple[float, float, str]] = []
        for entry in entries:  # one job hash may stand for several builds' jobs: split by end
            if group and entry[0] - group[-1][0] > _SAME_END_S:
                jobs.append(_job(rule, group, root))
                group = []
            group.append(entry)
        jobs.append(_job(rule, group, root))
    return sorted(jobs, key=lambda job: (job.start, job.rule))


def _run_files(root: Path, output: str) -> list[Path]:
    """The HDF5 files an output holds: itself, or those in it when it is a directory (a batch's runs)."""
    path = root / output
    return sorted(path.glob("*.h5")) if path.is_dir() else [path] if output.endswith(".h5") else []


def _job(rule: str, entries: list[tuple[float, float, str]], root: Path) -> Job:
    outputs = tuple(sorted(output for _, _, output in entries))
    solver = [s for o in outputs for f in _run_files(root, o) for s in _solver_seconds(f)]
    return Job(
        rule=rule,
        start=min(start for _, start, _ in entries),
        end=max(end for end, _, _ in entries),
        outputs=outputs,
        solver_s=sum(solver),
        runs=len(solver),
    )


def _stats(rule: str, jobs: Sequence[Job]) -> RuleStats:
    job_s = sum(job.seconds for job in jobs)
    solver_s = sum(job.solver_s for job in jobs)
    runs = sum(job.runs for job in jobs)
    return RuleStats(
        rule=rule,
        jobs=len(jobs),
        runs=runs,
        solver_s=solver_s,
        job_s=job_s,
        overhead_s=job_s - solver_s,
        median_job_s=statistics.median(job.seconds for job in jobs),
        median_overhead_s=statistics.median(job.seconds - job.solver_s for job in jobs),
        overhead_per_run_s=(job_s - solver_s) / runs if runs else None,
        wall_s=max(job.end for job in jobs) - min(job.start for job in jobs),
    )


def build_stats(jobs: Iterable[Job]) -> list[RuleStats]:
    """A row per rule (sorted by name) and a last row ``total``: every job of the build, whose
    ``wall_s`` is the build's wall time (first start to last end). Empty for no jobs."""
    jobs = list(jobs)
    if not jobs:
        return []
    rules: dict[str, list[Job]] = {}
    for job in jobs:
        rules.setdefault(job.rule, []).append(job)
    return [*(_stats(rule, rules[rule]) for rule in sorted(rules)), _stats("total", jobs)]


def write_build_stats(rows: Sequence[RuleStats], path: str | Path) -> Path:
    """Write the table as CSV (atomically; seconds with 4 decimals); returns the path."""

    def cell(value: object) -> object:
        return "" if value is None else round(value, 4) if isinstance(value, float) else value

    with atomic_output(path) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as handle:
            writer = csv.DictWriter(handle, fieldnames=COLUMNS)
            writer.writeheader()
            writer.writerows({key: cell(value) for key, value in row.row().items()} for row in rows)
    return Path(path)


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m rodimpact.tools.build_stats``: write the build's timing table."""
    parser = argparse.ArgumentParser(prog="python -m rodimpact.tools.build_stats", description=main.__doc__)
    parser.add_argument("--root", default=".", help="the workflow's directory (default: .)")
    parser.add_argument("--csv", default="results/benchmarks/build.csv", help="the table to write")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s", stream=sys.stdout)
    rows = build_stats(read_jobs(args.root))
    if not rows:
        log.error("no job records under %s/.snakemake/metadata: run `make paper` first", args.root)
        return 1
    path = write_build_stats(rows, Path(args.root, args.csv))
    total = rows[-1]
    log.info(
        "%s: %d jobs, %d runs in %.1f s (wall); jobs %.1f s = solvers %.1f s + overhead %.1f s (median per job %.2f s)",
        path,
        total.jobs,
        total.runs,
        total.wall_s,
        total.job_s,
        total.solver_s,
        total.overhead_s,
        total.median_overhead_s,
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
