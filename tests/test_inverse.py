"""The fit of one parameter to measured contact times (rodimpact.analysis.inverse): the fitted
value against the one that made the measurements, the Gauss-Newton standard error against its
closed form, leave-one-out, the grid's edge and the inputs' checks.

The model behind the synthetic measurements is the package's thin-film law: a steel ball on
the aluminium rod through a film of thickness h = 28 µm + theta, contact time of the rigid
impact at 0.3225 m/s (the six balls of the experiment)."""

from __future__ import annotations

import numpy as np
import pytest

from rodimpact.analysis.inverse import FitInputError, fit_theta, inside, leave_one_out, predict_at
from rodimpact.contact.film import HertzFilmLaw, constrained_modulus, film_constant
from rodimpact.contact.hertz import hertz_constant

from helpers.paper import ALUMINIUM, STEEL

RADII_M = 1e-3 * np.array([1.58, 2.375, 2.78, 3.17, 4.755, 6.365])
MASSES_KG = 1e-3 * np.array([0.13, 0.44, 0.71, 1.04, 3.51, 8.46])
VELOCITY_M_S = 0.3225
BASE_THICKNESS_M = 28e-6
FILM_MODULUS_PA = constrained_modulus(3e9, 0.35)
THETA_GRID_M = np.linspace(0.0, 60e-6, 8)
THETA_TRUE_M = 17e-6
NOISE = 0.005  # relative standard deviation of the synthetic measurements


def contact_times_us(theta_m: float) -> np.ndarray:
    """The six balls' rigid-flat contact times through a film 28 µm + theta thick, µs."""
    h = BASE_THICKNESS_M + theta_m
    times = []
    for radius, mass in zip(RADII_M, MASSES_KG):
        law = HertzFilmLaw(
            k=hertz_constant(radius, STEEL, ALUMINIUM),
            c=film_constant(radius, h, FILM_MODULUS_PA),
            sphere_radius_m=radius,
            thickness_m=h,
        )
        times.append(1e6 * law.rigid_impact(mass, VELOCITY_M_S).contact_time_s)
    return np.array(times)


@pytest.fixture(scope="module")
def film_model() -> dict[str, np.ndarray]:
    """The grid of predictions, the exact times at theta_true and their relative sensitivity."""
    step = 1e-8
    exact = contact_times_us(THETA_TRUE_M)
    slope = (contact_times_us(THETA_TRUE_M + step) - contact_times_us(THETA_TRUE_M - step)) / (2 * step)
    return {
        "predicted": np.column_stack([contact_times_us(x) for x in THETA_GRID_M]),
        "exact": exact,
        "sensitivity": slope / exact,
    }  # (1/t) dt/dtheta, 1/m


def test_the_model_grid_interpolates_to_the_exact_times_well_enough(film_model) -> None:
    # the zero-noise tolerance below rests on this: the grid's interpolation error at theta_true
    # is e (relative); it moves the fitted theta by at most max|e| / min(sensitivity)
    e = predict_at(THETA_GRID_M, film_model["predicted"], THETA_TRUE_M) / film_model["exact"] - 1.0
    theta_shift = np.max(np.abs(e)) / np.min(np.abs(film_model["sensitivity"]))
    assert theta_shift < 0.1 * 1e-3 * THETA_TRUE_M  # ten times inside the rtol 1e-3 used below


def test_without_noise_the_true_theta_is_recovered(film_model) -> None:
    fit = fit_theta(THETA_GRID_M, film_model["predicted"], film_model["exact"])
    assert fit.success and not fit.at_bound and fit.status == "converged"
    # rtol 1e-3: the interpolation error's shift of theta is 10x smaller (test above)
    assert fit.theta == pytest.approx(THETA_TRUE_M, rel=1e-3)
    assert fit.residual_rms < 1e-5
    assert fit.rows_used == tuple(range(6))
    assert fit.evaluations > 2001


