"""The calibration of declared constants (rodimpact.analysis.calibration, .calibration_loo), on
closed-form models:

- a linear model f = A theta: the fit is the weighted least-squares solution (np.linalg.lstsq)
  and its standard errors sqrt(diag(s2 (A_w^T A_w)^-1)), to 1e-6;
- a nonlinear model y = a exp(-b t) with noise, over 200 seeds: the true value lies within two
  standard errors in 88-99 % of the fits (95 % expected), and the mean fit is unbiased;
- identifiability (a product a b, a parameter the data do not see), a fit held by a bound, a
  model failing on the way, the inputs refused before any model call;
- leave-one-out: each held-out case's prediction is the least-squares refit without it, and a
  case whose removal leaves too few observations is marked so;
- the cache: the model is called once per distinct theta, and shared fits reuse its calls.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rodimpact.analysis.calibration import (
    MAX_CONDITION,
    MAX_CORRELATION,
    CalibrationInputError,
    ModelFailure,
    Observation,
    Parameter,
    calibrate,
)
from rodimpact.analysis.calibration_loo import TOO_FEW, leave_one_out

T = np.linspace(0.0, 3.0, 30)  # the abscissae of the exponential model


def linear_problem(seed: int = 0, n: int = 12):
    """A (n, 3) well-conditioned design, noisy measurements, relative scales, cases of 2 rows."""
    rng = np.random.default_rng(seed)
    x = np.linspace(-1.0, 1.0, n)
    a = np.column_stack([np.ones(n), x, x**2 - 0.4])
    measured = a @ np.array([2.0, -0.7, 0.9]) * (1.0 + 0.03 * rng.normal(size=n))
    observations = [Observation(f"case{i // 2}", "q", float(m), abs(float(m))) for i, m in enumerate(measured)]
    parameters = [Parameter(f"p{j}", -10.0, 10.0, unit="1", source="test") for j in range(3)]
    return a, measured, observations, parameters


def weighted_ols(a, measured, rows):
    """The least-squares solution with residuals (A theta - m) / |m|, and its standard errors."""
    w = 1.0 / np.abs(measured[rows])
    aw, mw = a[rows] * w[:, None], measured[rows] * w
    theta, *_ = np.linalg.lstsq(aw, mw, rcond=None)
    r = aw @ theta - mw
    s2 = r @ r / (len(rows) - a.shape[1])
    return theta, np.sqrt(np.diag(s2 * np.linalg.inv(aw.T @ aw)))


def never_called(theta):
    raise AssertionError(f"the model was called at {theta}")


def test_linear_model_is_weighted_least_squares():
    a, measured, observations, parameters = linear_problem()
    fit = calibrate(lambda theta: a @ theta, observations, parameters)
    theta, se = weighted_ols(a, measured, np.arange(len(measured)))
    assert fit.status == "converged" and fit.success and fit.identifiable
    np.testing.assert_allclose(fit.values, theta, rtol=1e-6)
    np.testing.assert_allclose(fit.standard_errors, se, rtol=1e-6)
    np.testing.assert_allclose(fit.jacobian, a, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(fit.predicted, a @ fit.values, rtol=1e-12)
    np.testing.assert_allclose(fit.residuals, (a @ fit.values - measured) / np.abs(measured), rtol=1e-12)
    assert fit.dof == len(measured) - 3
    assert fit.s2 == pytest.approx(np.sum(fit.residuals**2) / fit.dof)
    np.testing.assert_allclose(np.diag(fit.correlation), 1.0)
    assert np.all(np.abs(fit.correlation[np.triu_indices(3, 1)]) < MAX_CORRELATION)
    assert not fit.at_bound.any() and fit.warnings == ()
    rows = fit.table_rows()
    assert [row["name"] for row in rows] == ["p0", "p1", "p2"]
    assert rows[1]["standard_error"] == pytest.approx(se[1], rel=1e-6) and rows[1]["source"] == "test"


def test_nonlinear_standard_errors_cover_the_truth():
    true, sigma, seeds = np.array([2.0, 0.7]), 0.05, 200
    parameters = [Parameter("a", 0.5, 5.0), Parameter("b", 0.1, 3.0)]
    fits = []
    for seed in range(seeds):
        y = true[0] * np.exp(-true[1] * T) + sigma * np.random.default_rng(seed).normal(size=T.size)
        observations = [Observation("c", "y", float(v), 1.0) for v in y]  # s2 carries sigma^2
        fit = calibrate(lambda theta: theta[0] * np.exp(-theta[1] * T), observations, parameters)
        assert fit.status == "converged"
        fits.append(fit)
    values = np.array([f.values for f in fits])
    errors = np.array([f.standard_errors for f in fits])
    coverage = np.mean(np.abs(values - true) <= 2.0 * errors, axis=0)
    assert np.all((coverage >= 0.88) & (coverage <= 0.99)), coverage
    assert np.all(np.abs(values.mean(axis=0) - true) < 3.0 * values.std(axis=0, ddof=1) / math.sqrt(seeds))


def test_a_product_of_parameters_is_not_identifiable():
    t = np.arange(1.0, 11.0)
    y = 6.0 * t * (1.0 + 0.01 * np.random.default_rng(1).normal(size=t.size))
    observations = [Observation("c", "y", float(v), abs(float(v))) for v in y]
    fit = calibrate(lambda theta: theta[0] * theta[1] * t, observations, [Parameter("a", 1, 5), Parameter("b", 1, 5)])
    assert not fit.identifiable and fit.status == "not_identifiable" and not fit.success
    assert fit.condition_number > MAX_CONDITION and any("near-singular" in w for w in fit.warnings)
    # J is singular to rounding: the correlation is -1 to rounding, or undefined (NaN)
    assert not abs(fit.correlation[0, 1]) <= MAX_CORRELATION
    assert fit.values[0] * fit.values[1] == pytest.approx(6.0, rel=0.01)  # the product is determined


def test_a_parameter_the_data_do_not_see_is_flagged():
    t = np.arange(1.0, 11.0)
    y = 3.0 * t * (1.0 + 0.01 * np.random.default_rng(2).normal(size=t.size))
    observations = [Observation("c", "y", float(v), abs(float(v))) for v in y]
    fit = calibrate(lambda theta: theta[0] * t, observations, [Parameter("a", 1, 5), Parameter("unseen", 0, 1)])
    assert not fit.identifiable and fit.status == "not_identifiable"
    assert any("do not see unseen" in w for w in fit.warnings)
    assert fit.standard_errors[1] == math.inf and math.isfinite(fit.standard_errors[0])
    a_only = calibrate(lambda theta: theta[0] * t, observations, [Parameter("a", 1, 5)])
    assert fit.values[0] == pytest.approx(a_only.values[0], rel=1e-8)
    assert fit.standard_errors[0] == pytest.approx(a_only.standard_errors[0] * math.sqrt(9 / 8), rel=1e-6)


def test_an_optimum_beyond_a_bound_is_reported_at_the_bound():
    t = np.arange(1.0, 11.0)
    y = 3.0 * t + 0.5 + 0.05 * np.random.default_rng(3).normal(size=t.size)
    observations = [Observation("c", "y", float(v), 0.05) for v in y]
    parameters = [Parameter("slope", 0.0, 2.0, unit="1/s"), Parameter("offset", -20.0, 20.0)]
    fit = calibrate(lambda theta: theta[0] * t + theta[1], observations, parameters)
    assert fit.status == "at_bound" and not fit.success
    assert fit.at_bound.tolist() == [True, False]
    assert fit.values[0] == pytest.approx(2.0, rel=1e-8)
    assert any("bound of slope" in w for w in fit.warnings)
    # the offset is the least-squares one given the slope at its bound
    assert fit.values[1] == pytest.approx(np.mean(y - 2.0 * t), rel=1e-6)


def test_as_many_observations_as_parameters_leaves_the_errors_undefined():
    observations = [Observation("c", "y", 3.0, 1.0), Observation("d", "y", 5.0, 1.0)]
    fit = calibrate(lambda theta: np.array([theta[0] + theta[1], theta[0] + 2 * theta[1]]), observations,
                    [Parameter("a", -10, 10), Parameter("b", -10, 10)])  # fmt: skip
    np.testing.assert_allclose(fit.values, [1.0, 2.0], rtol=1e-6)
    assert fit.dof == 0 and math.isnan(fit.s2) and np.all(np.isnan(fit.standard_errors))
    assert np.all(np.isfinite(fit.correlation)) and any("undefined" in w for w in fit.warnings)


def _exponential_observations():
    y = 2.0 * np.exp(-0.7 * T) + 0.02 * np.random.default_rng(1).normal(size=T.size)
    return [Observation("c", "y", float(v), 0.02) for v in y]


def test_a_model_failing_near_the_minimum_falls_back_to_one_sided_differences():
    observations = _exponential_observations()
    clean = calibrate(lambda theta: theta[0] * np.exp(-theta[1] * T), observations,
                      [Parameter("a", 0.5, 5.0), Parameter("b", 0.1, 3.0)])  # fmt: skip
    edge = clean.values[1] + 0.5 * 1e-3 * 2.9  # half a finite-difference step above the minimum

    def model(theta):
        if theta[1] > edge:
            raise ArithmeticError("no root")
        return theta[0] * np.exp(-theta[1] * T)

    fit = calibrate(model, observations, [Parameter("a", 0.5, 5.0), Parameter("b", 0.1, 3.0, start=0.2)])
    assert fit.status == "converged" and fit.failed_trials >= 1
    assert any("failed at" in w for w in fit.warnings)
    np.testing.assert_allclose(fit.values, clean.values, atol=1e-3 * clean.standard_errors.min())
    np.testing.assert_allclose(fit.standard_errors, clean.standard_errors, rtol=1e-3)


def test_a_fit_stopped_by_model_failures_is_failed_not_converged():
    observations = _exponential_observations()

    def model(theta):  # fails on the way from the start (a = 4.9) to the minimum (a = 2)
        if 3.0 < theta[0] < 4.0:
            raise ModelFailure("diverged")
        return theta[0] * np.exp(-theta[1] * T)

    fit = calibrate(model, observations, [Parameter("a", 0.5, 5.0, start=4.9), Parameter("b", 0.1, 3.0)])
    assert fit.status == "failed" and not fit.success and "short of the minimum" in fit.message
    assert fit.failed_trials > 0


@pytest.mark.parametrize("bad", ["raise", "nan"])
def test_a_model_failing_at_the_start_gives_a_failed_fit(bad):
    def model(theta):
        if bad == "raise":
            raise ModelFailure("the solver diverged")
        return np.full(T.size, math.nan)

    fit = calibrate(model, _exponential_observations(), [Parameter("a", 0.5, 5.0), Parameter("b", 0.1, 3.0)])
    assert fit.status == "failed" and "start" in fit.message and fit.failed_trials == 1 and fit.evaluations == 1
    assert np.all(np.isnan(fit.standard_errors))


def test_a_model_of_the_wrong_shape_is_refused():
    with pytest.raises(CalibrationInputError) as error:
        calibrate(lambda theta: np.zeros(3), _exponential_observations(), [Parameter("a", 0, 1)])
    assert error.value.field == "model"


P = [Parameter("a", 0.0, 1.0), Parameter("b", 0.0, 1.0)]
O3 = [Observation("c1", "y", 1.0, 1.0), Observation("c2", "y", 2.0, 1.0), Observation("c3", "y", 3.0, 1.0)]


@pytest.mark.parametrize(
    ("observations", "parameters", "options", "field"),
    [
        (O3[:1], P, {}, "parameters"),
        (O3, [], {}, "parameters"),
        (O3, [P[0], Parameter("a", 0.0, 2.0)], {}, "parameters"),
        (O3, [Parameter("a", math.nan, 1.0)], {}, "parameters.a.low"),
        (O3, [Parameter("a", 0.0, math.inf)], {}, "parameters.a.high"),
        (O3, [Parameter("a", 1.0, 1.0)], {}, "parameters.a.low"),
        (O3, [Parameter("a", 0.0, 1.0, start=1.5)], {}, "parameters.a.start"),
        ([], P, {}, "observations"),
        ([O3[0], Observation("c2", "y", math.nan, 1.0), O3[2]], P, {}, "observations[1]"),
        ([Observation("c1", "y", 1.0, 0.0), *O3[1:]], P, {}, "observations[0]"),
        ([*O3[:2], Observation("c3", "y", 1.0, -1.0)], P, {}, "observations[2]"),
        ([*O3[:2], Observation("", "y", 1.0, 1.0)], P, {}, "observations[2]"),
        (O3, P, {"rows": [0, 5]}, "rows"),
        (O3, P, {"rows": [0]}, "rows"),
        (O3, P, {"rows": [1, 1]}, "rows"),
        (O3, P, {"model_tolerance": -1.0}, "model_tolerance"),
        (O3, P, {"max_trials": 0}, "max_trials"),
    ],
)
def test_inputs_are_refused_before_any_model_call(observations, parameters, options, field):
    with pytest.raises(CalibrationInputError) as error:
        calibrate(never_called, observations, parameters, **options)
    assert error.value.field == field
    if "rows" not in options:
        with pytest.raises(CalibrationInputError) as error:
            leave_one_out(never_called, observations, parameters, **options)
        assert error.value.field == field


def test_leave_one_out_is_the_refit_without_each_case():
    a, measured, observations, parameters = linear_problem(seed=4)
    result = leave_one_out(lambda theta: a @ theta, observations, parameters)
    assert result.cases == tuple(f"case{c}" for c in range(6)) and result.possible == 6
    assert result.status == ("converged",) * 6
    for c in range(6):
        held = [2 * c, 2 * c + 1]
        kept = np.array([i for i in range(len(measured)) if i not in held])
        theta, _ = weighted_ols(a, measured, kept)
        np.testing.assert_allclose(result.values[c], theta, rtol=1e-6)
        np.testing.assert_allclose(result.held_out_predicted[held], a[held] @ theta, rtol=1e-6)
        assert result.folds[c].rows_used == tuple(kept)
    expected = 100.0 * (result.held_out_predicted - measured) / np.abs(measured)
    np.testing.assert_allclose(result.held_out_error_pct, expected, rtol=1e-12)
    assert result.mean_abs_error_pct == pytest.approx(np.mean(np.abs(expected)))
    assert result.mean_abs_error_pct > result.in_sample_mean_abs_error_pct  # out of sample is worse
    assert result.table_rows()[3]["held_out_error_pct"] == pytest.approx(expected[3])


def test_a_case_whose_removal_leaves_too_few_observations_is_marked():
    t = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    y = 1.0 + 2.0 * t + np.array([0.1, -0.1, 0.05, 0.0, -0.05])
    observations = [Observation("big" if i < 4 else "small", "y", float(v), 1.0) for i, v in enumerate(y)]
    parameters = [Parameter("c", -5, 5), Parameter("k", -5, 5)]
    result = leave_one_out(lambda theta: theta[0] + theta[1] * t, observations, parameters)
    assert result.status == (TOO_FEW, "converged") and result.possible == 1 and result.folds[0] is None
    assert np.all(np.isnan(result.held_out_predicted[:4])) and np.all(np.isnan(result.values[0]))
    assert result.row_status == (TOO_FEW,) * 4 + ("converged",)
    coefficients = np.polyfit(t[:4], y[:4], 1)
    assert result.held_out_predicted[4] == pytest.approx(np.polyval(coefficients, 4.0), rel=1e-6)


def test_the_model_is_called_once_per_theta_and_shared_fits_reuse_its_calls():
    a, measured, observations, parameters = linear_problem(seed=5)
    calls = []

    def model(theta):
        calls.append(tuple(theta))
        return a @ theta

    cache = {}
    fit = calibrate(model, observations, parameters, cache=cache)
    assert fit.evaluations == len(calls) == len(set(calls)) == len(cache)
    again = calibrate(model, observations, parameters, cache=cache)
    assert again.evaluations == 0 and len(calls) == fit.evaluations
    np.testing.assert_array_equal(again.values, fit.values)
    shared = leave_one_out(model, observations, parameters, fit, cache=cache)
    assert shared.evaluations == len(calls) - fit.evaluations == len(set(calls)) - fit.evaluations
    alone = leave_one_out(lambda theta: a @ theta, observations, parameters, fit)
    assert shared.evaluations < alone.evaluations  # the folds start where the full fit's calls are
    np.testing.assert_allclose(shared.held_out_predicted, alone.held_out_predicted, rtol=1e-9)


def test_leave_one_out_refuses_a_fit_of_other_data():
    a, measured, observations, parameters = linear_problem()
    fit = calibrate(lambda theta: a[:-1] @ theta, observations[:-1], parameters)
    with pytest.raises(CalibrationInputError) as error:
        leave_one_out(never_called, observations, parameters, fit)
    assert error.value.field == "fit"
