"""A batch job's runs: each with its own provenance, as a single run's, in a file of runs or a file each."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest

from rodimpact.analysis.sweeps import sweep_point_case, sweep_points
from rodimpact.jobs.batch import run_batch, run_batch_file
from rodimpact.jobs.cases import write_case_file
from rodimpact.jobs.runner import SolverFailed, run_to_file
from rodimpact.storage.runs import read_run, run_references


@pytest.fixture(scope="module")
def sweep(shipped_project) -> dict:
    """A Table 2 sweep case, and three of its points run by sem."""
    return copy.deepcopy(next(iter(shipped_project.sweeps.values())))


def _runs(sweep: dict, count: int) -> dict[str, dict]:
    points = sweep_points(sweep["sweep"])[:count]
    names = ["_".join(f"{k}~{v}" for k, v in point.items()) for point in points]
    return {
        f"p{i}": {
            "case": sweep_point_case(sweep, point, name),
            "method": "sem",
            "study": {"name": "sweep", "sweep": sweep["id"], "point": name},
        }
        for i, (point, name) in enumerate(zip(points, names))
    }


def test_each_run_is_its_own_file_as_a_single_run_writes_it(sweep: dict, tmp_path: Path) -> None:
    case_file = write_case_file(sweep["id"], [sweep], tmp_path / "case.yaml")
    runs = _runs(sweep, 3)
    paths = {name: tmp_path / f"{name}.h5" for name in runs}
    assert run_batch(runs, paths, case_file=case_file) == list(paths.values())
    single = run_to_file(
        runs["p1"]["case"], "sem", tmp_path / "single.h5", study=runs["p1"]["study"], case_file=case_file
    )
    batch, alone = read_run(paths["p1"]), read_run(single)
    assert batch.config == alone.config and batch.config_sha256 == alone.config_sha256
    assert (
        batch.code_version == alone.code_version and batch.summary["contact_time_s"] == alone.summary["contact_time_s"]
    )
    assert batch.config["run"]["case_file"]["path"] == str(case_file)
    assert {read_run(p).case_id for p in paths.values()} == {run["case"]["id"] for run in runs.values()}


def test_a_batch_reads_its_case_file_once(sweep: dict, tmp_path: Path, monkeypatch) -> None:
    """Every run of a sweep has its own case id in the same case file: the file is read once for
    the batch, and each run still records its case's hash in it."""
    import rodimpact.jobs.batch as batch_module
    import rodimpact.storage.casefile as casefile_module

    case_file = write_case_file(sweep["id"], [sweep], tmp_path / "case.yaml")
    reads = []
    read = casefile_module.read_case_file
    for module in (batch_module, casefile_module):
        monkeypatch.setattr(module, "read_case_file", lambda path: reads.append(path) or read(path), raising=False)
    runs = _runs(sweep, 3)
    paths = {name: tmp_path / f"{name}.h5" for name in runs}
    run_batch(runs, paths, case_file=case_file)
    assert reads == [case_file]
    recorded = {read_run(path).config["run"]["case_file"]["config_sha256"] for path in paths.values()}
    assert recorded == {read(case_file)["cases"][0]["config_sha256"]}


def test_outputs_and_runs_must_match(sweep: dict, tmp_path: Path) -> None:
    runs = _runs(sweep, 1)
    with pytest.raises(ValueError, match="runs and paths differ"):
        run_batch(runs, {"other": tmp_path / "x.h5"})
    assert not list(tmp_path.iterdir())


def test_a_part_of_a_sweep_is_one_file_of_runs_each_as_its_own_file_holds_it(sweep: dict, tmp_path: Path) -> None:
    """run_batch_file: every run of the batch a group of one file, in order, each with the same
    config, config hash and numbers as the run written to its own file (all but the solver's
    timing); a batch that fails leaves no file."""
    case_file = write_case_file(sweep["id"], [sweep], tmp_path / "case.yaml")
    runs = _runs(sweep, 3)
    target = tmp_path / "part0.h5"
    references = run_batch_file(runs, target, case_file=case_file)
    assert references == run_references(target) == [f"{target}#{name}" for name in runs]
    alone = run_batch(runs, {name: tmp_path / f"{name}.h5" for name in runs}, case_file=case_file)
    for reference, path in zip(references, alone):
        grouped, single = read_run(reference), read_run(path)
        assert grouped.path == Path(reference) and grouped.config == single.config
        assert grouped.config_sha256 == single.config_sha256 and grouped.data_sha256
        timed = {key for key in single.summary if "wall_time" in key}
        assert timed and grouped.summary.keys() == single.summary.keys()
        assert {k: str(v) for k, v in grouped.summary.items() if k not in timed} == {
            k: str(v) for k, v in single.summary.items() if k not in timed
        }
        assert grouped.series.keys() == single.series.keys()
        for name in single.series:
            assert (grouped.series[name] == single.series[name]).all(), name
    failing = copy.deepcopy(runs)
    failing["p2"]["case"]["numerics"]["sem"]["max_steps"] = 10  # the last run fails after two are in
    with pytest.raises(SolverFailed):
        run_batch_file(failing, tmp_path / "failed.h5")
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(("failed", ".failed"))]
    with pytest.raises(ValueError, match="cannot name a run"):
        run_batch_file({"a#b": runs["p0"]}, tmp_path / "bad.h5")
    assert not (tmp_path / "bad.h5").exists()


def test_a_calibrated_sweep_point_computes_its_own_curve_as_the_indentation_rule_does(
    shipped_project, shipped_config: dict, tmp_path: Path
) -> None:
    """A point of a sweep with the law the continuum calibrates: its batch indents the point's
    own ball (the indentation rule's function, the rule's settings) and runs the SEM with that
    curve; the run stores the curve's summary, and equals the same point with its curve given."""
    from rodimpact.jobs.indentation import indentation_curve

    sweep = copy.deepcopy(shipped_project.sweeps["ball_sweep_sensor-r10_l30_sensor_cal"])
    runs = _runs(sweep, 1)
    settings = shipped_config["numerics"]["fem_axi"]
    runs["p0"]["curve"] = {"rule": "indentation", "settings": settings}
    run_batch(runs, {"p0": tmp_path / "p0.h5"})
    stored = read_run(tmp_path / "p0.h5")
    curve = indentation_curve(runs["p0"]["case"], settings)
    given = run_to_file(
        runs["p0"]["case"], "sem", tmp_path / "given.h5", study=runs["p0"]["study"], contact_curve=curve
    )
    assert stored.summary["contact_time_s"] == read_run(given).summary["contact_time_s"]
    assert stored.config["run"]["contact_curve"] == {"computed_in_job": True, "summary": curve.summary}
    with pytest.raises(ValueError, match="no curve rule 'elsewhere'"):
        run_batch({"p0": {**runs["p0"], "curve": {"rule": "elsewhere"}}}, {"p0": tmp_path / "x.h5"})
    assert not (tmp_path / "x.h5").exists()
