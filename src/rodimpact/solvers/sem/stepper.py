"""One SEM run at a fixed step: the state, the two schemes' steps, the stop tests and the
result (the driver, :func:`rodimpact.solvers.sem.solve_sem`, chooses and checks the step)."""

from __future__ import annotations

import logging
import math
import time as _time
from typing import Any

import numpy as np

from rodimpact.analysis.signals import ZIGZAG_UNSTABLE, sawtooth_amplitude, zigzag_steps
from rodimpact.contact.law import contact_energies
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.sem.grid import CommensurateGrid
from rodimpact.solvers.sem.history import ForceHistory
from rodimpact.solvers.sem.record import run_histories
from rodimpact.solvers.sem.roots import brent_root
from rodimpact.solvers.sem.stability import paper_step_limit
from rodimpact.solvers.stepping import SEPARATION_ROUND_TRIPS, Outcome, StepHistory, limit_reached

__all__ = ["SEMRun", "run_fixed_step"]

log = logging.getLogger(__name__)

_MAX_WINDOW_SAMPLES = 400_000


class _Stepper(StepHistory):
    """State of one run: the histories every run records (its times and forces are the force
    history's nodes) and the scheme's step, ``step``."""

    def __init__(self, problem: ImpactProblem, options: Any, h: float) -> None:
        self.problem = problem
        self.options = options
        self.m = problem.mass_kg
        self.law = problem.contact
        # a law with memory: the curve of the largest approach so far, and its residual approach
        # (the dent) below which the bodies are apart; an elastic law is its own curve, with none
        self.branch = self.law.branch(0.0)
        self.peak = 0.0
        self.residual = 0.0
        self.h = h
        self.implicit = options.scheme == "implicit"
        rod = problem.rod
        grid = CommensurateGrid.of(h, rod.reflection_period, rod.reflection_sign, self.implicit)
        self.hist = ForceHistory(rod, linear=self.implicit, grid=grid)
        super().__init__(t=self.hist.t, force=self.hist.P, x=[0.0], w=[problem.velocity_m_s], u_end=[0.0], alpha=[0.0])
        self.in_contact = True
        self.n_events = 0

    # -- kinematics over a step with the scheme's force representation -------------------
    def _impactor(self, h: float, p_new: float) -> tuple[float, float]:
        x, v, p = self.x[-1], self.w[-1], self.hist.P[-1]
        if self.implicit:
            return (x + v * h - h * h * (p / 3.0 + p_new / 6.0) / self.m, v - 0.5 * h * (p + p_new) / self.m)
        return x + v * h - 0.5 * h * h * p / self.m, v - h * p / self.m

    def _free_approach(self, h: float) -> float:
        """Approach at t_last + h if the force reached zero there, less the residual approach
        (zero where the bodies touch; implicit scheme)."""
        x_new, _ = self._impactor(h, 0.0)
        known, _ = self.hist.rod_step_terms(h)
        return x_new - known - self.residual

    def _reached(self, alpha: float) -> None:
        """A node reached the approach ``alpha`` (m), beyond the largest so far: a law with
        memory goes on along the curve of the new largest approach."""
        self.peak = alpha
        self.branch = self.law.branch(alpha)
        self.residual = float(self.law.residual_approach(alpha))

    def _accept(self, t_new: float, p_new: float, u_new: float, x_new: float, v_new: float) -> None:
        self.hist.append(t_new, p_new, u_new)
        self.x.append(x_new)
        self.w.append(v_new)
        self.u_end.append(u_new)
        self.alpha.append(x_new - u_new)

    # -- the steps -----------------------------------------------------------------------
    def step(self, t_max: float, force_bound: float, max_nodes: int) -> None:
        """Step on until the driver has something to check.

        The paper scheme takes one step. The implicit scheme (:meth:`_step_implicit`) goes on
        from node to node while the bodies stay in contact: it returns after a node where a
        contact begins or ends, after a node with no force, and after the node that reaches
        one of the limits below, the driver then checking the run's state.

        Parameters
        ----------
        t_max : float
            Time horizon, s: no implicit node after the one that reaches it.
        force_bound : float
            No implicit node after one whose force exceeds it, N.
        max_nodes : int
            No implicit node after the one that makes the history longer than this.
        """
        if self.implicit:
            self._step_implicit(t_max, force_bound, max_nodes)
        else:
            self._step_paper()

    def _step_implicit(self, t_max: float, force_bound: float, max_nodes: int) -> None:
        """The implicit scheme's step: every node of an implicit run is made here, the same way.

        1. The next node: the next grid node (the grid's step from a grid node, the rest of
           it after an event node, :meth:`ForceHistory.next_step`), or ``h`` on without a grid.
        2. The rod end's displacement there, ``known + coef P_new`` (m; on the grid the
           constant-cost sum of :class:`~rodimpact.solvers.sem.grid.CommensurateGrid`,
           otherwise :meth:`ForceHistory.rod_step_terms`), and the approach ``a`` the
           bodies would reach with the force falling to zero over the step, m.
        3. Where the force starts or stops over the step (``a > alpha_p`` before a contact with
           a gap at the last node, ``a <= alpha_p`` in a contact with an approach beyond
           alpha_p at the last node; alpha_p the residual approach of a law with memory, 0 for
           an elastic law), the time where the approach crosses alpha_p (:meth:`_event_step`)
           becomes the node, with no force.
        4. Otherwise, with ``a > alpha_p``, the new force from the contact law's curve,
           ``alpha + b P(alpha) = a`` with ``b = h^2 / (6 m) + coef`` (``solve_step_force`` of
           the law's branch, the law itself when it is elastic; Newton's first guess the
           approach extrapolated from the last three nodes, quadratic); with ``a <= alpha_p`` no
           force. A node whose approach passes the largest so far takes the new branch
           (:meth:`_reached`).
        5. The impactor's exact motion under the force linear over the step, and the node
           accepted: time, force, impulse Q, W on a grid node, the motions and the approach.

        The last node is carried from one node to the next in local variables: inside a
        contact a node costs the law's root and a few dozen operations. Returning to the
        driver after every node gives the same numbers to the last bit (tested).

        Parameters
        ----------
        t_max, force_bound, max_nodes : float, float, int
            The limits of :meth:`step` (s, N, nodes).

        Notes
        -----
        This is the one place where an implicit run solves its contact law and accepts a
        node. Steps 2 and 5 do inline the operations of :meth:`ForceHistory.rod_step_terms` (on the
        grid) and :meth:`ForceHistory.append`, and of :meth:`_impactor` (which the event
        search and the paper scheme use), in the same order: ``tests/test_sem_grid.py``
        replays runs through the first two to the last bit. Through those two methods a node
        costs more: 9 shipped sem cases (model, thin_wire, long_rod_heavy, heavy_slow,
        seconds_contact, steel_on_rubber and three of table 2's, 1.4e5 nodes), each solved at
        the step its automatic choice gives, take 5.53e9 instructions here, 5.90e9 (+6.7 per
        cent) with ``rod_step_terms`` and 5.97e9 (+8.0 per cent) with ``append`` (valgrind
        --tool=cachegrind --cache-sim=no, the process without the solves subtracted); the
        former tight loop beside a general step took 5.54e9.
        """
        m, hist = self.m, self.hist
        memory = self.law.memory
        branch, peak, residual = self.branch, self.peak, self.residual
        grid = hist.grid
        T, P, Q, W = hist.t, hist.P, hist.Q, hist.W
        X, V, U, A = self.x, self.w, self.u_end, self.alpha
        impedance = hist.impedance
        if grid is not None:
            g_step, a0, a1, w_coef, lag = grid.step, grid.a0, grid.a1, grid.w_coef, grid.lag
            g_coef = grid.c / impedance
            g_b = g_step * g_step / (6.0 * m) + g_coef
        # the last node, and the approach at the two before it (None: there are fewer)
        t_n, p_n, q_n, x, v, alpha_n = T[-1], P[-1], Q[-1], X[-1], V[-1], A[-1]
        alpha_1 = A[-2] if len(A) > 1 else None
        alpha_2 = A[-3] if len(A) > 2 else None
        in_contact, on_grid, k, nodes = self.in_contact, hist.on_grid, len(W), len(T)
        newton = 0
        try:
            while True:
                if on_grid:  # Z u_{k+1} = a0 q_n + a1 p_n + c P_new + w_coef W_{k+1-lag}
                    h, t_new = g_step, k * g_step
                    known = a0 * q_n + a1 * p_n
                    if k >= lag:
                        known += w_coef * W[k - lag]
                    known /= impedance
                    coef, b = g_coef, g_b
                else:
                    h, t_new = hist.next_step(self.h)
                    known, coef = hist.rod_step_terms(h)
                    b = h * h / (6.0 * m) + coef
                a = x + v * h - h * h * (p_n / 3.0 + 0.0 / 6.0) / m - known
                touching = a > residual  # False for a NaN too
                event = None
                if touching != in_contact and (alpha_n < residual if touching else alpha_n > residual):
                    event = self._event_step(h)
                if touching and event is None:
                    guess = a if alpha_2 is None else 3.0 * (alpha_n - alpha_1) + alpha_2
                    _, p_new, iterations = branch.solve_step_force(a, b, guess)
                    newton += iterations
                    u_new = known + coef * p_new
                else:
                    if event is not None:
                        h, t_new = event, t_n + event
                        known, _ = hist.rod_step_terms(h)
                    p_new, u_new = 0.0, known
                x_new = x + v * h - h * h * (p_n / 3.0 + p_new / 6.0) / m
                v_new = v - 0.5 * h * (p_n + p_new) / m
                q_new = q_n + 0.5 * (p_n + p_new) * (t_new - t_n)
                T.append(t_new)
                P.append(p_new)
                Q.append(q_new)
                if grid is not None and (event is None or t_new == k * g_step):
                    W.append(0.5 * (impedance * u_new + q_new))
                    k += 1
                    if not on_grid:
                        hist.on_grid = on_grid = True
                elif on_grid:
                    hist.on_grid = on_grid = False
                X.append(x_new)
                V.append(v_new)
                U.append(u_new)
                alpha_2, alpha_1, alpha_n = alpha_1, alpha_n, x_new - u_new
                A.append(alpha_n)
                nodes += 1
                if memory and alpha_n > peak:
                    self._reached(alpha_n)
                    branch, peak, residual = self.branch, self.peak, self.residual
                if not touching:  # no force: a contact ends (at its event node or at this node)
                    if in_contact:
                        self.in_contact = False
                        self.ends.append(t_new)
                    return
                if not in_contact:  # a contact begins (at its event node or at the last node)
                    self.in_contact = True
                    self.starts.append(t_n if event is None else t_new)
                    return
                if t_new >= t_max or p_new > force_bound or nodes > max_nodes:
                    return
                t_n, p_n, q_n, x, v = t_new, p_new, q_new, x_new, v_new
        finally:
            self.n_newton += newton

    def _event_step(self, h: float) -> float | None:
        """Length of the step to the zero of the free approach inside (0, h), or None when
        round-off leaves no sign change (the event is then at the current node)."""
        if self._free_approach(0.0) * self._free_approach(h) >= 0.0:
            return None
        self.n_events += 1
        return brent_root(self._free_approach, 0.0, h, xtol=1e-15 * self.hist.t[-1] + 1e-300, rtol=8.9e-16)

    def _step_paper(self) -> None:
        h, t_new = self.hist.next_step(self.h)
        x_new, v_new = self._impactor(h, self.hist.P[-1])
        known, _ = self.hist.rod_step_terms(h)
        alpha_new = x_new - known
        p_new = self.branch.force(alpha_new)
        alpha_n, t_n = self.alpha[-1], self.hist.t[-1]
        self._accept(t_new, p_new, known, x_new, v_new)
        residual = self.residual  # the contact starts and ends where the approach crosses it
        if self.in_contact and alpha_new <= residual:
            self.in_contact = False
            frac = (alpha_n - residual) / (alpha_n - alpha_new) if alpha_n > alpha_new else 1.0
            self.ends.append(t_n + frac * h)
        elif not self.in_contact and alpha_new > residual:
            self.in_contact = True
            frac = (residual - alpha_n) / (alpha_new - alpha_n) if alpha_new > alpha_n else 0.0
            self.starts.append(t_n + frac * h)
        if self.law.memory and alpha_new > self.peak:
            self._reached(alpha_new)

    # -- termination -----------------------------------------------------------------------
    def rod_mean_velocity(self) -> float:
        """Mean velocity of the rod end after the force stopped (free end: rigid drift)."""
        rod = self.problem.rod
        if rod.far_end == "free" and math.isfinite(rod.length_m):
            return self.hist.Q[-1] / rod.mass_kg
        return 0.0

    def no_further_contact(self) -> bool:
        """True when, with no force, the impactor can never reach the rod again.

        After the force stops the fixed rod's end motion is periodic (period 4T) from 4T
        on, the free rod's is a drift plus a 2T-periodic motion. If the impactor moves away
        at least as fast as that mean motion and stays clear over the window of
        :data:`~rodimpact.solvers.stepping.SEPARATION_ROUND_TRIPS` round trips (8T), it stays
        clear for ever.
        """
        if self.w[-1] > self.rod_mean_velocity():
            return False
        period = self.problem.rod.reflection_period
        if not math.isfinite(period):
            return True
        window = SEPARATION_ROUND_TRIPS * period
        t0 = self.hist.t[-1]
        times = self._window_samples(t0, window, period)
        x = self.x[-1] + self.w[-1] * (times - t0)
        return bool(np.all(x - self.hist.rod_displacement(times) < self.residual))

    def _window_samples(self, t0: float, window: float, period: float) -> np.ndarray:
        """Times in (t0, t0 + window] at which to compare the impactor with the rod end.

        The end's displacement is a sum of the impulse Q at t - 2jT; Q is constant outside
        the force's nodes, so between the nodes shifted by whole round trips the gap is a
        polynomial of degree <= 2. Those shifted nodes, the midpoints between them and the
        window's end are the samples (uniform at the step when they would be more than
        ``_MAX_WINDOW_SAMPLES``).
        """
        nodes = np.asarray(self.hist.t)
        j = np.arange(max(0, math.floor((t0 - nodes[-1]) / period)), math.ceil((t0 + window) / period) + 1)
        lo = np.searchsorted(nodes, t0 - j * period, side="right")
        hi = np.searchsorted(nodes, t0 + window - j * period, side="right")
        counts = hi - lo
        total = int(np.sum(counts))
        if total <= _MAX_WINDOW_SAMPLES // 2:
            # every node in [lo_k, hi_k) shifted by j_k round trips, gathered without a loop
            first = np.cumsum(counts) - counts
            index = np.arange(total) + np.repeat(lo - first, counts)
            shifted = nodes[index] + np.repeat(j * period, counts)
            times = np.unique(np.concatenate([shifted, [t0, t0 + window]]))
            return np.concatenate([times[1:], 0.5 * (times[1:] + times[:-1])])
        n = min(_MAX_WINDOW_SAMPLES, max(2, int(math.ceil(window / self.h)) + 1))
        return t0 + np.linspace(0.0, window, n)[1:]


