"""Tests of rodimpact.tools.bench_planning (what it runs and writes; its timings are make bench's)."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from rodimpact.tools.bench_planning import _ONE_RULE, SWEEP_SET, sweep_plan_project, time_dry_runs, write_timings

from helpers.repo import ROOT


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


@pytest.mark.parametrize("points, grid", [(300, {"mass_kg": 300}), (2000, {"mass_kg": 20, "velocity_m_s": 100})])
def test_the_planned_sweep_is_the_only_built_set(tmp_path: Path, points: int, grid: dict) -> None:
    """The copy's configuration checks, builds the planning sweep's set alone, and that sweep has
    the points asked for (above 1000: masses times 100 velocities); other sizes are refused."""
    import yaml

    from rodimpact.analysis.sweeps import sweep_points
    from rodimpact.config.load import load_project

    folder = sweep_plan_project(ROOT, points, tmp_path / "copy")
    config = yaml.safe_load((folder / "config" / "config.yaml").read_text())
    assert config["targets"]["sets"] == [SWEEP_SET]
    project = load_project(config, root=folder)
    (sweep,) = project.sweeps_in(SWEEP_SET)
    points_of = sweep_points(sweep["sweep"])
    assert len(points_of) == points
    assert {name: len({point[name] for point in points_of}) for name in points_of[0]} == grid
    with pytest.raises(ValueError, match="multiple of 100"):
        sweep_plan_project(ROOT, 1050, tmp_path / "other")
