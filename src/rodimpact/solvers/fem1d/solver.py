"""``fem1d``: a rigid impactor with the case's contact law on a 1D finite-element bar.

Newmark's average-acceleration rule (beta = 1/4, gamma = 1/2) for the bar and for the
impactor: it conserves the energy of the linear part exactly, and is unconditionally
stable. With K_eff = K + (4/h^2) M factorised once, the new displacement is

    u_{n+1} = u_pred + P_{n+1} g,   g = K_eff^-1 e0,

so the approach is affine in the new force, alpha_{n+1} = A - B P_{n+1} (B > 0), and the
contact law is solved as one scalar equation, exactly as in the SEM (the law's
``solve_step``). Contact ends and starts are located between steps by the root of the
cubic Hermite interpolant of the approach.
"""

from __future__ import annotations

import logging
import math
import time as _time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from rodimpact.model.gauges import Gauge
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.fem1d.bar import BarModel, banded_solver, bar_model, end_vector, row_blocks
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.field import FieldGrid, field_datasets
from rodimpact.solvers.gauge_series import (
    checked_gauges,
    far_end_datasets,
    gauge_datasets,
    record_until_s,
    recorded_reach_m,
)
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.stepping import (
    SEPARATION_ROUND_TRIPS,
    Outcome,
    StepHistory,
    contact_series,
    energy_error,
    limit_reached,
)

