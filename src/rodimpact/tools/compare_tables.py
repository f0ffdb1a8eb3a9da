"""``python -m rodimpact.tools.compare_tables BEFORE AFTER``: are two builds' tables the same?

Every ``results/tables/*.{csv,md,html,tex,json}`` of one build is compared with the other's:

* a CSV column by column: the same columns and rows; a numeric column by its largest relative
  difference ``max |a - b| / max(|a|, tiny)`` over its rows (NaN equal to NaN), any other column
  exactly. A percentage column (``*_pct``: 100 times a ratio of two results, or a difference of
  two such) is compared in percentage points: within ``100 rtol (1 + |a| / 100)``, what a
  relative change ``rtol`` of the results it is made of gives (a difference of two percentages
  near zero has no relative precision). Columns that time the machine's work
  (:data:`TIMING_COLUMNS`) are left out;
* a Markdown or HTML table cell by cell under its header (the timing columns left out again),
  numbers within ``rtol``; any other line, and a LaTeX or JSON file, line by line, numbers
  within ``rtol``. Provenance records (``*.provenance.json``: times, versions and digests by
  design) are not compared.

It prints one line per file that differs beyond ``--rtol`` (with the column or line and the
difference) and the largest relative difference of every CSV, and exits 1 when any file
differs, is missing on one side, or has other columns or rows. This is how a refactor shows it
kept the results (docs/studies.md, "How the tables were compared").
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["TIMING_COLUMNS", "TableDifference", "compare_csv", "compare_text", "compare_tables", "main"]

#: Columns of the machine's work, not of the results: wall times, their repeats, the machine.
TIMING_COLUMNS = frozenset(
    {
        "wall_time_s",
        "wall_time_min_s",
        "wall_time_max_s",
        "repeats",
        "wall_time_repeats",
        "machine",
        "run_time_s",
        "created_utc",
        "Wall time (s)",
        "Run time (s)",
    }
)
SUFFIXES = (".csv", ".md", ".html", ".tex", ".json")
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_HTML_CELL = re.compile(r"<t[hd][^>]*>(.*?)</t[hd]>", re.S)


@dataclass(frozen=True)
class TableDifference:
    """One file's comparison: its largest relative difference, and what differs beyond rtol."""

    name: str
    largest: float
    problems: tuple[str, ...]

    @property
    def same(self) -> bool:
        return not self.problems


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    both_nan = np.isnan(a) & np.isnan(b)
    scale = np.maximum(np.abs(a), np.finfo(float).tiny)
    with np.errstate(invalid="ignore"):
        diff = np.where(both_nan, 0.0, np.abs(a - b) / scale)
    diff = np.where(np.isnan(diff), np.inf, diff)  # NaN on one side only
    return float(diff.max()) if diff.size else 0.0


def compare_csv(before: Path, after: Path, rtol: float) -> TableDifference:
    """Two CSV tables: columns, rows, and each column's largest relative difference."""
    a, b = pd.read_csv(before), pd.read_csv(after)
    problems: list[str] = []
    if list(a.columns) != list(b.columns):
        return TableDifference(after.name, math.inf, (f"columns differ: {list(a.columns)} / {list(b.columns)}",))
    if len(a) != len(b):
        return TableDifference(after.name, math.inf, (f"{len(a)} rows / {len(b)} rows",))
    largest = 0.0
    for column in a.columns:
        if column in TIMING_COLUMNS:
            continue
        x, y = a[column], b[column]
        if pd.api.types.is_numeric_dtype(x) and pd.api.types.is_numeric_dtype(y):
            if str(column).endswith("_pct"):
                u, v = x.to_numpy(float), y.to_numpy(float)
                with np.errstate(invalid="ignore"):
                    points = np.where(np.isnan(u) & np.isnan(v), 0.0, np.abs(u - v) / (100.0 + np.abs(u)))
                worst = float(np.nan_to_num(points, nan=np.inf).max()) if len(u) else 0.0
                if worst > rtol:
                    problems.append(f"column {column!r}: {100 * worst:.3g} percentage points per 100")
                continue
            worst = _relative(x.to_numpy(float), y.to_numpy(float))
            largest = max(largest, worst)
            if worst > rtol:
                problems.append(f"column {column!r}: relative difference {worst:.3g}")
        elif not x.fillna("").astype(str).equals(y.fillna("").astype(str)):
            rows = [i for i, (p, q) in enumerate(zip(x.fillna("").astype(str), y.fillna("").astype(str))) if p != q]
            problems.append(f"column {column!r}: text differs in rows {rows[:5]}")
    return TableDifference(after.name, largest, tuple(problems))


