"""The numerical studies: study cases, failure kept as data, timing, work-precision errors and
fitted orders, and the stress checks on a fast subset of config/cases/stress.yaml."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from rodimpact.analysis.stability_study import map_frame, stability_frame, violations
from rodimpact.analysis.studies import level_case, map_point_case, map_point_names, reference_case
from rodimpact.analysis.work_precision import observed_orders, work_precision_frame
from rodimpact.jobs.runner import SolverFailed, Timing, run_to_file
from rodimpact.model.problem import ImpactProblem
from rodimpact.storage.runs import read_run


@pytest.fixture(scope="module")
def config(shipped_config):
    return shipped_config


@pytest.fixture(scope="module")
def project(shipped_project):
    return shipped_project


def test_map_point_has_the_asked_mass_and_impedance(project, config):
    spec = config["stability"]["map"]
    base = project.cases[spec["base_case"]]
    names = map_point_names(spec)
    assert len(names) == len(spec["mass_kg"]) * len(spec["impedance_kg_s"])
    case = map_point_case(base, spec, "m1_z2", "sem_paper", config["numerics"])
    rod = case["rod"]["material"]
    impedance = case["rod"]["area_m2"] * math.sqrt(rod["youngs_modulus_pa"] * rod["density_kg_m3"])
    assert impedance == pytest.approx(spec["impedance_kg_s"][2], rel=1e-12)
    assert case["impactor"]["mass_kg"] == spec["mass_kg"][1]
    assert case["methods"] == ["sem_paper"] and case["numerics"]["sem_paper"]["allow_unstable"] is True
    assert case["numerics"]["sem_paper"]["steps_per_contact"] == spec["steps_per_contact"]
    assert base["impactor"]["mass_kg"] == 0.5  # the base case is not modified


def test_a_failed_study_run_is_data_and_a_failed_paper_run_writes_nothing(project, config, tmp_path):
    case = level_case(project.cases["model"], "sem", config["numerics"], {"steps_per_contact": 2000, "max_steps": 50})
    with pytest.raises(SolverFailed, match="max_steps=50"):
        run_to_file(case, "sem", tmp_path / "paper.h5")
    assert not (tmp_path / "paper.h5").exists()
    rec = read_run(run_to_file(case, "sem", tmp_path / "study.h5", keep_failed=True))
    assert rec.summary["success"] is False and rec.summary["status"] == "failed"
    assert "max_steps=50" in rec.summary["message"]


def test_timing_repeats_and_records_the_machine(project, config, tmp_path):
    case = level_case(project.cases["ball_3.16mm-r1_l30"], "sem", config["numerics"], {"steps_per_contact": 100})
    path = run_to_file(
        case,
        "sem",
        tmp_path / "timed.h5",
        level=0,
        timing=Timing(3, 0.0, 60.0),
        study={"name": "work_precision", "level": 0, "overrides": {"steps_per_contact": 100}},
    )
    rec = read_run(path)
    assert rec.summary["wall_time_repeats"] == 3
    assert rec.summary["wall_time_min_s"] <= rec.wall_time_s <= rec.summary["wall_time_max_s"]
    assert "logical CPUs" in rec.summary["machine"]
    assert rec.config["run"]["study"]["overrides"] == {"steps_per_contact": 100}


@pytest.fixture(scope="module")
def sweep(project, config, tmp_path_factory):
    """sem and sem_paper swept on the lightest Table 2 ball, as the workflow does."""
    methods = {name: dict(config["work_precision"]["methods"][name]) for name in ("sem", "sem_paper")}
    methods["sem"]["levels"] = [{"steps_per_contact": n} for n in (25, 50, 100, 200, 400, 800, 1600, 3200)]
    methods["sem_paper"]["levels"] = [{"steps_per_contact": n} for n in (250, 500, 1000, 2000, 4000, 8000)]
    folder = tmp_path_factory.mktemp("sweep")
    records = []
    for method, spec in methods.items():
        for level, overrides in enumerate(spec["levels"]):
            case = level_case(project.cases["ball_3.16mm-r1_l30"], method, config["numerics"], overrides)
            records.append(read_run(run_to_file(case, method, folder / f"{method}_{level}.h5", level=level)))
    frame = work_precision_frame(records, methods)
    return frame, observed_orders(
        frame, methods, fit_levels=4, arrival_window=config["work_precision"]["arrival_window"]
    )


def test_work_precision_errors_fall_with_cost(sweep):
    frame, _ = sweep
    for _, rows in frame.groupby("method"):
        rows = rows.sort_values("resolution_value")
        assert np.all(np.diff(rows["n_steps"]) > 0)
        assert rows["err_contact_time"].iloc[-1] < rows["err_contact_time"].iloc[0] / 20
    # the reference is converged far below the errors it measures
    assert frame["ref_err_contact_time"].max() < 1e-8


def test_observed_orders_match_the_theory(sweep):
    _, orders = sweep
    table = orders.set_index(["method", "quantity"])["observed_order"]
    for quantity in ("contact_time", "max_1", "history_l2"):
        assert 1.8 < table[("sem", quantity)] < 2.3, quantity
        assert 0.85 < table[("sem_paper", quantity)] < 1.2, quantity


# ----------------------------------------------------------------- stress cases (fast subset)

FAST_STRESS = [
    "short_rod",
    "rubber_on_steel",
    "steel_on_rubber",
    "long_rod_heavy",
    "heavy_slow",
    "thornton_far_below",
    "thornton_far_above",
]


@pytest.fixture(scope="module")
def stress(project, config, tmp_path_factory):
    folder = tmp_path_factory.mktemp("stress")
    runs, refs = [], {}
    for case_id in FAST_STRESS:
        case = project.cases[case_id]
        ref = reference_case(case, config["numerics"], config["stability"]["reference_tolerance"])
        refs[case_id] = read_run(run_to_file(ref, "sem", folder / f"{case_id}_ref.h5", keep_failed=True))
        for method in case["methods"]:
            if method == "fem_axi":
                continue  # covered by the workflow's stability target (seconds per case)
            runs.append(read_run(run_to_file(case, method, folder / f"{case_id}_{method}.h5", keep_failed=True)))
    return stability_frame(runs, refs, config["stability"]["tolerances"]), runs, refs


def test_stress_subset_meets_its_tolerances(stress):
    frame, _, _ = stress
    assert violations(frame) == []
    assert (frame["verdict"] == "ok").all(), frame[["case_id", "method", "verdict"]]
    assert frame["finite"].all() and (frame["min_force_N"] >= 0).all()


def test_every_contact_interval_is_reported(stress):
    """The 50 kg ball strikes the 5 m rod twice: every method reports both intervals alike."""
    frame, _, refs = stress
    rows = frame[frame["case_id"] == "long_rod_heavy"]
    assert (rows["n_contacts"] == 2).all()
    ref = refs["long_rod_heavy"].summary
    assert len(ref["contact_start_s"]) == 2 and ref["contact_start_s"][1] > ref["contact_end_s"][0]
    for intervals in rows["contact_intervals_us"]:
        values = [float(x) for pair in intervals.split("; ") for x in pair.split("-")]
        expected = 1e6 * np.ravel(np.column_stack([ref["contact_start_s"], ref["contact_end_s"]]))
        assert values == pytest.approx(expected, rel=1e-3)


def test_thorntons_law_dissipates_far_below_its_hertz_pressure_and_not_far_above(stress, project):
    """Far below: most of the impact energy is dissipated in the contact and a dent is left,
    the restitution under the rigid flat's closed form (the rod takes some energy too); far above:
    the law is Hertz's, with no dissipation and no dent."""
    _, runs, _ = stress
    by_case: dict[str, list] = {}
    for run in runs:
        by_case.setdefault(run.case_id, []).append(run)
    for run in by_case["thornton_far_above"]:
        assert run.summary["dissipated_energy_J"] == 0.0 and run.summary["residual_approach_m"] == 0.0
    problem = ImpactProblem.from_case(project.cases["thornton_far_below"])
    rigid = problem.rigid_contact
    for run in by_case["thornton_far_below"]:
        assert 0.9 * problem.kinetic_energy_J < run.summary["dissipated_energy_J"] < problem.kinetic_energy_J
        assert run.summary["residual_approach_m"] > 0.0
        assert 0.9 * rigid.restitution < run.summary["restitution"] < rigid.restitution


