"""The contact-force history and the rod's end displacement it causes.

The force is stored at nodes t_i (not necessarily uniform) and is either piecewise linear
between nodes (``linear=True``) or held at its left-node value (``linear=False``, the
paper's rectangle rule). The impulse Q(t) = integral_0^t P is then piecewise quadratic
(or linear) and is evaluated *exactly* at any time, so the rod's delayed terms

    Z u(t) = sum_j c_j Q(t - 2 j T)

use the true delays 2jT, never rounded to the grid. A term costs one binary search:
the cost of a step is O(number of reflections so far), independent of the step count.
"""

from __future__ import annotations

import math
from bisect import bisect_right

import numpy as np
from numpy.typing import NDArray

from rodimpact.model.responses import Rod

__all__ = ["ForceHistory"]


class ForceHistory:
    """Nodes of the contact force and the exact rod response to it.

    Parameters
    ----------
    rod : Rod
        The rod (its impedance Z, round trip 2T and reflection sign s).
    linear : bool
        Piecewise-linear force (True) or left-held rectangles (False).
    """

    def __init__(self, rod: Rod, linear: bool) -> None:
        self.linear = linear
        self.impedance = rod.impedance
        self.wave_speed = rod.wave_speed
        self.length = rod.length_m
        self.period = rod.reflection_period
        self.sign = rod.reflection_sign
        self.t: list[float] = [0.0]
        self.P: list[float] = [0.0]
        self.Q: list[float] = [0.0]

    # -- nodes -------------------------------------------------------------------------
    def append(self, t: float, force: float) -> None:
        """Add the node (t, P); t must exceed the last node's time."""
        h = t - self.t[-1]
        mean = 0.5 * (self.P[-1] + force) if self.linear else self.P[-1]
        self.t.append(t)
        self.P.append(force)
        self.Q.append(self.Q[-1] + mean * h)

    def impulse(self, tau: float) -> float:
        """Q(tau) for 0 <= tau <= t_last (0 for tau <= 0), N s."""
        if tau <= 0.0:
            return 0.0
        t = self.t
        i = bisect_right(t, tau) - 1
        if i >= len(t) - 1:
            return self.Q[-1] + (tau - t[-1]) * self.P[-1]
        dt = tau - t[i]
        if not self.linear:
            return self.Q[i] + dt * self.P[i]
        return self.Q[i] + dt * (self.P[i] + 0.5 * dt * (self.P[i + 1] - self.P[i]) / (t[i + 1] - t[i]))

    def impulse_array(self, tau: NDArray[np.float64]) -> NDArray[np.float64]:
        """Vectorised :meth:`impulse` (times beyond the last node hold its force)."""
        t = np.asarray(self.t)
        P = np.asarray(self.P)
        Q = np.asarray(self.Q)
        i = np.clip(np.searchsorted(t, tau, side="right") - 1, 0, len(t) - 1)
        dt = tau - t[i]
        out = Q[i] + dt * P[i]
        if self.linear:
            inner = i < len(t) - 1
            j = i[inner]
            out[inner] += 0.5 * dt[inner] ** 2 * (P[j + 1] - P[j]) / (t[j + 1] - t[j])
        return np.where(tau > 0.0, out, 0.0)

    def force_array(self, tau: NDArray[np.float64]) -> NDArray[np.float64]:
        """The force at any times, with the history's own interpolation (0 before t = 0)."""
        tau = np.asarray(tau, dtype=float)
        t = np.asarray(self.t)
        P = np.asarray(self.P)
        if self.linear:
            return np.where(tau > 0.0, np.interp(tau, t, P), 0.0)
        i = np.clip(np.searchsorted(t, tau, side="right") - 1, 0, len(t) - 1)
        return np.where(tau > 0.0, P[i], 0.0)

    # -- rod ---------------------------------------------------------------------------
    def _coefficient(self, j: int) -> float:
        return 1.0 if j == 0 else 2.0 * self.sign**j

    def rod_step_terms(self, h: float) -> tuple[float, float]:
        """End displacement at t_last + h as ``known + coef * P_new``.

        Parameters
        ----------
        h : float
            Step from the last node, s (> 0). The force over the step is linear from the
            last node's value to the unknown P_new (``linear``), or held (then coef = 0).

        Returns
        -------
        known, coef : float
            u(t_last + h) = known + coef * P_new, in m and m/N.
        """
        t_n, p_n, q_n = self.t[-1], self.P[-1], self.Q[-1]
        t_new = t_n + h
        known, coef = 0.0, 0.0
        j = 0
        while True:
            tau = t_new - j * self.period if j else t_new
            if tau <= 0.0:
                break
            c = self._coefficient(j)
            if tau > t_n:  # the delayed time falls inside the current step
                d = tau - t_n
                if self.linear:
                    known += c * (q_n + d * p_n - 0.5 * d * d * p_n / h)
                    coef += c * 0.5 * d * d / h
                else:
                    known += c * (q_n + d * p_n)
            else:
                known += c * self.impulse(tau)
            j += 1
            if not math.isfinite(self.period):
                break
        return known / self.impedance, coef / self.impedance

    def _waves(self, x: float, times: NDArray[np.float64]) -> list[tuple[float, float, float]]:
        """(sign, delay, direction) of every wave that has reached x by max(times).

        d'Alembert with reflections: waves travelling towards the far end (direction +1)
        arrive with delay (2jl + x)/a and sign s^j; those travelling back (direction -1)
        with delay (2(j+1)l - x)/a and sign s^(j+1).
        """
        a, length = self.wave_speed, self.length
        waves = [(1.0, x / a, 1.0)]
        if not math.isfinite(length):
            return waves
        horizon = float(np.max(times, initial=0.0))
        j = 0
        while True:
            back = (2 * (j + 1) * length - x) / a
            if back > horizon:
                break
            waves.append((float(self.sign ** (j + 1)), back, -1.0))
            forward = (2 * (j + 1) * length + x) / a
            if forward > horizon:
                break
            waves.append((float(self.sign ** (j + 1)), forward, 1.0))
            j += 1
        return waves

    def displacement_at(self, x: float, times: NDArray[np.float64]) -> NDArray[np.float64]:
        """Axial displacement u(x, t) of the cross-section at distance x from the struck end, m.

        u = (1/Z) sum over waves of sign * Q(t - delay).
        """
        times = np.asarray(times, dtype=float)
        total = np.zeros_like(times)
        for sign, delay, _ in self._waves(x, times):
            total += sign * self.impulse_array(times - delay)
        return total / self.impedance

    def strain_at(self, x: float, times: NDArray[np.float64]) -> NDArray[np.float64]:
        """Axial strain du/dx at x (negative in compression), dimensionless.

        du/dx = -(1/(E S)) sum over waves of sign * direction * P(t - delay).
        """
        times = np.asarray(times, dtype=float)
        total = np.zeros_like(times)
        for sign, delay, direction in self._waves(x, times):
            total -= sign * direction * self.force_array(times - delay)
        return total / (self.impedance * self.wave_speed)

    def rod_displacement(self, times: NDArray[np.float64]) -> NDArray[np.float64]:
        """End displacement u at any times (force beyond the last node held), m."""
        times = np.asarray(times, dtype=float)
        total = self.impulse_array(times)
        if math.isfinite(self.period):
            n_max = int(np.max(times, initial=0.0) // self.period) + 1
            for j in range(1, n_max + 1):
                total += self._coefficient(j) * self.impulse_array(times - j * self.period)
        return total / self.impedance
