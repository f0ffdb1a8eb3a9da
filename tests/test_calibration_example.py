"""The calibration of the strain-gauge worked example (config/cases/worked_example_gauge.yaml): the
shipped synthetic records' known constants recovered, and the standard errors' coverage over
noise seeds (docs/calibration.md)."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np

from rodimpact.analysis.calibration import calibrate
from rodimpact.analysis.measured import read_history
from rodimpact.config.calibration import with_method
from rodimpact.config.paths import with_setting
from rodimpact.config.project import Project
from rodimpact.jobs.calibrate import calibration_parameters, observations_of, run_calibration
from rodimpact.jobs.calibration_model import SetModel
from rodimpact.storage.calibrations import read_calibration
from rodimpact.tools.synthetic_history import SyntheticRecord, synthetic_history, write_synthetic_history

SET = "gauge_example"
#: The constants the shipped records were made with (the case file's notes).
TRUE = {"rod.material.youngs_modulus_pa": 2.0e11, "impactor.velocity_m_s": 1.05}
#: Noise seeds of the coverage test, and the least fraction of fits whose two-standard-error
#: interval holds the true value: with 12 measurements and 2 constants the fitted value lies
#: within two standard errors as Student's t with 10 degrees of freedom does, 92.7 % of the
#: time (95 % only as the degrees of freedom grow); 85 % leaves room for 20 draws.
SEEDS = range(20)
#: The SEM's steps per contact in the coverage test (its error, some 1e-5 of the contact time,
#: is the same in the records and in the model).
FIXED_STEPS = 400
MIN_COVERAGE = 0.85


def test_the_shipped_example_recovers_its_true_constants(shipped_project: Project, tmp_path: Path) -> None:
    block = shipped_project.calibrate[SET]
    out = tmp_path / "calibration.h5"
    fit = run_calibration(SET, shipped_project.cases_in(SET), block, shipped_project.config["numerics"], out)
    assert fit.success and fit.identifiable, (fit.status, fit.message, fit.warnings)
    for name, value, error in zip([p.name for p in fit.parameters], fit.values, fit.standard_errors, strict=True):
        assert abs(value - TRUE[name]) < 2.0 * error, (name, value, error)
        assert error < 0.01 * TRUE[name], (name, error)  # the records determine each to 1 %
    stored = read_calibration(out)
    assert stored.scalars["status"] == fit.status
    np.testing.assert_allclose(stored.arrays["values"], fit.values, rtol=1e-15)
    assert stored.described["loo"]["status"] == ["converged"] * 4
    # the held-out predictions are predictions: none of them is the fitted model's own value
    assert np.all(stored.arrays["held_out_predicted"] != stored.arrays["predicted"])


def test_a_constant_the_first_pulse_does_not_see_is_not_identifiable(shipped_project: Project, tmp_path: Path):
    """The rod's length fitted to the first pulse at the gauge, which ends before any reflection
    returns: the data do not see it, and the fit says so by its documented status (not ``failed``,
    whatever the optimiser did along a direction the data do not determine)."""
    block = copy.deepcopy(shipped_project.calibrate[SET])
    block["parameters"][1] = {"path": "rod.length_m", "bounds": [0.45, 0.55], "unit": "m", "source": "a test"}
    cases = shipped_project.cases_in(SET)[:2]
    fit = run_calibration(SET, cases, block, shipped_project.config["numerics"], tmp_path / "calibration.h5")
    assert fit.status == "not_identifiable" and not fit.identifiable and not fit.success, (fit.status, fit.message)
    assert any("the data do not see rod.length_m" in w for w in fit.warnings), fit.warnings
    assert read_calibration(tmp_path / "calibration.h5").scalars["status"] == "not_identifiable"


def _synthetic_cases(project: Project, seed: int, directory: Path) -> list[dict]:
    """The example's cases with records made by the SEM itself (no model error) at the true
    constants, plus 1 % noise drawn from ``seed``."""
    cases = []
    for case in project.cases_in(SET):
        # a fixed number of steps per contact (one solve a run, no step doubling): the records
        # and the model are the same model, so its own error drops out; what is left is the noise
        case = copy.deepcopy(case)
        case["numerics"]["sem"] = {**case["numerics"]["sem"], "steps_per_contact": FIXED_STEPS}
        truth = with_method(case, "sem", project.config["numerics"])
        for path, value in TRUE.items():
            truth = with_setting(truth, path, value)
        spec = case["measured"]["strain_history"]
        record = SyntheticRecord(
            method="sem",
            noise=0.01,
            seed=seed,
            sample_us=0.5,
            pretrigger_us=20.0,
            posttrigger_us=10.0,
            gauge=(spec["station_m"], spec["gauge_length_m"]),
        )
        path = directory / f"{case['id']}_{seed}.csv"
        write_synthetic_history(truth, record, path)
        case["measured"]["strain_history"]["path"] = str(path)
        cases.append(case)
    return cases


def test_two_standard_errors_cover_the_true_constants_over_noise_seeds(
    shipped_project: Project, tmp_path: Path
) -> None:
    """The fit alone (the job's model and observations, without its leave-one-out), on records
    made by the model itself: what is left is the noise, which the standard errors must cover."""
    block, numerics = shipped_project.calibrate[SET], shipped_project.config["numerics"]
    parameters = calibration_parameters(block)
    start = np.asarray([0.5 * (p.low + p.high) for p in parameters])
    covered = {name: 0 for name in TRUE}
    for seed in SEEDS:
        cases = _synthetic_cases(shipped_project, seed, tmp_path)
        records = {
            c["id"]: {
                "strain_history": read_history(
                    c["measured"]["strain_history"]["path"], c["measured"]["strain_history"], "strain_history"
                )
            }
            for c in cases
        }
        model = SetModel(cases, block, numerics, records)
        fit = calibrate(model, observations_of(model.rows, model.observe(start)), parameters)
        assert fit.success, (seed, fit.status, fit.message)
        for name, value, error in zip([p.name for p in fit.parameters], fit.values, fit.standard_errors, strict=True):
            covered[name] += abs(value - TRUE[name]) <= 2.0 * error
    fractions = {name: count / len(SEEDS) for name, count in covered.items()}
    assert all(fraction >= MIN_COVERAGE for fraction in fractions.values()), fractions


def test_the_shipped_gauge_records_are_what_the_tool_makes(shipped_project: Project, root: Path) -> None:
    """Each synthetic gauge record is reproduced by the command in its case's note, to the
    digits written: fem1d at the true constants, the gauge's mean strain, 1 % noise, seed 1."""
    for case in shipped_project.cases_in(SET):
        spec = case["measured"]["strain_history"]
        truth = case
        for path, value in TRUE.items():
            truth = with_setting(truth, path, value)
        record = SyntheticRecord(
            sample_us=0.5, pretrigger_us=20.0, posttrigger_us=10.0, gauge=(spec["station_m"], spec["gauge_length_m"])
        )
        times, strains, _ = synthetic_history(truth, record)
        shipped = read_history(root / spec["path"], spec, "strain_history")
        np.testing.assert_allclose(shipped.time_s, 1e-6 * np.round(times, 3), rtol=1e-12)
        np.testing.assert_allclose(shipped.values, strains, rtol=1e-5, atol=1e-12)
        assert "SYNTHETIC" in spec["note"] and "synthetic" in spec["path"]


def test_measurements_weighted_two_ways_are_warned_of() -> None:
    """A record's readings carry the noise's uncertainty; a value typed in has none and counts by
    its relative error: a fit that mixes the two says so; one kind alone, or norms, does not."""
    from rodimpact.analysis.observations import Observed
    from rodimpact.jobs.calibrate import mixed_scales_warning

    record = Observed("strain_peak_microstrain", "peak", "microstrain", -77.0, -76.9, -0.1, 0.2)
    typed = Observed("contact_time_us", "contact time", "µs", 77.2, 77.0, -0.3)
    norm = Observed("strain_l2_pct", "strain, L2 error", "%", float("nan"), float("nan"), 2.0)
    warning = mixed_scales_warning([record, typed, norm])
    assert warning is not None and warning.startswith("1 of 2 measurements (contact_time_us)")
    assert mixed_scales_warning([record, record]) is None
    assert mixed_scales_warning([typed, norm]) is None