def _numbers_close(line_a: str, line_b: str, rtol: float) -> bool:
    if _NUMBER.sub("#", line_a) != _NUMBER.sub("#", line_b):
        return False
    for p, q in zip(_NUMBER.findall(line_a), _NUMBER.findall(line_b)):
        x, y = float(p), float(q)
        if x != y and abs(x - y) > rtol * max(abs(x), abs(y)):
            return False
    return True


def _cells(line: str, suffix: str) -> list[str] | None:
    """A Markdown or HTML table row's cells (None: not a table row)."""
    if suffix == ".md" and line.lstrip().startswith("|"):
        return [cell.strip() for cell in line.strip().strip("|").split("|")]
    if suffix == ".html":
        cells = _HTML_CELL.findall(line)
        # a header's words without their markup ("Wall time<br><span>(s)</span>": "Wall time (s)")
        return [" ".join(re.sub(r"<[^>]+>", " ", cell).split()) for cell in cells] if cells else None
    return None


def compare_text(before: Path, after: Path, rtol: float) -> TableDifference:
    """Two text tables line by line, a table row cell by cell under its header (numbers within
    ``rtol`` equal; the timing columns left out)."""
    a = before.read_text(encoding="utf-8").splitlines()
    b = after.read_text(encoding="utf-8").splitlines()
    if len(a) != len(b):
        return TableDifference(after.name, math.inf, (f"{len(a)} lines / {len(b)} lines",))
    problems = []
    header: list[str] | None = None
    for i, (p, q) in enumerate(zip(a, b)):
        cells_p, cells_q = _cells(p, before.suffix), _cells(q, before.suffix)
        if cells_p is None or cells_q is None or len(cells_p) != len(cells_q):
            if before.suffix == ".md":  # a Markdown table is a block of rows, its header the first
                header = None
            if p != q and not _numbers_close(p, q, rtol):
                problems.append(f"line {i + 1}: {p.strip()[:80]!r} / {q.strip()[:80]!r}")
            continue
        if header is None or "<th" in p:
            header = cells_p
        for j, (x, y) in enumerate(zip(cells_p, cells_q)):
            name = header[j] if j < len(header) else ""
            if x != y and name not in TIMING_COLUMNS and not _numbers_close(x, y, rtol):
                problems.append(f"line {i + 1}, column {name!r}: {x[:40]!r} / {y[:40]!r}")
    return TableDifference(after.name, 0.0, tuple(problems[:5]))


def compare_tables(before: Path, after: Path, rtol: float = 1e-9, ignore: Sequence[str] = ()) -> list[TableDifference]:
    """Every table file of two ``results/tables`` directories (``ignore``: file names left out)."""
    names = sorted(
        {
            p.name
            for d in (before, after)
            for p in d.iterdir()
            if p.suffix in SUFFIXES and not p.name.endswith(".provenance.json")
        }
        - set(ignore)
    )
    out = []
    for name in names:
        a, b = before / name, after / name
        if not (a.is_file() and b.is_file()):
            out.append(TableDifference(name, math.inf, (f"only in {before if a.is_file() else after}",)))
        elif a.suffix == ".csv":
            out.append(compare_csv(a, b, rtol))
        else:
            out.append(compare_text(a, b, rtol))
    return out


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m rodimpact.tools.compare_tables", description=__doc__.split("\n")[0]
    )
    parser.add_argument("before", type=Path, help="a build's results/tables directory")
    parser.add_argument("after", type=Path, help="the other build's results/tables directory")
    parser.add_argument("--rtol", type=float, default=1e-9, help="relative tolerance (default 1e-9)")
    parser.add_argument("--ignore", nargs="*", default=[], help="file names to leave out")
    args = parser.parse_args(argv)
    results = compare_tables(args.before, args.after, args.rtol, args.ignore)
    for result in results:
        if result.name.endswith(".csv") and result.same:
            print(f"{result.name}: same (largest relative difference {result.largest:.2g})")
        for problem in result.problems:
            print(f"{result.name}: {problem}")
    differing = [r.name for r in results if not r.same]
    print(f"{len(results)} files, {len(differing)} differ beyond rtol {args.rtol:g}")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
