"""The build's timing table (make bench's build.csv), from a small hand-made set of snakemake
job records."""

from __future__ import annotations

import base64
import csv
import json
from pathlib import Path

import h5py
import pytest

from rodimpact.tools.build_stats import COLUMNS, build_stats, main, read_jobs, write_build_stats


def _record(root: Path, output: str, rule: str, start: float, end: float, job_hash: int) -> None:
    """snakemake's record of one output (its path in URL-safe base64 is the file name)."""
    name = base64.urlsafe_b64encode(output.encode()).decode()
    path = root / ".snakemake" / "metadata" / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps({"rule": rule, "starttime": start, "endtime": end, "job_hash": job_hash}))


def _run(root: Path, output: str, wall: float, repeats: int | None = None) -> None:
    path = root / output
    path.parent.mkdir(parents=True, exist_ok=True)
    with h5py.File(path, "w") as h5:
        h5.attrs["wall_time_s"] = wall
        summary = h5.create_group("summary")
        if repeats is not None:
            summary.attrs["wall_time_repeats"] = repeats


def _runs(root: Path, output: str, walls: list[float]) -> None:
    """A file of runs (a sweep's part): one group per run, each with its solver time."""
    path = root / output
    path.parent.mkdir(parents=True, exist_ok=True)
    with h5py.File(path, "w") as h5:
        h5.attrs["layout"] = "runs"
        for index, wall in enumerate(walls):
            group = h5.create_group(f"p{index}")
            group.attrs["wall_time_s"] = wall
            group.create_group("summary")


def _file(root: Path, output: str) -> None:
    (root / output).parent.mkdir(parents=True, exist_ok=True)
    (root / output).write_text("x")


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """A sweep's part: a file of two runs (1.5 s and 0.5 s of solver in a 3 s job), a single run
    (2 s in a 2.5 s job), a timed run in a batch's directory (median 0.25 s, 4 repeats, in a 2 s
    job, with snakemake's timestamp file), a table (two outputs, 1 s), a benchmark (left out)
    and the record of a file that no longer exists (left out)."""
    _runs(tmp_path, "results/sweeps/s/sem/part0.h5", [1.5, 0.5])
    _record(tmp_path, "results/sweeps/s/sem/part0.h5", "solve_sweep", 100.0, 103.0, 7)
    _run(tmp_path, "results/runs/c/sem.h5", 2.0)
    _record(tmp_path, "results/runs/c/sem.h5", "solve", 101.0, 103.5, 8)
    _run(tmp_path, "results/convergence/c/sem/level0.h5", 0.25, repeats=4)
    _file(tmp_path, "results/convergence/c/sem/.snakemake_timestamp")
    _record(tmp_path, "results/convergence/c/sem", "solve_levels", 103.5, 105.5, 9)
    _file(tmp_path, "results/tables/t.csv")
    _file(tmp_path, "results/tables/t.md")
    _record(tmp_path, "results/tables/t.csv", "table", 106.0, 107.0, 10)
    _record(tmp_path, "results/tables/t.md", "table", 106.0, 107.0, 10)
    _file(tmp_path, "results/benchmarks/sem.csv")
    _record(tmp_path, "results/benchmarks/sem.csv", "bench_sem", 200.0, 300.0, 11)
    _record(tmp_path, "results/tables/gone.csv", "table", 50.0, 51.0, 12)
    return tmp_path


def test_jobs_group_the_records_of_one_job(project: Path) -> None:
    jobs = read_jobs(project)
    assert [(job.rule, job.start, job.end, job.runs) for job in jobs] == [
        ("solve_sweep", 100.0, 103.0, 2),
        ("solve", 101.0, 103.5, 1),
        ("solve_levels", 103.5, 105.5, 1),
        ("table", 106.0, 107.0, 0),
    ]
    assert jobs[0].solver_s == pytest.approx(2.0) and jobs[2].solver_s == pytest.approx(1.0)
    assert jobs[3].outputs == ("results/tables/t.csv", "results/tables/t.md")


def test_rows_per_rule_and_the_build(project: Path) -> None:
    rows = {row.rule: row for row in build_stats(read_jobs(project))}
    assert list(rows) == ["solve", "solve_levels", "solve_sweep", "table", "total"]
    batch = rows["solve_sweep"]
    assert (batch.jobs, batch.runs) == (1, 2)
    assert batch.job_s == pytest.approx(3.0) and batch.solver_s == pytest.approx(2.0)
    assert batch.overhead_s == pytest.approx(1.0) and batch.overhead_per_run_s == pytest.approx(0.5)
    assert rows["solve_levels"].overhead_s == pytest.approx(1.0)  # 2 s job, 4 x 0.25 s of solves
    assert rows["table"].solver_s == 0 and rows["table"].overhead_per_run_s is None
    total = rows["total"]
    assert (total.jobs, total.runs) == (4, 4)
    assert total.job_s == pytest.approx(3.0 + 2.5 + 2.0 + 1.0)
    assert total.solver_s == pytest.approx(2.0 + 2.0 + 1.0)
    assert total.median_job_s == pytest.approx(2.25) and total.median_overhead_s == pytest.approx(1.0)
    assert total.wall_s == pytest.approx(7.0)  # 100 s to 107 s; the benchmark is not the build's


def test_the_csv_and_the_command(project: Path) -> None:
    assert main(["--root", str(project)]) == 0
    with open(project / "results/benchmarks/build.csv", newline="") as handle:
        table = list(csv.DictReader(handle))
    assert tuple(table[0]) == COLUMNS
    assert [row["rule"] for row in table][-1] == "total"
    assert float(table[-1]["wall_s"]) == pytest.approx(7.0) and table[-1]["jobs"] == "4"
    written = write_build_stats(build_stats(read_jobs(project)), project / "again.csv")
    assert written.read_text() == (project / "results/benchmarks/build.csv").read_text()


def test_no_records_says_so(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    assert read_jobs(tmp_path) == [] and build_stats([]) == []
    assert main(["--root", str(tmp_path)]) == 1
    assert "run `make paper` first" in caplog.text
    assert not (tmp_path / "results/benchmarks/build.csv").exists()
