"""The contact-force history and the rod's end displacement it causes.

The force is stored at nodes t_i (not necessarily uniform) and is either piecewise linear
between nodes (``linear=True``) or held at its left-node value (``linear=False``, the
paper's rectangle rule). The impulse Q(t) = integral_0^t P is then piecewise quadratic
(or linear) and is evaluated *exactly* at any time, so the rod's delayed terms

    Z u(t) = sum_j c_j Q(t - 2 j T)

use the true delays 2jT, never rounded to the grid. On a grid commensurate with the round
trip (:mod:`.grid`) a step costs O(1): the sum is carried by W(t) = Q(t) + s W(t - 2T) at
the grid's nodes. Any other step (a fixed step that is not commensurate, the short steps
that put a contact's start or end on a node and return to the grid) sums the terms, one
binary search each, vectorised once they are many.
"""

from __future__ import annotations

import math
from bisect import bisect_right

import numpy as np
from numpy.typing import NDArray

from rodimpact.model.responses import Rod
from rodimpact.solvers.sem.grid import CommensurateGrid

__all__ = ["ForceHistory"]

#: Delayed terms beyond which a step's sum is evaluated with numpy rather than term by term.
_VECTOR_TERMS = 48


class ForceHistory:
    """Nodes of the contact force and the exact rod response to it.

    Parameters
    ----------
    rod : Rod
        The rod (its impedance Z, round trip 2T and reflection sign s).
    linear : bool
        Piecewise-linear force (True) or left-held rectangles (False).
    grid : CommensurateGrid, optional
        A step commensurate with the round trip: nodes at its multiples k h carry W, and a
        step between two of them costs O(1). Other nodes (events) may lie between.
    """

    def __init__(self, rod: Rod, linear: bool, grid: CommensurateGrid | None = None) -> None:
        self.linear = linear
        self.grid = grid
        self.W: list[float] = [0.0]  # W(k h) at the grid's nodes k = 0, 1, ...
        self.on_grid = grid is not None
        self._cache: tuple[int, NDArray, NDArray, NDArray] | None = None
        self.impedance = rod.impedance
        self.wave_speed = rod.wave_speed
        self.length = rod.length_m
        self.period = rod.reflection_period
        self.sign = rod.reflection_sign
        self.t: list[float] = [0.0]
        self.P: list[float] = [0.0]
        self.Q: list[float] = [0.0]

    @classmethod
    def of_nodes(cls, rod: Rod, linear: bool, t: NDArray[np.float64], force: NDArray[np.float64]) -> ForceHistory:
        """The history of a finished run's force nodes (t[0] = 0, P[0] = 0), s and N."""
        history = cls(rod, linear)
        for time, value in zip(np.asarray(t, dtype=float)[1:], np.asarray(force, dtype=float)[1:]):
            history.append(float(time), float(value))
        return history

    # -- nodes -------------------------------------------------------------------------
    def next_step(self, h: float) -> tuple[float, float]:
        """The next node for the nominal step ``h``: (step, time), s.

        On a grid, the step to the next grid node (``h`` itself from a grid node, the rest
        of the grid's step after an event node), and that node's exact time k h.
        """
        if self.grid is None:
            return h, self.t[-1] + h
        t_grid = len(self.W) * self.grid.step
        return (self.grid.step if self.on_grid else t_grid - self.t[-1]), t_grid

    def append(self, t: float, force: float, displacement: float | None = None) -> None:
        """Add the node (t, P); t must exceed the last node's time.

        On a grid, a node at the next grid time also records W from the rod end's
        ``displacement`` there, m (required for such a node). The implicit scheme's step
        (:mod:`.stepper`) appends its nodes by these same operations inline, for speed
        (``tests/test_sem_grid.py`` replays its runs through this method to the last bit).
        """
        h = t - self.t[-1]
        mean = 0.5 * (self.P[-1] + force) if self.linear else self.P[-1]
        q = self.Q[-1] + mean * h
        self.t.append(t)
        self.P.append(force)
        self.Q.append(q)
        if self.grid is not None:
            self.on_grid = t == len(self.W) * self.grid.step
            if self.on_grid:
                self.W.append(0.5 * (self.impedance * displacement + q))

    def _arrays(self) -> tuple[NDArray, NDArray, NDArray]:
        """Views of the nodes as arrays, kept in step with the lists (amortised O(1) a node)."""
        n = len(self.t)
        if self._cache is None or len(self._cache[1]) < n:
            capacity = max(1024, 2 * n)
            grown = tuple(np.empty(capacity) for _ in range(3))
            done = 0
            if self._cache is not None:
                done = self._cache[0]
                for new, old in zip(grown, self._cache[1:]):
                    new[:done] = old[:done]
            self._cache = (done, *grown)
        done, t, P, Q = self._cache
        if done < n:
            t[done:n] = self.t[done:n]
            P[done:n] = self.P[done:n]
            Q[done:n] = self.Q[done:n]
            self._cache = (n, t, P, Q)
        return t[:n], P[:n], Q[:n]

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
        tau = np.asarray(tau, dtype=float)
        t, P, Q = self._arrays()
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
        t, P, _ = self._arrays()
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

        Notes
        -----
        The grid's step from a grid node costs O(1) (:class:`.CommensurateGrid`); the implicit
        scheme's step (:mod:`.stepper`) does that sum by these same operations inline, for
        speed (``tests/test_sem_grid.py`` checks its runs against this method to the last bit).
        """
        grid = self.grid
        if grid is not None and self.on_grid and h == grid.step:
            lag = len(self.W) - grid.lag
            known = grid.a0 * self.Q[-1] + grid.a1 * self.P[-1]
            if lag >= 0:
                known += grid.w_coef * self.W[lag]
            return known / self.impedance, grid.c / self.impedance
        t_n, p_n, q_n = self.t[-1], self.P[-1], self.Q[-1]
        t_new = t_n + h
        known, coef = 0.0, 0.0
        j = 0
        while True:
            tau = t_new - j * self.period if j else t_new
            if tau <= t_n:
                break
            c = self._coefficient(j)
            d = tau - t_n  # the delayed time falls inside the current step
            if self.linear:
                known += c * (q_n + d * p_n - 0.5 * d * d * p_n / h)
                coef += c * 0.5 * d * d / h
            else:
                known += c * (q_n + d * p_n)
            j += 1
            if not math.isfinite(self.period):
                break
        if math.isfinite(self.period):
            known += self._past_sum(t_new, j)
        return known / self.impedance, coef / self.impedance

    def _past_sum(self, t_new: float, j0: int) -> float:
        """sum_{j >= j0} c_j Q(t_new - 2 j T) over the delayed times in the past (> 0)."""
        count = int(t_new // self.period) - j0 + 1
        if count <= 0:
            return 0.0
        if count <= _VECTOR_TERMS:
            total = 0.0
            j = j0
            while True:
                tau = t_new - j * self.period
                if tau <= 0.0:
                    return total
                total += self._coefficient(j) * self.impulse(tau)
                j += 1
        j = np.arange(j0, j0 + count + 1)
        tau = t_new - j * self.period
        coefficient = np.where(j == 0, 1.0, 2.0 * np.where(j % 2 == 1, float(self.sign), 1.0))
        return float(np.sum(coefficient * self.impulse_array(tau)))

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

    def velocity_at(self, x: float, times: NDArray[np.float64]) -> NDArray[np.float64]:
        """Axial velocity du/dt at x (positive away from the struck end), m/s.

        du/dt = (1/Z) sum over waves of sign * P(t - delay), the time derivative of
        :meth:`displacement_at`. At a free far end x = l the waves towards it and back arrive
        together with the same sign, v(l, t) = (2/Z) sum_j P(t - (2j + 1) l/a); at a fixed
        one they cancel.
        """
        times = np.asarray(times, dtype=float)
        total = np.zeros_like(times)
        for sign, delay, _ in self._waves(x, times):
            total += sign * self.force_array(times - delay)
        return total / self.impedance

    def rod_displacement(self, times: NDArray[np.float64]) -> NDArray[np.float64]:
        """End displacement u at any times (force beyond the last node held), m."""
        times = np.asarray(times, dtype=float)
        if not math.isfinite(self.period):
            return self.impulse_array(times) / self.impedance
        n_max = int(np.max(times, initial=0.0) // self.period) + 1
        j = np.arange(n_max + 1)
        coefficient = np.where(j == 0, 1.0, 2.0 * np.where(j % 2 == 1, float(self.sign), 1.0))
        tau = times[:, None] - j[None, :] * self.period
        return (self.impulse_array(tau.ravel()).reshape(tau.shape) @ coefficient) / self.impedance