class SEMRun:
    """One run at a fixed step that can pause when its first contact has ended.

    The automatic step compares runs at two steps on their first contact only, then
    finishes the run it keeps: :meth:`first_contact` steps to the end of the first contact,
    :meth:`finish` goes on to the end and returns the result.
    """

    def __init__(self, problem: ImpactProblem, options: Any, h: float) -> None:
        self.st = _Stepper(problem, options, h)
        self.t_max = options.max_time_factor * problem.contact_time_estimate()
        # the contact energy never exceeds the impact energy, so P <= the rigid-rod contact force
        self.force_bound = 10.0 * problem.rigid_contact.peak_force_N
        self.checked_end = 0
        self.outcome: tuple[str, str] | None = None

    @property
    def n_steps(self) -> int:
        return len(self.st.hist.t) - 1

    def first_contact(self) -> tuple[float, float] | None:
        """Step to the end of the first contact: its duration, s, and its largest force, N.

        None when the run ended (failed or hit a limit) before that.
        """
        st = self.st
        if not st.ends:
            self._advance(first_end=True)
        if not st.ends:
            return None
        first_end = st.hist.t.index(st.ends[0]) if st.implicit else len(st.hist.t)
        return st.ends[0] - st.starts[0], max(st.hist.P[: first_end + 1])

    def finish(self, stations: tuple[float, ...], started: float, extra: dict) -> ImpactResult:
        """Step to the end of the run; the result, timed from ``started`` (perf_counter)."""
        status, message = self.outcome or self._advance(first_end=False)
        st = self.st
        if st.in_contact:
            st.starts = st.starts[: len(st.ends)]
        return _result(st, Outcome(status, message, _time.perf_counter() - started), stations, extra)

    def _advance(self, first_end: bool) -> tuple[str, str] | None:
        st, options, h = self.st, self.st.options, self.st.h
        problem = st.problem
        stepped = False
        while True:
            if stepped:
                st.step(self.t_max, self.force_bound, options.max_steps)
            stepped = True
            if len(st.ends) > self.checked_end and not st.in_contact:
                if first_end:
                    return None
                self.checked_end = len(st.ends)
                if st.no_further_contact():
                    self.outcome = "completed", f"{len(st.ends)} contact(s); no further contact possible"
                    return self.outcome
            limit = limit_reached(st.starts, st.ends, st.hist.t[-1], self.t_max, options)
            if limit:
                self.outcome = limit
                return limit
            if st.hist.P[-1] > self.force_bound:
                self.outcome = (
                    "failed",
                    (
                        f"diverged: the force {st.hist.P[-1]:.4g} N exceeds 10 times the rigid-rod "
                        f"{st.law.label or st.law.name} force {problem.rigid_contact.peak_force_N:.4g} N, which "
                        f"bounds it (energy); the step dt_s={h:.4g} s is unstable"
                    ),
                )
                return self.outcome
            if len(st.hist.t) > options.max_steps:
                self.outcome = (
                    ("truncated" if st.ends else "failed"),
                    (
                        f"step budget max_steps={options.max_steps} spent at t={st.hist.t[-1]:.6g} s with "
                        f"dt_s={h:.4g} s" + ("" if st.ends else " before the first contact ended")
                    ),
                )
                return self.outcome


