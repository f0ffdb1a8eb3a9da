"""What an accuracy costs each method, from the error-against-run-time table of a build.

For each method and case of ``results/tables/work_precision.csv`` (:mod:`rodimpact.analysis.work_precision`)
and each tolerance, the cheapest level whose errors of the contact time and of the first maximum
(``err_contact_time``, ``err_max_1``: relative to the case's reference) are both at most the
tolerance, priced at the best of its timed repeats (``wall_time_min_s``); and the finest level's
best time. An error is only known to within the reference's own uncertainty
(``ref_err_contact_time``, ``ref_err_max_1``), so a level reaches a tolerance only if that
uncertainty is within it too: ``fem_axi``, whose reference is its own finest level, reaches
none below its uncertainty. ``docs/studies.md`` ("Cost") quotes the table.

``python -m rodimpact.tools.accuracy_cost [results/tables/work_precision.csv] [--tolerance 1e-4 1e-6]``
prints the table (times in s, three digits; NaN: no level reaches the tolerance).
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

__all__ = ["accuracy_cost", "main"]

#: The errors an accuracy is asked of, and the reference's uncertainty of each.
ERRORS = ("err_contact_time", "err_max_1", "ref_err_contact_time", "ref_err_max_1")


def accuracy_cost(frame: pd.DataFrame, tolerances: Sequence[float]) -> pd.DataFrame:
    """One row per method and case (in the table's order): for each tolerance ``t``, the column
    ``cost_{t:g}_s`` (s; NaN where no level reaches ``t``), then ``finest`` (the finest level's
    resolution) and ``finest_s`` (its best time, s).

    Parameters
    ----------
    frame : DataFrame
        The work-precision table: ``method``, ``case_id``, ``level``, ``resolution``,
        ``wall_time_min_s`` and the columns of :data:`ERRORS`.
    tolerances : sequence of float
        Relative errors, each > 0.

    Raises
    ------
    ValueError
        A tolerance is not a positive number, or a column is missing.
    """
    bad = [t for t in tolerances if not (isinstance(t, (int, float)) and math.isfinite(t) and t > 0)]
    if bad:
        raise ValueError(f"tolerances: must be positive numbers, got {bad[0]!r}")
    needed = ["method", "case_id", "level", "resolution", "wall_time_min_s", *ERRORS]
    missing = [name for name in needed if name not in frame.columns]
    if missing:
        raise ValueError(f"frame: no column {missing[0]!r}")
    error = frame[list(ERRORS)].max(axis=1)
    rows = []
    for (method, case), group in frame.groupby(["method", "case_id"], sort=False):
        row: dict[str, object] = {"method": method, "case_id": case}
        for tolerance in tolerances:
            met = group.loc[error[group.index] <= tolerance, "wall_time_min_s"]
            row[f"cost_{tolerance:g}_s"] = float(met.min()) if len(met) else math.nan
        finest = group.loc[group["level"].idxmax()]
        row["finest"], row["finest_s"] = finest["resolution"], float(finest["wall_time_min_s"])
        rows.append(row)
    return pd.DataFrame(rows)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m rodimpact.tools.accuracy_cost", description=__doc__.split("\n")[0])
    parser.add_argument("table", nargs="?", type=Path, default=Path("results/tables/work_precision.csv"))
    parser.add_argument("--tolerance", type=float, nargs="+", default=[1e-4, 1e-6])
    args = parser.parse_args(argv)
    if not args.table.is_file():
        print(f"{args.table}: no such file (make paper, or make convergence, writes it)", file=sys.stderr)
        return 2
    try:
        cost = accuracy_cost(pd.read_csv(args.table), args.tolerance)
    except ValueError as error:
        print(f"{args.table}: {error}", file=sys.stderr)
        return 2
    print(cost.to_string(index=False, float_format=lambda value: f"{value:.3g}"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