def test_a_wrong_answer_is_a_violation_and_a_failure_is_not(stress, config):
    _, runs, refs = stress
    run = runs[0]
    gained = dataclasses.replace(run, summary={**run.summary, "energy_error": -0.2})
    negative = dataclasses.replace(run, series={**run.series, "contact_force": run.series["contact_force"] - 1.0})
    failed = dataclasses.replace(run, summary={**run.summary, "success": False, "message": "step budget spent"})
    frame = stability_frame([gained, negative, failed], refs, config["stability"]["tolerances"])
    assert frame["verdict"].iloc[0].startswith("VIOLATION: energy gain 0.2")
    assert "negative force" in frame["verdict"].iloc[1]
    assert frame["verdict"].iloc[2] == "failed: step budget spent"


def test_map_classifies_the_papers_instability(project, config, tmp_path):
    """On a thin rod at a coarse step the paper scheme diverges; the implicit one does not."""
    spec = {**config["stability"]["map"], "steps_per_contact": 20}
    base = project.cases[spec["base_case"]]
    runs, refs = [], {}
    point = "m0_z1"  # 0.1 g on Z = 3 kg/s: twice the paper scheme's limit at 20 steps
    for method in ("sem", "sem_paper", "reference"):
        case = map_point_case(base, spec, point, method, config["numerics"])
        name = "sem" if method == "reference" else method
        rec = read_run(run_to_file(case, name, tmp_path / f"{method}.h5", keep_failed=True))
        (refs.__setitem__(point, rec) if method == "reference" else runs.append(rec))
    frame = map_frame(runs, refs, spec["accuracy"]).set_index("method")
    assert frame.loc["sem_paper", "h_over_limit"] > 1
    assert frame.loc["sem_paper", "class"] == "zig-zag or failed"
    assert frame.loc["sem", "class"] != "zig-zag or failed"