def run_fixed_step(
    problem: ImpactProblem, options: Any, h: float, stations: tuple[float, ...], started: float, extra: dict
) -> ImpactResult:
    """One run at the fixed step ``h``."""
    return SEMRun(problem, options, h).finish(stations, started, extra)


def _scales(problem: ImpactProblem) -> dict[str, float]:
    """The case's scales, stored so that presentation never recomputes physics."""
    rigid = problem.rigid_contact
    return {
        **problem.contact.summary(),
        "rod_impedance_kg_s": problem.rod.impedance,
        "rigid_contact_time_s": rigid.contact_time_s,
        "rigid_contact_force_N": rigid.peak_force_N,
        "paper_step_limit_s": paper_step_limit(problem),
    }


def _result(
    st: _Stepper, outcome: Outcome, stations: tuple[float, ...] = (), extra_summary: dict | None = None
) -> ImpactResult:
    """The run's result. Its energy balance is the work done on the rod, with the scheme's own
    force representation, against the impactor's loss; a run fails on a force or balance that
    is not finite and, beyond ``energy_tolerance``, on the balance itself."""
    status, message = outcome.status, outcome.message
    nodes = st.nodes()
    p, u = nodes.force, nodes.u_end
    mean_force = 0.5 * (p[1:] + p[:-1]) if st.implicit else p[:-1]
    rod_work = np.concatenate([[0.0], np.cumsum(mean_force * np.diff(u))])
    rod_energy = float(rod_work[-1])
    problem = st.problem
    series, extra = run_histories(st.m, st.law, st.hist, problem.rod.length_m, nodes, stations, rod_work)
    ke_in = problem.kinetic_energy_J
    ke_out = 0.5 * problem.mass_kg * st.w[-1] ** 2
    # what the contact still stores and what it dissipated (a law with memory) at the last node
    stored, dissipated = contact_energies(problem.contact, nodes.alpha)
    contact_left = float(stored[-1] + dissipated[-1])
    energy_error = (ke_in - ke_out - rod_energy - contact_left) / ke_in
    sawtooth = sawtooth_amplitude(p)
    zigzag = zigzag_steps(p)
    if not (np.all(np.isfinite(p)) and math.isfinite(energy_error)):
        status, message = "failed", "non-finite force or energy balance (the scheme diverged)"
    elif status != "failed" and abs(energy_error) > st.options.energy_tolerance:
        kind = "gained" if energy_error < 0 else "lost"
        status, message = (
            "failed",
            (
                f"energy balance off: {abs(energy_error):.3g} of the impact energy {kind}, beyond "
                f"energy_tolerance={st.options.energy_tolerance:.3g}"
                + (
                    f"; the force zig-zags step to step over {zigzag} steps (amplitude {sawtooth:.2f}): unstable step"
                    if zigzag >= ZIGZAG_UNSTABLE
                    else ""
                )
            ),
        )
    log.info(
        "SEM %s: %s (%s), %d steps, contact time %.6g s",
        st.options.scheme,
        status,
        message,
        len(nodes.time) - 1,
        (st.ends[0] - st.starts[0]) if st.ends else math.nan,
    )
    return st.result(
        nodes,
        Outcome(status, message, outcome.wall_time_s),
        scheme=st.options.scheme,
        dt_s=st.h,
        energy_error=float(energy_error),
        rod_energy_J=rod_energy,
        n_events=st.n_events,
        extra={
            **extra,
            "sawtooth_amplitude": sawtooth,
            "zigzag_steps": zigzag,
            **_scales(problem),
            **(extra_summary or {}),
        },
        extra_series=series,
    )
