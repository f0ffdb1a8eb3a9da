"""Brent's root finder of the SEM's contact end: exact roots, the same iterates as scipy's brentq."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rodimpact.solvers.sem.roots import RootNotBracketedError, RootNotConvergedError, brent_root


@pytest.mark.parametrize(
    "f, a, b, root",
    [
        (lambda x: x * x - 2.0, 0.0, 2.0, math.sqrt(2.0)),
        (lambda x: math.cos(x) - x, 0.0, 1.0, 0.7390851332151607),
        (lambda x: math.exp(x) - 3.0, -1.0, 4.0, math.log(3.0)),
        (lambda x: x**3 - 1e-9, 0.0, 1.0, 1e-3),
    ],
)
def test_brent_root_finds_the_zero_to_its_tolerance(f, a, b, root):
    x = brent_root(f, a, b, xtol=1e-300, rtol=8.9e-16)
    assert x == pytest.approx(root, rel=4e-15, abs=0.0)


def test_brent_root_matches_scipy_brentq_bit_for_bit():
    rng = np.random.default_rng(7)
    functions = (
        lambda x: x * x - 2.0,
        lambda x: math.sin(5.0 * x) + 0.3,
        lambda x: (x - 0.3) ** 1.5 if x > 0.3 else -((0.3 - x) ** 0.7),
    )
    compared = 0
    for f in functions:
        for a, b in np.sort(rng.uniform(-3.0, 3.0, (200, 2)), axis=1):
            if f(a) * f(b) >= 0.0:
                continue
            for xtol, rtol in ((1e-12, 8.9e-16), (1e-300, 8.9e-16), (1e-6, 1e-10)):
                assert brent_root(f, a, b, xtol=xtol, rtol=rtol) == brentq(f, a, b, xtol=xtol, rtol=rtol)
                compared += 1
    assert compared > 300


def test_brent_root_refuses_a_bracket_without_sign_change_and_reports_no_convergence():
    with pytest.raises(RootNotBracketedError):
        brent_root(lambda x: x * x + 1.0, -1.0, 1.0, xtol=1e-12, rtol=8.9e-16)
    with pytest.raises(RootNotConvergedError):
        brent_root(
            lambda x: math.copysign(abs(x - 0.123) ** 0.05, x - 0.123), 0.0, 1.0, xtol=1e-300, rtol=8.9e-16, maxiter=3
        )
    assert brent_root(lambda x: x, 0.0, 1.0, xtol=1e-12, rtol=8.9e-16) == 0.0
