"""The cluster check's benchmark: ``.test/`` built through SLURM against a local build, by wall
time, written to ``results/benchmarks/cluster.csv``.

Rows (one per build, the file rewritten whole by every ``make test-cluster``):

* ``local``: ``snakemake -j2 --directory .test`` on this machine. Timed by the check when it
  builds the reference itself; when it reuses the checkout's ``.test/`` (built by ``make test``
  just before, alone on the machine), the span of that build's job records
  (:func:`rodimpact.tools.build_stats.build_stats`: first job's start to last job's end, which
  leaves out snakemake's planning, a few seconds, so the ratio is if anything overstated);
* ``slurm``: ``snakemake --workflow-profile profiles/slurm --directory .test`` through the
  one-node scheduler, timed by the check (planning included), with the number of ``sbatch``
  submissions, and its ratio to the local row.

The target (docs/cluster.md): a ratio of at most 1.5 (:data:`TARGET_RATIO`).
"""

from __future__ import annotations

import csv
import datetime
import subprocess
from dataclasses import asdict, dataclass
from pathlib import Path

from rodimpact.storage.atomic import atomic_output
from rodimpact.tools.build_stats import build_stats, read_jobs

#: Where the benchmark is written, under the checkout.
CLUSTER_CSV = Path("results") / "benchmarks" / "cluster.csv"
#: The target: the SLURM build's wall time over the local build's.
TARGET_RATIO = 1.5


@dataclass(frozen=True)
class BuildTiming:
    """One build of ``.test/``: how, how many jobs and submissions, and its wall time (s)."""

    build: str
    jobs: int
    submissions: int | None
    wall_s: float
    measured: str


def job_count(workdir: Path) -> int:
    """The jobs that made ``workdir``'s outputs, from its job records (every row counts jobs so,
    a local build and a SLURM build alike; the target rule ``all`` makes no output)."""
    return len(read_jobs(workdir))


def recorded_build(workdir: Path) -> BuildTiming | None:
    """The build that made ``workdir``'s outputs, from its job records (None without records)."""
    rows = build_stats(read_jobs(workdir))
    if not rows:
        return None
    total = rows[-1]
    return BuildTiming(
        build="local",
        jobs=job_count(workdir),
        submissions=None,
        wall_s=total.wall_s,
        measured="job records of the checkout's build (first start to last end)",
    )


def write_cluster_csv(path: Path, local: BuildTiming | None, slurm: BuildTiming, root: Path) -> Path:
    """Write the local and SLURM rows (the SLURM row with its ratio to the local one)."""
    commit = subprocess.run(
        ["git", "-C", str(root), "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=False
    ).stdout.strip()
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%dT%H:%M:%SZ")
    columns = ["build", "jobs", "submissions", "wall_s", "ratio_to_local", "target_ratio", "measured", "commit", "date"]
    rows = []
    for timing in (local, slurm):
        if timing is None:
            continue
        row = {**asdict(timing), "wall_s": round(timing.wall_s, 1), "commit": commit, "date": when}
        if timing is slurm and local is not None:
            row.update(ratio_to_local=round(slurm.wall_s / local.wall_s, 2), target_ratio=TARGET_RATIO)
        rows.append({column: "" if row.get(column) is None else row.get(column, "") for column in columns})
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_output(path) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as handle:
            writer = csv.DictWriter(handle, fieldnames=columns)
            writer.writeheader()
            writer.writerows(rows)
    return path