def test_with_noise_the_true_theta_is_recovered_within_the_noise(film_model) -> None:
    rng = np.random.default_rng(20240517)
    measured = film_model["exact"] * (1.0 + NOISE * rng.standard_normal(6))
    fit = fit_theta(THETA_GRID_M, film_model["predicted"], measured)
    assert fit.success
    assert abs(fit.theta - THETA_TRUE_M) <= 3.0 * fit.standard_error
    # Linearized least squares: theta_hat - theta_true = sum s_i eps_i / sum s_i^2 (s_i the
    # relative sensitivity, eps_i the relative noise), of standard deviation
    # NOISE / sqrt(sum s_i^2) (~0.45 µm here). Four of them (a 1-in-15000 miss for a fixed
    # seed drawn at random), plus 1e-3 theta_true for the grid's interpolation (test above).
    sigma_theta = NOISE / np.sqrt(np.sum(film_model["sensitivity"] ** 2))
    assert abs(fit.theta - THETA_TRUE_M) <= 4.0 * sigma_theta + 1e-3 * THETA_TRUE_M
    # the standard error estimates sigma_theta from 5 degrees of freedom: within a factor 3
    assert sigma_theta / 3.0 < fit.standard_error < 3.0 * sigma_theta
    assert fit.residual_rms == pytest.approx(np.sqrt(np.mean((fit.predicted / measured - 1.0) ** 2)), rel=1e-12)


def test_linear_rows_give_the_closed_form_of_least_squares_and_its_standard_error() -> None:
    # PCHIP reproduces straight lines exactly, so the fit is linear least squares on
    # r_i = (a_i + b_i theta - m_i) / m_i: theta = sum u_i v_i / sum u_i^2 with u_i = b_i / m_i,
    # v_i = (m_i - a_i) / m_i, and se = sqrt(SSR / (n - 1) / sum u_i^2)
    grid = np.linspace(0.0, 1.0, 5)
    a, b = np.array([10.0, 20.0, 30.0, 40.0]), np.array([5.0, -8.0, 12.0, 3.0])
    measured = np.array([12.6, 16.1, 36.2, 41.4])
    u, v = b / measured, (measured - a) / measured
    theta = np.sum(u * v) / np.sum(u * u)
    ssr = np.sum((u * theta - v) ** 2)
    fit = fit_theta(grid, a[:, None] + b[:, None] * grid, measured)
    assert fit.theta == pytest.approx(theta, rel=1e-9)
    assert fit.standard_error == pytest.approx(np.sqrt(ssr / 3 / np.sum(u * u)), rel=1e-6)
    np.testing.assert_allclose(fit.predicted, a + b * theta, rtol=1e-9)


def test_leave_one_out_without_noise_predicts_every_held_out_ball(film_model) -> None:
    loo = leave_one_out(THETA_GRID_M, film_model["predicted"], film_model["exact"])
    assert len(loo.folds) == 6 and loo.all_success
    assert [fold.rows_used for fold in loo.folds] == [tuple(j for j in range(6) if j != i) for i in range(6)]
    assert np.all(loo.abs_error_pct < 0.1)
    np.testing.assert_allclose(loo.theta, THETA_TRUE_M, rtol=1e-3)
    np.testing.assert_allclose(loo.abs_error_pct, np.abs(loo.signed_error_pct))
    assert loo.mean_abs_error_pct == pytest.approx(np.mean(loo.abs_error_pct))
    np.testing.assert_allclose(
        loo.held_out_predicted,
        [predict_at(THETA_GRID_M, film_model["predicted"], t)[i] for i, t in enumerate(loo.theta)],
    )


def test_the_held_out_row_does_not_influence_its_own_fold(film_model) -> None:
    rng = np.random.default_rng(7)
    measured = film_model["exact"] * (1.0 + NOISE * rng.standard_normal(6))
    absurd = measured.copy()
    absurd[2] = 1e-3 * measured[2]  # far below anything the model predicts
    before = leave_one_out(THETA_GRID_M, film_model["predicted"], measured)
    after = leave_one_out(THETA_GRID_M, film_model["predicted"], absurd)
    assert after.theta[2] == before.theta[2]  # bit for bit: the fold never reads it
    assert after.held_out_predicted[2] == before.held_out_predicted[2]
    assert after.signed_error_pct[2] > 1e4  # but its error is measured against the absurd value
    # every other fold uses row 2, and it drags them to the grid's bottom
    assert all(fold.status == "at_lower_bound" for i, fold in enumerate(after.folds) if i != 2)


