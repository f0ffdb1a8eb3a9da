"""Observed orders and the grid convergence index against closed forms (rodimpact.analysis.convergence)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rodimpact.analysis.convergence import (
    changes_sign,
    constant_ratio,
    fitted_order,
    grid_convergence_index,
    is_monotone,
    numerical_uncertainty,
    oscillatory_uncertainty,
)


@pytest.mark.parametrize("order", [1.0, 1.5, 2.0, 4.0])
def test_an_exact_power_law_gives_its_order_with_no_spread(order: float) -> None:
    h = 0.1 / 2.0 ** np.arange(5)
    fit = fitted_order(h, 3.0 * h**order)
    assert fit.order == pytest.approx(order, rel=1e-12) and fit.points == 5
    assert fit.stderr == pytest.approx(0.0, abs=1e-10)


def test_the_standard_error_is_the_slopes() -> None:
    # log e = 2 log h + noise: the slope's standard error by the textbook formula
    rng = np.random.default_rng(3)
    h = 0.1 / 2.0 ** np.arange(6)
    noise = 0.1 * rng.standard_normal(6)
    fit = fitted_order(h, h**2 * np.exp(noise))
    x, y = np.log(h), 2 * np.log(h) + noise
    slope, intercept = np.polyfit(x, y, 1)
    expected = math.sqrt(np.sum((y - slope * x - intercept) ** 2) / 4 / np.sum((x - x.mean()) ** 2))
    assert fit.order == pytest.approx(slope, rel=1e-12) and fit.stderr == pytest.approx(expected, rel=1e-12)
    assert math.isnan(fitted_order(h[:2], h[:2] ** 2).stderr)  # two points: a slope, no spread


@pytest.mark.parametrize("order, ratio", [(2.0, 2.0), (1.5, 1.5), (1.0, 3.0)])
def test_the_index_of_an_exact_power_law(order: float, ratio: float) -> None:
    # f(h) = f0 + C h^p on h, r h, r^2 h: p, f0 and GCI = Fs |f1 - f0| / |f1| exactly
    f0, c, h = 56.5, -3.0, 0.01
    f1, f2, f3 = (f0 + c * (h * ratio**k) ** order for k in range(3))
    gci = grid_convergence_index(f1, f2, f3, ratio)
    assert gci.order == pytest.approx(order, rel=1e-9) and gci.monotone
    assert gci.extrapolated == pytest.approx(f0, rel=1e-12)
    assert gci.gci == pytest.approx(1.25 * abs(f1 - f0) / abs(f1), rel=1e-9)


def test_oscillatory_and_diverging_sequences_have_no_index() -> None:
    oscillating = grid_convergence_index(1.00, 1.01, 0.99, 2.0)
    assert not oscillating.monotone and math.isnan(oscillating.order) and math.isnan(oscillating.gci)
    diverging = grid_convergence_index(1.0, 1.1, 1.15, 2.0)  # the differences grow on refinement
    assert diverging.monotone and diverging.order < 0 and math.isnan(diverging.gci)
    with pytest.raises(ValueError, match="ratio"):
        grid_convergence_index(1.0, 1.1, 1.2, 1.0)


def test_monotone_errors() -> None:
    assert is_monotone([1e-2, -5e-3, 1e-3]) and not is_monotone([1e-2, 1e-3, 2e-3]) and not is_monotone([1e-2])


def test_sign_changes_and_constant_ratios() -> None:
    assert changes_sign([3e-5, -9e-6, 6e-5]) and not changes_sign([3e-5, 9e-6, math.nan])
    assert not changes_sign([-1e-3, -1e-4]) and not changes_sign([])
    assert constant_ratio([5, 10, 20]) == 2.0 and constant_ratio([150.0, 300.0, 600.0]) == 2.0
    assert math.isnan(constant_ratio([4, 6, 8])) and math.isnan(constant_ratio([6, 8, 12]))
    assert math.isnan(constant_ratio([10])) and math.isnan(constant_ratio([20, 10, 5]))


def test_the_oscillatory_uncertainty_is_half_the_range() -> None:
    # Stern et al. 2001: U = (max - min) / 2, here relative to the finest solution
    assert oscillatory_uncertainty(1.00, 1.01, 0.99) == pytest.approx(0.01, rel=1e-12)
    assert oscillatory_uncertainty(-2.0, -2.2, -2.1) == pytest.approx(0.05, rel=1e-12)


def test_the_uncertainty_is_the_index_where_defined_else_half_the_range() -> None:
    f0, c, h = 56.5, -3.0, 0.01
    f1, f2, f3 = (f0 + c * (h * 2.0**k) ** 2 for k in range(3))
    monotone = numerical_uncertainty(f1, f2, f3, 2.0)
    assert not monotone.oscillatory and monotone.value == monotone.index.gci
    assert monotone.value == pytest.approx(1.25 * abs(f1 - f0) / abs(f1), rel=1e-9)
    oscillating = numerical_uncertainty(1.00, 1.01, 0.99, 2.0)
    assert oscillating.oscillatory and math.isnan(oscillating.index.gci)
    assert oscillating.value == pytest.approx(0.01, rel=1e-12)
    # no constant ratio: no index, but half the range still bounds the levels
    uneven = numerical_uncertainty(f1, f2, f3, math.nan)
    assert not uneven.oscillatory and math.isnan(uneven.index.gci)
    assert uneven.value == pytest.approx(0.5 * (f1 - f3) / f1, rel=1e-12)
