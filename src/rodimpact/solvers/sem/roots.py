"""Brent's bracketing root finder, for the end of a contact inside a step.

The same iteration as :func:`scipy.optimize.brentq` (Brent 1973 as written by C. Harris for
scipy: bisection, secant and inverse quadratic steps, with the step kept inside the bracket),
so the roots agree to the last bit, in plain Python: a SEM run locates a handful of events,
and importing :mod:`scipy.optimize` for them would cost a workflow job about half a second.
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = ["RootNotBracketedError", "RootNotConvergedError", "brent_root"]


class RootNotBracketedError(ValueError):
    """f(a) and f(b) have the same sign, so [a, b] brackets no root."""


class RootNotConvergedError(RuntimeError):
    """The iteration did not meet its tolerance within ``maxiter`` steps."""


def brent_root(
    f: Callable[[float], float], a: float, b: float, *, xtol: float, rtol: float, maxiter: int = 100
) -> float:
    """A zero of ``f`` in the bracket [a, b].

    Parameters
    ----------
    f : callable
        Continuous scalar function; f(a) and f(b) differ in sign (or one is zero).
    a, b : float
        The bracket's ends (same unit as the root).
    xtol, rtol : float
        The root x0 returned satisfies |x0 - x| <= xtol + rtol |x0| for the exact zero x.
    maxiter : int
        Most iterations.

    Returns
    -------
    float
        The zero.

    Raises
    ------
    RootNotBracketedError
        f(a) f(b) > 0.
    RootNotConvergedError
        No convergence within ``maxiter`` iterations.
    """
    x_pre, x_cur = float(a), float(b)
    f_pre, f_cur = float(f(x_pre)), float(f(x_cur))
    if f_pre == 0.0:
        return x_pre
    if f_cur == 0.0:
        return x_cur
    if math.copysign(1.0, f_pre) == math.copysign(1.0, f_cur):
        raise RootNotBracketedError(f"f({a!r}) = {f_pre!r} and f({b!r}) = {f_cur!r} have the same sign")
    x_blk = f_blk = s_pre = s_cur = 0.0
    for _ in range(maxiter):
        if f_pre != 0.0 and f_cur != 0.0 and math.copysign(1.0, f_pre) != math.copysign(1.0, f_cur):
            # the root lies between x_pre and x_cur: x_pre becomes the far end of the bracket
            x_blk, f_blk = x_pre, f_pre
            s_pre = s_cur = x_cur - x_pre
        if abs(f_blk) < abs(f_cur):
            # keep the best estimate in x_cur
            x_pre, x_cur, x_blk = x_cur, x_blk, x_cur
            f_pre, f_cur, f_blk = f_cur, f_blk, f_cur
        delta = (xtol + rtol * abs(x_cur)) / 2.0
        s_bis = (x_blk - x_cur) / 2.0
        if f_cur == 0.0 or abs(s_bis) < delta:
            return x_cur
        if abs(s_pre) > delta and abs(f_cur) < abs(f_pre):
            if x_pre == x_blk:
                # secant through the two ends
                s_try = -f_cur * (x_cur - x_pre) / (f_cur - f_pre)
            else:
                # inverse quadratic through three points
                d_pre = (f_pre - f_cur) / (x_pre - x_cur)
                d_blk = (f_blk - f_cur) / (x_blk - x_cur)
                s_try = -f_cur * (f_blk * d_blk - f_pre * d_pre) / (d_blk * d_pre * (f_blk - f_pre))
            if 2.0 * abs(s_try) < min(abs(s_pre), 3.0 * abs(s_bis) - delta):
                s_pre, s_cur = s_cur, s_try
            else:
                s_pre = s_cur = s_bis
        else:
            s_pre = s_cur = s_bis
        x_pre, f_pre = x_cur, f_cur
        x_cur += s_cur if abs(s_cur) > delta else (delta if s_bis > 0.0 else -delta)
        f_cur = float(f(x_cur))
    raise RootNotConvergedError(f"no convergence in {maxiter} iterations (last estimate {x_cur!r})")