__all__ = ["solve_fem1d"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class _Setup:
    """What one run builds before stepping: the bar, the step and the Newmark operators."""

    bar: BarModel
    n_elements: int
    h: float
    warnings: tuple[str, ...]
    stations_m: tuple[float, ...]
    gauges: tuple[Gauge, ...]
    solve: Any  # K_eff^-1 (a banded Cholesky factor's solve)
    g: NDArray[np.float64]  # K_eff^-1 e0
    static_end: float  # end compliance of the fixed bar, m/N (inf for a free far end)
    rod_momentum: NDArray[np.float64]  # momentum of the rod = rod_momentum @ v


@dataclass(eq=False)
class _History(StepHistory):
    """The histories every run records, and fem1d's own: the stations' displacement and strain,
    the gauges' strain, the far end's velocity and the rod's kinetic and strain energies."""

    station_u: list[NDArray[np.float64]] = field(default_factory=list)
    station_e: list[NDArray[np.float64]] = field(default_factory=list)
    gauge_e: list[NDArray[np.float64]] = field(default_factory=list)
    far_v: list[float] = field(default_factory=list)
    rod_kinetic: list[float] = field(default_factory=list)
    rod_strain: list[float] = field(default_factory=list)


def _hermite_root(a0: float, a1: float, d0: float, d1: float, h: float) -> float:
    """Zero in (0, h) of the cubic Hermite interpolant of values a0, a1 and slopes d0, d1."""

    def cubic(s: float) -> float:
        q = s / h
        return (
            (2 * q**3 - 3 * q**2 + 1) * a0
            + (q**3 - 2 * q**2 + q) * h * d0
            + (-2 * q**3 + 3 * q**2) * a1
            + (q**3 - q**2) * h * d1
        )

    if cubic(0.0) * cubic(h) > 0:  # interpolant without a sign change: fall back to linear
        return h * a0 / (a0 - a1)
    return brentq(cubic, 0.0, h, xtol=1e-14 * h)


def _setup(
    problem: ImpactProblem,
    options: FEM1DOptions,
    stations: Sequence[float],
    field: FieldGrid | None = None,
    gauges: Sequence[Gauge] = (),
    far_end: bool = False,
) -> _Setup:
    n_el, h, warnings = options.resolve(problem)
    rod = problem.rod
    gauges = checked_gauges(gauges, rod.length_m)
    xs = tuple(float(s) * rod.length_m for s in stations)
    bar = bar_model(
        rod,
        options.element,
        n_el,
        xs,
        () if field is None else field.positions(rod.length_m),
        [(g.station_m, g.gauge_length_m) for g in gauges],
        far_end,
    )
    M, K = bar.mass, bar.stiffness
    solve = banded_solver(K + (4.0 / h**2) * M)
    e0 = end_vector(bar)
    static_end = banded_solver(K)(e0)[bar.end] if rod.far_end == "fixed" else math.inf
    return _Setup(
        bar=bar,
        n_elements=n_el,
        h=h,
        warnings=tuple(warnings),
        stations_m=xs,
        gauges=gauges,
        solve=solve,
        g=solve(e0),
        static_end=static_end,
        rod_momentum=M.T @ np.ones(M.shape[0]),
    )


def solve_fem1d(
    problem: ImpactProblem,
    options: FEM1DOptions | None = None,
    stations: Sequence[float] = (),
    field: FieldGrid | None = None,
    gauges: Sequence[Gauge] = (),
    far_end_velocity: bool = False,
) -> ImpactResult:
    """Solve the impact with the rod as a finite-element bar.

    Parameters
    ----------
    problem : ImpactProblem
        The impact (the same contact law as the SEM).
    options : FEM1DOptions, optional
        Discretisation; defaults to ``FEM1DOptions()``.
    stations : sequence of float
        Fractions of the rod length, from the struck end, where the displacement and the
        strain are recorded (``station_displacement``, ``station_strain``, shape (n, k)).
    field : FieldGrid, optional
        Record the strain over the whole rod on this grid (:attr:`ImpactResult.field`), linear
        in time between steps. A completed run then keeps stepping the bar alone (the impactor
        never returns) until the grid's last time, one or more round trips after the last
        contact; its histories and summary stop where they stop without a field. None
        (default) records none, and the run is the same.
    gauges : sequence of Gauge
        Strain gauges (:class:`~rodimpact.model.gauges.Gauge`): the mean strain over each,
        (u(x + g/2) - u(x - g/2)) / g from the bar's displacement at the gauge's ends (a point
        gauge: du/dx as at a station), at every step (``gauge_strain``, shape (n, k)).
    far_end_velocity : bool
        Also record the velocity of the bar's last node x = l (Newmark's velocity;
        ``far_end_velocity``, m/s; zero at a fixed far end).

        With gauges or the far end's velocity, a run that has proven that no further contact is
        possible keeps stepping, past the time limit, until every wave its last contact sent has
        passed the farthest section recorded
        (:func:`~rodimpact.solvers.gauge_series.record_until_s`; the summary's
        ``recorded_until_s``). Its contact results (and the energy balance, taken at the node
        where the proof came) are those of the run without them.

    Returns
    -------
    ImpactResult
        As the SEM's, plus the station histories and the energies (impactor, contact, rod
        kinetic and strain) as extra series, and the element count in ``extra``.

    Raises
    ------
    rodimpact.solvers.options.OptionError
        The options cannot resolve the contact (too few elements, too long a step).
    rodimpact.model.gauges.GaugeError
        A gauge is off the rod.
    """
    options = FEM1DOptions() if options is None else options
    started = _time.perf_counter()
    setup = _setup(problem, options, stations, field, gauges, far_end_velocity)
    for warning in setup.warnings:
        log.warning(warning)
    bar, h, solve, g = setup.bar, setup.h, setup.solve, setup.g
    rod, m, law = problem.rod, problem.mass_kg, problem.contact
    M, K = bar.mass, bar.stiffness
    b_rod = g[bar.end]
    # what a step records of u (the probes, K u) and of v (M v, the far end), one product each
    of_u, (at_station, at_strain, at_gauge, at_k) = row_blocks(
        bar.station_probes, bar.strain_probes, bar.gauge_probes, K
    )
    of_v, (at_m, at_far) = row_blocks(M, bar.far_probe)

    d = M.shape[0]
    u, v, a = np.zeros(d), np.zeros(d), np.zeros(d)
    x, w, p, alpha = 0.0, problem.velocity_m_s, 0.0, 0.0
    hist = _History(
        t=[0.0],
        force=[0.0],
        x=[0.0],
        w=[w],
        u_end=[0.0],
        alpha=[0.0],
        station_u=[bar.station_probes @ u],
        station_e=[bar.strain_probes @ u],
        gauge_e=[] if bar.gauge_probes is None else [bar.gauge_probes @ u],
        far_v=[] if bar.far_probe is None else [float((bar.far_probe @ v)[0])],
        rod_kinetic=[0.0],
        rod_strain=[0.0],
    )
    recorder = None if field is None else _FieldRecorder(field, rod, bar.field_probes, u)
    starts, ends, AL = hist.starts, hist.ends, hist.alpha
    in_contact = True
    # a law with memory: the curve of the largest approach so far and its residual approach (the
    # dent), below which the bodies are apart; an elastic law is its own curve, with none
    branch, peak, residual = law.branch(0.0), 0.0, 0.0
    t_max = options.max_time_factor * problem.contact_time_estimate()
    reach = recorded_reach_m(setup.gauges, far_end_velocity, rod.length_m)
    # the node at which no further contact was proven (where a run that records nothing ends)
    finished: int | None = None
    status, message = "failed", ""
    t = 0.0
    while True:
        u_pred = _free_displacement(solve, M, u, v, a, h)
        big_a = x + h * w - h * h * p / (4.0 * m) - u_pred[bar.end]
        big_b = h * h / (4.0 * m) + b_rod
        if big_a > residual:
            guess = 2.0 * AL[-1] - AL[-2] if len(AL) > 1 else big_a
            alpha_new, iterations = branch.solve_step(big_a, big_b, guess)
            hist.n_newton += iterations
            p_new = branch.force(alpha_new)
        else:
            alpha_new, p_new = big_a, 0.0
        u_new = u_pred + p_new * g
        v_new, a_new = _rates(u, v, a, u_new, h)
        x_new = x + h * w - h * h * (p + p_new) / (4.0 * m)
        w_new = w - h * (p + p_new) / (2.0 * m)
        if (p_new > 0.0) != in_contact:  # a contact ends or begins inside this step
            crossing = t + _hermite_root(
                AL[-1] - residual, alpha_new - residual, w - v[bar.end], w_new - v_new[bar.end], h
            )
            (starts if p_new > 0.0 else ends).append(crossing)
            in_contact = p_new > 0.0
        u, v, a, x, w, p, alpha = u_new, v_new, a_new, x_new, w_new, p_new, alpha_new
        if law.memory and alpha > peak:
            branch, peak = law.branch(alpha), alpha
            residual = float(law.residual_approach(alpha))
        t += h
        hist.t.append(t)
        hist.force.append(p)
        hist.x.append(x)
        hist.w.append(w)
        hist.u_end.append(u[bar.end])
        AL.append(alpha)
        u_products, v_products = of_u @ u, of_v @ v
        hist.station_u.append(u_products[at_station].copy())
        hist.station_e.append(u_products[at_strain].copy())
        if at_gauge is not None:
            hist.gauge_e.append(u_products[at_gauge].copy())
        if at_far is not None:
            hist.far_v.append(float(v_products[at_far][0]))
        hist.rod_kinetic.append(0.5 * v @ v_products[at_m])
        hist.rod_strain.append(0.5 * u @ u_products[at_k])
        if recorder is not None:
            recorder.record(t, u)
        if in_contact:
            finished = None  # a contact after the proof (not for a sound one): the run goes on as ever
        elif finished is None and (
            ends
            and _no_further_contact(
                rod,
                x - residual,
                w,
                hist.rod_kinetic[-1] + hist.rod_strain[-1],
                setup.static_end,
                t - ends[-1],
                setup.rod_momentum @ v,
            )
        ):
            finished = len(hist.t) - 1
            status, message = "completed", f"{len(ends)} contact(s); no further contact possible"
        if finished is not None:
            # a run that records gauges or the far end goes on, without the time limit, until every
            # wave the last contact sent has passed the farthest section it records
            if reach is None or t >= record_until_s(ends[-1], reach, rod.wave_speed):
                break
            continue
        limit = limit_reached(starts, ends, t, t_max, options)
        if limit:
            status, message = limit
            break
    field_data = {}
    if recorder is not None:
        times = field.times(recorder.transit, status, ends, t)
        while status == "completed" and recorder.count < len(times):
            u_new = _free_displacement(solve, M, u, v, a, h)  # the bar alone: no force
            v, a = _rates(u, v, a, u_new, h)
            u = u_new
            t += h
            recorder.record(t, u)
        field_data = recorder.datasets(times)
    outcome = Outcome(status, message, _time.perf_counter() - started)
    recorded_until = (
        record_until_s(ends[-1], reach, rod.wave_speed) if reach is not None and finished is not None else None
    )
    return _result(problem, options, setup, hist, outcome, field_data, finished, recorded_until)


def _free_displacement(
    solve: Any, M: Any, u: NDArray[np.float64], v: NDArray[np.float64], a: NDArray[np.float64], h: float
) -> NDArray[np.float64]:
    """The bar's displacement after a step ``h`` (s) with no contact force (average-acceleration
    Newmark; ``solve`` factors K + 4 M / h^2)."""
    return solve(M @ ((4.0 / h**2) * u + (4.0 / h) * v + a))


def _rates(
    u: NDArray[np.float64], v: NDArray[np.float64], a: NDArray[np.float64], u_new: NDArray[np.float64], h: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Velocity and acceleration after a Newmark step from ``u, v, a`` to ``u_new``."""
    a_new = (4.0 / h**2) * (u_new - u) - (4.0 / h) * v - a
    return v + 0.5 * h * (a + a_new), a_new


class _FieldRecorder:
    """The strain at the field's cross-sections at its sample times k dt_f, linear in time
    between the steps around each."""

    def __init__(self, grid: FieldGrid, rod: Rod, probes: Any, u: NDArray[np.float64]) -> None:
        self.transit = rod.length_m / rod.wave_speed
        self.positions = grid.positions(rod.length_m)
        self.step = grid.sample_step(self.transit)
        self.probes = probes
        self.last = (0.0, probes @ u)
        self.samples = [self.last[1]]

    @property
    def count(self) -> int:
        return len(self.samples)

    def record(self, t: float, u: NDArray[np.float64]) -> None:
        """The bar's state ``u`` at time ``t`` (s): every sample time up to ``t`` is taken."""
        strain = self.probes @ u
        t0, before = self.last
        while len(self.samples) * self.step <= t:
            weight = (len(self.samples) * self.step - t0) / (t - t0)
            self.samples.append(before + weight * (strain - before))
        self.last = (t, strain)

    def datasets(self, times: NDArray[np.float64]) -> dict[str, tuple[NDArray[np.float64], str, str]]:
        """The field at ``times`` (the grid's; those the run reached)."""
        count = min(len(times), len(self.samples))
        return field_datasets(
            times[:count], self.positions, np.asarray(self.samples[:count]), "FEM, the bar's displacements"
        )


def _no_further_contact(
    rod: Rod, x: float, w: float, rod_energy: float, static_end: float, since_separation: float, rod_momentum: float
) -> bool:
    """Fixed far end: the end can never be further out than sqrt(2 E_rod C_static), so an
    impactor moving away beyond that never returns (rigorous). Free far end: the impactor
    is no faster than the rod's centre of mass and has stayed clear for
    :data:`~rodimpact.solvers.stepping.SEPARATION_ROUND_TRIPS` round trips, 8T (a heuristic:
    the end oscillates about the centre-of-mass motion)."""
    if rod.far_end == "fixed":
        return w <= 0.0 and x + math.sqrt(2.0 * rod_energy * static_end) < 0.0
    return w <= rod_momentum / rod.mass_kg and since_separation >= SEPARATION_ROUND_TRIPS * rod.reflection_period


def _result(
    problem: ImpactProblem,
    options: FEM1DOptions,
    setup: _Setup,
    hist: _History,
    outcome: Outcome,
    field: dict[str, tuple[NDArray[np.float64], str, str]],
    finished: int | None = None,
    recorded_until: float | None = None,
) -> ImpactResult:
    """The run's result. Its energy balance and the rod's energy are those at the node where no
    further contact was proven (``finished``; the last node when None), where a run that records
    no gauge ends: a run that records goes on stepping the free bodies (whose energies Newmark's
    rule conserves to rounding), and its contact results stay those of the run without records.
    ``recorded_until`` (s): the time the record had to reach, in the summary's ``recorded_until_s``."""
    nodes = hist.nodes()
    end = len(nodes.time) if finished is None else finished + 1
    kinetic = 0.5 * problem.mass_kg * nodes.w**2
    contact_histories = contact_series(problem.contact, nodes.alpha)
    # the contact's energy: what it stores and, a law with memory, what it has dissipated
    contact = contact_histories["contact_energy"][0]
    if "contact_dissipated_energy" in contact_histories:
        contact = contact + contact_histories["contact_dissipated_energy"][0]
    rod_kin, rod_str = np.asarray(hist.rod_kinetic), np.asarray(hist.rod_strain)
    series = {
        "impactor_kinetic_energy": (kinetic, "J", "kinetic energy of the impactor"),
        **contact_histories,
        "rod_energy": (rod_kin + rod_str, "J", "energy in the rod (kinetic + strain)"),
        "rod_kinetic_energy": (rod_kin, "J", "kinetic energy of the rod, v^T M v / 2"),
        "rod_strain_energy": (rod_str, "J", "strain energy of the rod, u^T K u / 2"),
    }
    extra: dict[str, Any] = {
        "n_elements": int(setup.n_elements),
        "element": options.element,
        "n_dofs": int(setup.bar.mass.shape[0]),
        "warnings": "; ".join(setup.warnings),
    }
    if setup.stations_m:
        series["station_displacement"] = (
            np.asarray(hist.station_u),
            "m",
            "axial displacement of the cross-sections at station_x_m (FEM)",
        )
        series["station_strain"] = (
            np.asarray(hist.station_e),
            "1",
            "axial strain du/dx at station_x_m (negative in compression; FEM)",
        )
        extra["station_x_m"] = np.asarray(setup.stations_m)
    if setup.gauges:
        gauge_series, gauge_summary = gauge_datasets(setup.gauges, np.asarray(hist.gauge_e), "FEM")
        series.update(gauge_series)
        extra.update(gauge_summary)
    if setup.bar.far_probe is not None:
        series.update(far_end_datasets(np.asarray(hist.far_v), "FEM, the last node's Newmark velocity"))
    if field:
        extra["wave_speed_m_s"] = float(problem.rod.wave_speed)
    if recorded_until is not None:
        extra["recorded_until_s"] = float(recorded_until)
    # every located start and end, less the run's first start (t = 0) and a start left open
    events = len(hist.ends) + min(len(hist.starts), len(hist.ends)) - 1
    return hist.result(
        nodes,
        outcome,
        scheme=f"fem1d-{options.element}-newmark",
        dt_s=float(setup.h),
        energy_error=energy_error(kinetic[:end], contact[:end], rod_kin[:end], rod_str[:end]),
        rod_energy_J=float(rod_kin[end - 1] + rod_str[end - 1]),
        n_events=events,
        extra=extra,
        extra_series=series,
        field=field,
    )
