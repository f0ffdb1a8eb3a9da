"""Tests of rodimpact.tools.bench_planning (what it runs and writes; its timings are make bench's)."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from rodimpact.tools.bench_planning import _ONE_RULE, time_dry_runs, write_timings


@pytest.mark.workflow  # it runs snakemake (four dry runs)
def test_the_dry_runs_are_timed_and_written(tmp_path: Path) -> None:
    """On a one-rule workflow: each kind is timed the number of runs asked for, and the table has
    one row per kind."""
    (tmp_path / "Snakefile").write_text(_ONE_RULE, encoding="utf-8")
    (tmp_path / "a.txt").touch()
    timings = time_dry_runs(tmp_path, runs=1)
    assert [t.name for t in timings] == ["dry_run", "one_rule"]
    assert all(len(t.seconds) == 1 and t.seconds[0] > 0 for t in timings)
    path = write_timings(timings, tmp_path / "bench" / "planning.csv")
    with open(path, newline="", encoding="utf-8") as stream:
        rows = list(csv.DictReader(stream))
    assert [row["name"] for row in rows] == ["dry_run", "one_rule"]
    assert all(row["runs"] == "1" and float(row["min_s"]) == float(row["median_s"]) for row in rows)


def test_at_least_one_run() -> None:
    with pytest.raises(ValueError, match="runs"):
        time_dry_runs(".", runs=0)
