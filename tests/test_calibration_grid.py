"""A calibration read between runs on a grid, and the cases predicted at the fitted constants.

- :class:`~rodimpact.jobs.calibration_model.GridModel` equals the model it reads at the grid's
  values (to round-off), follows it between them (relative 1e-4 on five points over 0.8-1.2 m/s
  of the impact velocity; measured 1.7e-5 there and 1.2e-4 on three points), and a fit through
  it recovers a velocity from measurements the model itself made there;
- the standard error propagated to a prediction is exact for a linear model:
  sqrt(diag(A Cov A^T)).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from rodimpact.analysis.calibration import Observation, Parameter, calibrate
from rodimpact.analysis.measured import read_history
from rodimpact.jobs.calibrate import propagated_standard_errors
from rodimpact.jobs.calibration_model import GridModel, SetModel

BOUNDS = (0.8, 1.2)


@pytest.fixture(scope="module")
def model(shipped_project) -> SetModel:
    """The SEM's peak strain and strain integral at the gauge of the example's two lightest balls,
    against the impact velocity."""
    cases = shipped_project.cases_in("gauge_example")[:2]
    block = {
        "method": "sem",
        "parameters": [{"path": "impactor.velocity_m_s", "bounds": list(BOUNDS), "source": "a test"}],
        "quantities": ["strain_peak_microstrain", "strain_integral_microstrain_us"],
    }
    records = {
        c["id"]: {
            "strain_history": read_history(
                c["measured"]["strain_history"]["path"], c["measured"]["strain_history"], "strain_history"
            )
        }
        for c in cases
    }
    return SetModel(cases, block, shipped_project.config["numerics"], records)


def _midpoint_error(grid: GridModel, model: SetModel) -> float:
    mids = 0.5 * (grid.grid[1:] + grid.grid[:-1])
    return max(float(np.max(np.abs(grid(np.array([x])) / model(np.array([x])) - 1.0))) for x in mids)


def test_the_grid_model_is_the_model_at_its_points_and_follows_it_between(model: SetModel) -> None:
    coarse, fine = GridModel(model, np.linspace(*BOUNDS, 3)), GridModel(model, np.linspace(*BOUNDS, 5))
    for value in fine.grid:
        np.testing.assert_allclose(fine(np.array([value])), model(np.array([value])), rtol=1e-12)
    assert _midpoint_error(fine, model) < 1e-4
    assert _midpoint_error(fine, model) < _midpoint_error(coarse, model)


def test_a_fit_through_the_grid_recovers_the_velocity_the_model_measured(model: SetModel) -> None:
    truth = 1.037
    measured = model(np.array([truth]))
    observations = [
        Observation(cid, quantity, float(value), abs(float(value)))
        for (cid, quantity), value in zip(model.rows, measured, strict=True)
    ]
    parameter = Parameter("impactor.velocity_m_s", *BOUNDS, start=1.0, unit="m/s", source="a test")
    fit = calibrate(GridModel(model, np.linspace(*BOUNDS, 5)), observations, [parameter])
    assert fit.success, fit.message
    np.testing.assert_allclose(fit.values, [truth], rtol=1e-4)


def test_a_linear_models_propagated_standard_errors_are_exact() -> None:
    a = np.array([[1.0, 2.0], [0.5, -3.0], [4.0, 0.0]])
    covariance = np.array([[0.04, 0.01], [0.01, 0.09]])
    parameters = [Parameter("x", -1.0, 1.0, unit="", source="-"), Parameter("y", 0.0, 2.0, unit="", source="-")]
    for values in ([0.2, 1.0], [1.0, 0.0]):  # inside, and at a bound of each (one-sided there)
        fit = SimpleNamespace(values=np.array(values), parameters=parameters, covariance=covariance)
        expected = np.sqrt(np.diag(a @ covariance @ a.T))
        np.testing.assert_allclose(propagated_standard_errors(lambda theta: a @ theta, fit), expected, rtol=1e-10)


def test_a_case_at_its_own_constants_reads_its_rules_curve(shipped_project, tmp_path, monkeypatch) -> None:
    """A case whose law the continuum's indentation calibrates: at its own constants the model
    reads the curve the rule computed for its runs (the same numbers as computing it again), and
    at any other value of a constant it computes the curve anew."""
    import rodimpact.jobs.indentation as indentation

    case = shipped_project.cases["ball_3.16mm-r10_l30_sensor_cal"]
    numerics = shipped_project.config["numerics"]
    (curve,) = indentation.indentations_into([case], tmp_path / "curves", numerics["fem_axi"])
    path = "contact.stack.layers[3].thickness_m"
    block = {
        "method": "sem",
        "parameters": [{"path": path, "bounds": [3e-6, 8e-5], "source": "a test"}],
        "quantities": ["contact_time_us"],
    }
    computed = SetModel([case], block, numerics, {})
    reading = SetModel([case], block, numerics, {}, curves={case["id"]: str(curve)})
    own = np.array([case["contact"]["stack"]["layers"][3]["thickness_m"]])
    expected = computed(own)
    built = []
    original = indentation.indentation_curve
    monkeypatch.setattr(indentation, "indentation_curve", lambda *a: built.append(a) or original(*a))
    assert reading(own).tolist() == expected.tolist() and not built
    other = own * 1.5
    assert reading(other).tolist() == computed(other).tolist() and len(built) == 2
    assert reading(other)[0] > expected[0]  # a thicker bond line lengthens the contact