@pytest.mark.parametrize("scale, edge, status", [(1.2, -1, "at_upper_bound"), (0.8, 0, "at_lower_bound")])
def test_a_minimum_beyond_the_grid_is_reported_at_its_edge_never_extrapolated(film_model, scale, edge, status) -> None:
    predicted = film_model["predicted"]
    fit = fit_theta(THETA_GRID_M, predicted, scale * predicted[:, edge])
    assert fit.at_bound and not fit.success and fit.status == status
    assert fit.theta == THETA_GRID_M[edge]
    np.testing.assert_allclose(fit.predicted, predicted[:, edge], rtol=1e-12)
    with pytest.raises(FitInputError) as error:
        predict_at(THETA_GRID_M, predicted, THETA_GRID_M[-1] + 1e-6)
    assert error.value.field == "theta"


@pytest.mark.parametrize(
    "change, field",
    [
        ("non_monotone", "predicted"),
        ("short_row", "predicted"),
        ("nan_measured", "measured"),
        ("short_measured", "measured"),
        ("negative_measured", "measured"),
        ("decreasing_grid", "theta_grid"),
        ("two_point_grid", "theta_grid"),
        ("bad_rows", "rows"),
        ("bad_weights", "weights"),
        ("bad_range", "source_range"),
    ],
)
def test_bad_input_raises_naming_the_argument(film_model, change, field) -> None:
    predicted, exact = film_model["predicted"], film_model["exact"]
    wiggle = predicted.copy()
    wiggle[3, 4] = wiggle[3, 2]  # row 3 goes down between grid points 3 and 4
    args = {"theta_grid": THETA_GRID_M, "predicted": predicted, "measured": exact}
    options = {}
    if change == "non_monotone":
        args["predicted"] = wiggle
    elif change == "short_row":
        args["predicted"] = predicted[:, :-1]
    elif change == "nan_measured":
        args["measured"] = np.where(np.arange(6) == 1, np.nan, exact)
    elif change == "short_measured":
        args["measured"] = exact[:5]
    elif change == "negative_measured":
        args["measured"] = -exact
    elif change == "decreasing_grid":
        args["theta_grid"] = THETA_GRID_M[::-1]
    elif change == "two_point_grid":
        args["theta_grid"], args["predicted"] = THETA_GRID_M[:2], predicted[:, :2]
    elif change == "bad_rows":
        options["rows"] = [0, 6]
    elif change == "bad_weights":
        options["weights"] = np.zeros(6)
    elif change == "bad_range":
        options["source_range"] = (30e-6, 10e-6)
    with pytest.raises(FitInputError) as error:
        fit_theta(**args, **options)
    assert error.value.field == field
    assert isinstance(error.value, ValueError)
    if change in ("non_monotone", "nan_measured", "short_row"):
        with pytest.raises(FitInputError) as error:
            leave_one_out(**args)
        assert error.value.field == field


def test_the_source_range_says_whether_theta_lies_inside(film_model) -> None:
    args = (THETA_GRID_M, film_model["predicted"], film_model["exact"])
    assert fit_theta(*args).inside_range is None
    assert fit_theta(*args, source_range=(10e-6, 25e-6)).inside_range is True
    assert fit_theta(*args, source_range=(20e-6, 40e-6)).inside_range is False
    loo = leave_one_out(*args, source_range=(0.0, 5e-6))
    assert [fold.inside_range for fold in loo.folds] == [False] * 6
    assert inside(1.0, 1.0, 2.0) and inside(2.0, 1.0, 2.0) and not inside(2.5, 1.0, 2.0)


def test_rows_not_fitted_are_predicted_at_the_fitted_theta(film_model) -> None:
    predicted, exact = film_model["predicted"], film_model["exact"]
    spoiled = exact.copy()
    spoiled[[0, 5]] *= 3.0  # rows outside the fit: no effect on it
    fit = fit_theta(THETA_GRID_M, predicted, spoiled, rows=[1, 2, 3, 4])
    assert fit.rows_used == (1, 2, 3, 4) and fit.success
    assert fit.theta == pytest.approx(THETA_TRUE_M, rel=1e-3)
    np.testing.assert_allclose(fit.predicted, predict_at(THETA_GRID_M, predicted, fit.theta), rtol=1e-12)
    np.testing.assert_allclose(predict_at(THETA_GRID_M, predicted, THETA_GRID_M[3]), predicted[:, 3], rtol=1e-12)
