"""Steps commensurate with the wave round trip: the rod's delayed sum at constant cost.

The rod end's displacement is a sum over the wave's round trips 2T so far,

    Z u(t) = sum_j c_j Q(t - 2 j T),    c_0 = 1,  c_j = 2 s^j,

with Q the impulse of the contact force and s the far end's reflection sign. Written with

    W(t) = sum_{j >= 0} s^j Q(t - 2 j T) = Q(t) + s W(t - 2T),    Z u = 2 W - Q,

a step needs W one round trip back. When the step h and 2T are commensurate, that
time is a node of the grid t_k = k h, where W is known:

* ``2T = N h``: Z u_{k+1} = Q_{k+1} + 2 s W_{k+1-N};
* ``h = M 2T``: the M delayed times inside the step are summed in closed form for the
  step's force (held or linear), and Z u_{k+1} = ... + 2 s^M W_k.

Either way a step costs O(1) however many round trips have passed, and the result is the
exact sum (to rounding), not an approximation. W_k itself is (Z u_k + Q_k) / 2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["CommensurateGrid", "commensurate_step"]

#: Relative mismatch below which a step is taken as commensurate with the round trip.
COMMENSURATE_RTOL = 1e-9


def commensurate_step(step: float, period: float) -> float:
    """The largest step not above ``step`` that is commensurate with ``period`` (2T), s.

    2T / N for the smallest N >= 1 with 2T / N <= step, or M 2T for the largest M >= 1 with
    M 2T <= step. An infinite period (no reflection) leaves the step as it is.
    """
    if not math.isfinite(period):
        return step
    if step < period:
        return period / math.ceil(period / step * (1.0 - COMMENSURATE_RTOL))
    return period * math.floor(step / period * (1.0 + COMMENSURATE_RTOL))


@dataclass(frozen=True)
class CommensurateGrid:
    """The constant coefficients of a step on a grid commensurate with the round trip.

    On the step from grid node k to k + 1, with q_n, p_n the impulse and force at node k
    and p the new force,

        Z u_{k+1} = a0 q_n + a1 p_n + c p + w_coef W_{k+1-lag}

    (W of a negative index is 0). Built by :meth:`of`.
    """

    step: float
    per_period: int
    per_step: int
    a0: float
    a1: float
    c: float
    w_coef: float
    lag: int

    @classmethod
    def of(cls, step: float, period: float, sign: int, linear: bool) -> CommensurateGrid | None:
        """The grid of ``step`` for a round trip ``period`` (None when they are not commensurate).

        Parameters
        ----------
        step, period : float
            The time step h and the round trip 2T, s.
        sign : int
            The far end's reflection sign s (-1 fixed, +1 free).
        linear : bool
            Force linear over a step (True) or held at its left value (False).
        """
        if not (math.isfinite(period) and step > 0.0):
            return None
        if step <= period * (1.0 + COMMENSURATE_RTOL):
            n = round(period / step)
            if n < 1 or abs(n * step - period) > COMMENSURATE_RTOL * period:
                return None
            return cls(
                step,
                n,
                1 if n == 1 else 0,
                1.0,
                0.5 * step if linear else step,
                0.5 * step if linear else 0.0,
                2.0 * sign,
                n,
            )
        m = round(step / period)
        if abs(m * period - step) > COMMENSURATE_RTOL * step:
            return None
        # the delayed times t_{k+1} - 2jT, j < m, lie inside the step at d_j = h (m - j) / m
        s0 = s1 = s2 = 0.0
        for j in range(m):
            weight = float(sign**j)
            d = step * (m - j) / m
            s0 += weight
            s1 += weight * d
            s2 += weight * d * d
        if linear:
            a1, c = 2.0 * s1 - s2 / step - 0.5 * step, s2 / step - 0.5 * step
        else:
            a1, c = 2.0 * s1 - step, 0.0
        return cls(step, 0, m, 2.0 * s0 - 1.0, a1, c, 2.0 * float(sign**m), 1)
