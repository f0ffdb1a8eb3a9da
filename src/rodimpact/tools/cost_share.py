"""How much of its cost model a solve takes: measured solver time over modelled time, per method.

Each method's cost model (the registry's ``cost``) is upper-side: it covers every stored run,
so that a job's request is never short. A study cut into jobs of a target cost
(:mod:`rodimpact.jobs.parts`) needs the typical time instead: the model's time times its
method's ``TYPICAL_SHARE`` (in the method's ``cost.py``, carried by
:class:`rodimpact.solvers.cost.Cost`). This tool measures that share on the stored runs: for
every HDF5 run under ``results/`` (a run file, or each run of a file of runs), its solver time
(``wall_time_s``, the median of a timed run's repeats) over the modelled time of its own
config; per method the runs, the median, the 10th and 90th percentiles and the largest.

``python -m rodimpact.tools.cost_share [--root .] [--csv results/benchmarks/cost_share.csv]``
"""

from __future__ import annotations

import argparse
import csv
import logging
import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rodimpact.solvers.registry import METHODS
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.runs import StoreError, read_summary, run_references

__all__ = ["COLUMNS", "Share", "cost_shares", "main", "measured_shares", "write_shares"]

log = logging.getLogger(__name__)

#: Columns of ``cost_share.csv``, in order (shares: measured over modelled time).
COLUMNS = ("method", "runs", "median", "p10", "p90", "max", "typical_share")
#: The folders of stored solver runs (the benchmarks time their own runs).
RUN_FOLDERS = ("runs", "convergence", "stress", "stability_map", "sweeps")


@dataclass(frozen=True)
class Share:
    """Measured over modelled solve time of one method's stored runs.

    Attributes
    ----------
    method : str
        The method.
    runs : int
        Runs measured.
    median, p10, p90, max : float
        The share's median, 10th and 90th percentiles and largest value (-).
    typical_share : float
        The share the method's cost model declares (``Cost.typical_share``).
    """

    method: str
    runs: int
    median: float
    p10: float
    p90: float
    max: float
    typical_share: float

    def row(self) -> dict[str, object]:
        return {name: getattr(self, name) for name in COLUMNS}


def measured_shares(references: Iterable[str]) -> dict[str, list[tuple[float, float]]]:
    """Method -> (measured share, declared share) of every successful run of ``references``
    (run files, or ``file.h5#run`` of a file of runs); unreadable files are skipped and logged."""
    shares: dict[str, list[tuple[float, float]]] = {}
    for reference in references:
        try:
            record = read_summary(reference, verify=False)
        except (StoreError, OSError, ValueError) as error:
            log.warning("skipped %s: %s", reference, error)
            continue
        if record.method not in METHODS or not record.summary.get("success", True):
            continue
        case = record.config
        cost = METHODS[record.method].estimate(case, case["numerics"][record.method])
        shares.setdefault(record.method, []).append((record.wall_time_s / cost.solve_s, cost.typical_share))
    return shares


def cost_shares(root: str | Path = ".") -> list[Share]:
    """:class:`Share` of every method with stored runs under ``root/results`` (:data:`RUN_FOLDERS`)."""
    files = sorted(p for folder in RUN_FOLDERS for p in Path(root, "results", folder).rglob("*.h5"))
    references = [reference for path in files for reference in run_references(path)]
    rows = []
    for method, pairs in sorted(measured_shares(references).items()):
        values = np.array([share for share, _ in pairs])
        rows.append(
            Share(
                method,
                len(values),
                float(np.median(values)),
                float(np.percentile(values, 10)),
                float(np.percentile(values, 90)),
                float(values.max()),
                pairs[0][1],
            )
        )
    return rows


def write_shares(rows: Sequence[Share], path: str | Path) -> Path:
    """Write the table as CSV, atomically (shares to 4 significant digits)."""
    with atomic_output(path) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as handle:
            writer = csv.DictWriter(handle, fieldnames=COLUMNS)
            writer.writeheader()
            for row in rows:
                writer.writerow({k: f"{v:.4g}" if isinstance(v, float) else v for k, v in row.row().items()})
    return Path(path)


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m rodimpact.tools.cost_share``: measured over modelled solve time, per method."""
    parser = argparse.ArgumentParser(prog="python -m rodimpact.tools.cost_share", description=main.__doc__)
    parser.add_argument("--root", default=".", help="the workflow's directory (default: .)")
    parser.add_argument("--csv", default="results/benchmarks/cost_share.csv", help="the table to write")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s", stream=sys.stdout)
    rows = cost_shares(args.root)
    if not rows:
        log.error("no stored runs under %s/results: run `make paper` first", args.root)
        return 1
    path = write_shares(rows, Path(args.root, args.csv))
    for row in rows:
        log.info(
            "%-10s %5d runs: median %.3g, p10 %.3g, p90 %.3g, max %.3g (declared %.3g)",
            row.method, row.runs, row.median, row.p10, row.p90, row.max, row.typical_share,
        )  # fmt: skip
    log.info("wrote %s", path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
