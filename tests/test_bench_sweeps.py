"""A sweep in parts, planned: the jobs a large sweep is cut into (rodimpact.jobs.parts through
the rule solve_sweep), and the scaling benchmark's bookkeeping (rodimpact.tools.bench_sweeps;
its timings are make bench's)."""

from __future__ import annotations

import csv
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from rodimpact.tools.bench_planning import SWEEP_SET, sweep_plan_project
from rodimpact.tools.bench_sweeps import SweepScaling, _counts, write_scaling

from helpers.repo import ROOT

SNAKEMAKE = str(Path(sys.executable).parent / "snakemake")


def _fem_axi_sweep(folder: Path) -> Path:
    """The planning project with its sweep by fem_axi: 10 masses (1 g to 100 g) x 10 velocities
    (0.1 to 2 m/s) of a steel ball on the Model's rod, 100 points."""
    project = sweep_plan_project(ROOT, 100, folder)
    path = project / "config" / "cases" / f"{SWEEP_SET}.yaml"
    document = yaml.safe_load(path.read_text())
    case = document["cases"][0]
    case["methods"] = case["sweep"]["methods"] = ["fem_axi"]
    case["sweep"]["parameters"] = {
        "mass_kg": {"start": 1.0e-3, "stop": 1.0e-1, "num": 10, "spacing": "log"},
        "velocity_m_s": {"start": 0.1, "stop": 2.0, "num": 10, "spacing": "log"},
    }
    path.write_text(yaml.safe_dump(document, sort_keys=False))
    return project


@pytest.mark.workflow  # it runs snakemake (a dry run)
def test_a_100_point_fem_axi_sweep_is_cut_into_at_least_10_jobs_none_above_twice_the_target(tmp_path: Path) -> None:
    """The dry run plans one job per part of the cut of the points' typical costs at the default
    target, consecutive points each, every point in exactly one; and the cut (the same function
    of the same costs) has no part above twice the target."""
    from rodimpact.analysis.sweeps import sweep_point_case, sweep_points
    from rodimpact.config.load import load_project
    from rodimpact.jobs.parts import cut
    from rodimpact.jobs.resources import run_cost

    project = _fem_axi_sweep(tmp_path / "copy")
    table = f"results/tables/sweep_{SWEEP_SET}.csv"
    plan = subprocess.run([SNAKEMAKE, table, "-n"], cwd=project, capture_output=True, text=True, check=False)
    assert plan.returncode == 0, plan.stdout[-3000:] + plan.stderr[-3000:]
    outputs = sorted(set(re.findall(r"output: (results/sweeps/\S+)", plan.stdout)))
    config = yaml.safe_load((project / "config" / "config.yaml").read_text())
    target = config["batch"]["target_s"]
    (sweep,) = load_project(config, root=project).sweeps_in(SWEEP_SET)
    costs = [
        run_cost(sweep_point_case(sweep, point, "p"), "fem_axi").typical_s for point in sweep_points(sweep["sweep"])
    ]
    parts = cut(costs, target)
    assert target == 30 and len(costs) == 100
    assert len(outputs) == len(parts) >= 10, outputs
    assert outputs == sorted(f"results/sweeps/{SWEEP_SET}/fem_axi/part{k}.h5" for k in range(len(parts)))
    assert max(part.typical_s for part in parts) <= 2 * target
    assert sum(part.stop - part.start for part in parts) == 100


def test_the_dry_runs_summary_gives_the_jobs_and_the_parts() -> None:
    summary = (
        "Job stats:\njob            count\n-----------  -------\n"
        "case_file          1\nsolve_sweep        8\nsweep_table        1\ntotal             10\n"
    )
    assert _counts(summary) == (10, 8)
    with pytest.raises(RuntimeError, match="no job counts"):
        _counts("Nothing to be done.")


def test_the_scaling_table_has_a_row_per_size_with_the_ratio(tmp_path: Path) -> None:
    rows = [
        SweepScaling(100, 3, 1, 1, 5.0, 10.0, 10.5, True, True),
        SweepScaling(10000, 10, 8, 8, 7.0, 200.0, 110.0, True, True),
    ]
    path = write_scaling(rows, tmp_path / "sweep_scaling.csv")
    with open(path, newline="", encoding="utf-8") as stream:
        read = list(csv.DictReader(stream))
    assert [row["points"] for row in read] == ["100", "10000"]
    assert read[1]["ratio"] == "0.550" and read[1]["tables_identical"] == "True" and read[1]["parts"] == "8"


def test_a_points_time_is_split_into_its_solve_and_its_store(tmp_path: Path) -> None:
    from rodimpact.tools.bench_sweeps import split_point_time, write_split

    split = split_point_time(ROOT, 20, tmp_path / "split")
    assert split.points == 20 and split.solve_ms > 0 and split.store_ms > 0
    assert split.other_ms >= 0 and split.total_ms >= split.solve_ms + split.store_ms
    path = write_split(split, tmp_path / "sweep_point.csv")
    with open(path, newline="", encoding="utf-8") as stream:
        (row,) = list(csv.DictReader(stream))
    assert row["points"] == "20" and float(row["total_ms"]) == pytest.approx(split.total_ms, abs=0.006)
