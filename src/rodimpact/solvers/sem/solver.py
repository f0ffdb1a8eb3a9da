"""The SEM driver: the nonlinear Volterra equation of the contact, stepped in time.

    alpha(t) = v0 t - integral_0^t P(theta) [Y1(t - theta) + Y2(t - theta)] d theta,
    P = P(alpha), the case's contact law (Hertz: k alpha_+^(3/2)).

Both schemes keep the impactor as its exact ODE (equivalent to the kernel Y2 = t/m) and
the rod through its piecewise-constant impulse response (:mod:`.history`).

``implicit`` (default): P piecewise linear in time, every integral exact for it, the new
force solved from P_new = P(A - B P_new) (B > 0, one root: the law's ``solve_step``):
second order, no step-size limit from stability, true wave delays. Contact ends and
starts are located inside a step by root finding and become nodes.

``paper``: the paper's formula, P held constant over each step at its left value and
lagged one step (explicit), first order, conditionally stable. Contact ends are reported
at the zero of the approach interpolated linearly between nodes.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time as _time
from collections.abc import Sequence

import numpy as np

from rodimpact.analysis.signals import first_contact_maxima
from rodimpact.model.gauges import Gauge
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.field import FieldGrid, field_datasets
from rodimpact.solvers.gauge_series import (
    checked_gauges,
    far_end_datasets,
    gauge_datasets,
    record_until_s,
    recorded_reach_m,
)
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.sem.grid import commensurate_step
from rodimpact.solvers.sem.history import ForceHistory
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.record import extended_record
from rodimpact.solvers.sem.stepper import SEMRun, run_fixed_step

__all__ = ["solve_sem"]

log = logging.getLogger(__name__)

#: Refinements the automatic step may take after its first choice.
_MAX_REFINEMENTS = 8
#: The predicted step for the tolerance is taken this much finer.
_SAFETY = 0.8
#: The first check's run takes this many times the candidate's step (its first contact then
#: costs a quarter of the candidate's).
_CHECK_RATIO = 4.0
#: The finest next step in units of the last (a far-off first estimate does not jump to a step
#: the run cannot afford).
_MIN_FACTOR = 0.25
#: A refinement whose error estimate is above this fraction of the last one's is not converging
#: (order 2 at a step ratio of 2 or more gives at most 1/4).
_CONVERGING = 0.5
#: The first candidate step in units of the error model's guess
#: (:func:`~rodimpact.solvers.sem.stability.implicit_step`, whose error constant has a
#: margin of 4 over the measured one).
_FIRST_STEP_FACTOR = 2.0


def solve_sem(
    problem: ImpactProblem,
    options: SEMOptions | PaperSEMOptions | None = None,
    stations: Sequence[float] = (),
    field: FieldGrid | None = None,
    gauges: Sequence[Gauge] = (),
    far_end_velocity: bool = False,
) -> ImpactResult:
    """Solve the SEM contact problem.

    Parameters
    ----------
    problem : ImpactProblem
        The impact.
    options : SEMOptions or PaperSEMOptions, optional
        The scheme (by the class) and the step; defaults to ``SEMOptions()``: implicit
        scheme, step chosen from the case for ``tolerance`` and checked by step doubling.
    stations : sequence of float
        Positions along the rod as fractions of its length from the struck end (0..1);
        the displacement and strain there are computed from the force by d'Alembert's
        solution (``station_displacement``, ``station_strain``, shape (n, k)).
    field : FieldGrid, optional
        Record the strain over the whole rod on this grid (:attr:`ImpactResult.field`),
        through d'Alembert's solution driven by the run's contact force; None (default)
        records none, and the run is the same.
    gauges : sequence of Gauge
        Strain gauges (:class:`~rodimpact.model.gauges.Gauge`): the mean strain over each,
        from d'Alembert's solution driven by the run's force (:func:`_with_gauges`), is
        stored as ``gauge_strain`` (n, k) with ``gauge_x_m`` and ``gauge_length_m``.
    far_end_velocity : bool
        Also store the velocity of the far end x = l (``far_end_velocity``, m/s), from the
        same solution.

        With gauges or the far end's velocity, a completed run's histories go on after its
        last contact, at its step and with no force, until every wave the contact sent has
        passed the farthest section recorded (:func:`_recorded`; the summary's
        ``recorded_until_s``); its contact results, ``n_steps`` (the steps taken) and
        everything else are those of the run without them.

    Returns
    -------
    ImpactResult
        Histories, contact intervals, force maxima, energy balance and cost counters.
        ``success`` is False (``status`` ``failed``) when the first contact did not end
        within the time horizon or the step budget, when the energy balance is off by more
        than ``energy_tolerance``, or when an automatic step did not reach ``tolerance``.
        ``extra`` says how the step was chosen (``step_choice``) and, for an automatic
        step, the ``tolerance`` and the step-doubling ``error_estimate``.

    Raises
    ------
    rodimpact.solvers.sem.stability.UnstableStepError
        The paper scheme's step exceeds its stability limit and ``options.allow_unstable``
        is False.
    rodimpact.model.gauges.GaugeError
        A gauge is off the rod.
    ValueError
        A station outside [0, 1]; stations or the far end's velocity on a rod of infinite length.
    """
    options = SEMOptions() if options is None else options
    stations = _check_stations(stations, problem)
    gauges = checked_gauges(gauges, problem.rod.length_m)
    if far_end_velocity and not math.isfinite(problem.rod.length_m):
        raise ValueError("far_end_velocity needs a rod of finite length")
    if field is not None:
        field.positions(problem.rod.length_m)  # a rod of finite length, before any step
    started = _time.perf_counter()
    h = options.step(problem)
    options.check(problem)
    if not (options.automatic_step and options.scheme == "implicit"):
        if options.dt_s is not None:
            result = run_fixed_step(problem, options, h, stations, started, {"step_choice": "dt_s"})
        else:
            h = commensurate_step(h, problem.rod.reflection_period)
            result = run_fixed_step(problem, options, h, stations, started, {"step_choice": "steps_per_contact"})
    else:
        result = _automatic(problem, options, h, stations, started)
    if field is not None:
        result = _with_field(result, problem, options, field)
    if gauges or far_end_velocity:
        result = _with_gauges(
            _recorded(result, problem, stations, gauges, far_end_velocity), problem, options, gauges, far_end_velocity
        )
    return result


def _recorded(
    result: ImpactResult,
    problem: ImpactProblem,
    stations: tuple[float, ...],
    gauges: tuple[Gauge, ...],
    far_end_velocity: bool,
) -> ImpactResult:
    """A completed run that records gauges or the far end's velocity, continued after its last
    contact until every wave that contact sent has passed the farthest section it records
    (:func:`~rodimpact.solvers.gauge_series.record_until_s`, the summary's ``recorded_until_s``;
    :func:`~rodimpact.solvers.sem.record.extended_record`: the force is zero, the time limit
    does not apply, the contact results are the run's). A run that did not complete (a limit,
    a failure) is not continued: what follows its end was not computed."""
    if result.status != "completed" or not len(result.contact_end_s):
        return result
    rod = problem.rod
    reach = recorded_reach_m(gauges, far_end_velocity, rod.length_m)
    until = record_until_s(float(result.contact_end_s[-1]), reach, rod.wave_speed)
    result = extended_record(result, problem, stations, until)
    return dataclasses.replace(result, extra={**result.extra, "recorded_until_s": until})


def _with_gauges(
    result: ImpactResult,
    problem: ImpactProblem,
    options: SEMOptions | PaperSEMOptions,
    gauges: tuple[Gauge, ...],
    far_end_velocity: bool,
) -> ImpactResult:
    """The result with its gauges' strain and its far end's velocity at its nodes, from
    d'Alembert's solution driven by the run's force (its nodes, with the scheme's own
    interpolation: linear in time for ``implicit``, held for ``paper``).

    With the force P(t) at the struck end, the waves reach x with delays (2jl + x)/a (going
    towards the far end, direction +1, sign s^j) and (2(j+1)l - x)/a (coming back, direction
    -1, sign s^(j+1)), s = +1 for a free far end and -1 for a fixed one; then

        u(x, t) = (1/Z) sum_waves sign Q(t - delay),   Q(t) = int_0^t P,
        eps(x, t) = du/dx = -(1/(E A)) sum_waves sign direction P(t - delay),
        v(x, t) = du/dt = (1/Z) sum_waves sign P(t - delay),

    Z = E A / a. Before the first reflection reaches x (t < (2l - x)/a) only the first wave
    is there: eps = -P(t - x/a)/(E A). A point gauge reads eps at its station; a gauge of
    length g, (u(x + g/2) - u(x - g/2))/g, exactly the mean of eps over its length. At the far
    end v(l, t) = (2/Z) sum_j P(t - (2j + 1) l/a) when it is free, 0 when it is fixed.
    """
    rod = problem.rod
    history = ForceHistory.of_nodes(rod, options.scheme == "implicit", result.time, result.contact_force)
    t = result.time
    series, extra = {}, {}
    if gauges:
        columns = []
        for gauge in gauges:
            if gauge.gauge_length_m > 0.0:
                low, high = gauge.ends()
                columns.append(
                    (history.displacement_at(high, t) - history.displacement_at(low, t)) / gauge.gauge_length_m
                )
            else:
                columns.append(history.strain_at(gauge.station_m, t))
        series, extra = gauge_datasets(gauges, np.column_stack(columns), "d'Alembert, from the contact force")
    if far_end_velocity:
        series.update(far_end_datasets(history.velocity_at(rod.length_m, t), "d'Alembert, from the contact force"))
    return dataclasses.replace(result, extra={**result.extra, **extra}, extra_series={**result.extra_series, **series})


def _with_field(
    result: ImpactResult, problem: ImpactProblem, options: SEMOptions | PaperSEMOptions, grid: FieldGrid
) -> ImpactResult:
    """The result with its strain field: d'Alembert's solution driven by the run's force (its
    nodes, with the scheme's own interpolation); zero force after the run's last node."""
    rod = problem.rod
    transit = rod.length_m / rod.wave_speed
    times = grid.times(transit, result.status, result.contact_end_s, float(result.time[-1]))
    history = ForceHistory.of_nodes(rod, options.scheme == "implicit", result.time, result.contact_force)
    positions = grid.positions(rod.length_m)
    strain = np.column_stack([history.strain_at(x, times) for x in positions])
    field = field_datasets(times, positions, strain, "d'Alembert, from the contact force")
    log.info("SEM strain field: %d times x %d sections to %.6g s", len(times), len(positions), times[-1])
    return dataclasses.replace(result, field=field, extra={**result.extra, "wave_speed_m_s": rod.wave_speed})


def _automatic(
    problem: ImpactProblem, options: SEMOptions, h: float, stations: tuple[float, ...], started: float
) -> ImpactResult:
    """The implicit scheme with its step chosen for ``options.tolerance``, from the first guess ``h``.

    The first candidate is :data:`_FIRST_STEP_FACTOR` times the guess (whose error model
    has a margin of that factor squared). Each candidate is checked against a run at about
    twice its step, compared on their first contact only (its duration and largest force;
    Richardson's estimate for order 2 at the runs' ratio of steps), and the candidate that
    meets the tolerance is then finished: the check costs the coarser run's first contact.
    A candidate that misses the tolerance is replaced by the step the estimate predicts,
    with a margin, between 1/4 and 1/2 of it; when a finer step does not shrink the estimate as
    order 2 says, the whole runs are compared instead (:func:`_whole_runs`). Every step is
    commensurate with the wave round trip (constant cost per step).
    """
    period = problem.rod.reflection_period
    h = commensurate_step(_FIRST_STEP_FACTOR * h, period)
    coarse = SEMRun(problem, options, commensurate_step(_CHECK_RATIO * h, period))
    fine = SEMRun(problem, options, h)
    checks, previous = 0, math.inf
    for refinement in range(_MAX_REFINEMENTS + 1):
        c, f = coarse.first_contact(), fine.first_contact()
        if c is None or f is None:  # a run failed: the finer one is the answer
            return fine.finish(stations, started, {"step_choice": "auto"})
        checks += coarse.n_steps
        estimate = _richardson(f, c, coarse.st.h / fine.st.h)
        if estimate <= options.tolerance or refinement == _MAX_REFINEMENTS:
            break
        if estimate > _CONVERGING * previous:
            # a finer step did not shrink the first contact's error as order 2 says: its end
            # is ill-conditioned (a grazing separation); judge the whole runs instead
            return _whole_runs(problem, options, coarse, fine, stations, started, checks)
        previous = estimate
        factor = min(0.5, max(_MIN_FACTOR, _SAFETY * math.sqrt(options.tolerance / estimate)))
        h_new = commensurate_step(fine.st.h * factor, period)
        log.info(
            "SEM auto step %.4g s: error estimate %.2g > tolerance %.2g, next step %.4g s",
            fine.st.h,
            estimate,
            options.tolerance,
            h_new,
        )
        coarse, fine = fine, SEMRun(problem, options, h_new)
    h = fine.st.h
    extra = {
        "step_choice": "auto",
        "tolerance": options.tolerance,
        "error_estimate": estimate,
        "error_estimate_basis": "Richardson (order 2) between two steps: first contact time and its largest force",
        "n_steps_error_check": checks,
    }
    if estimate > options.tolerance:
        return _with_extra(
            fine.finish(stations, started, extra),
            {},
            status="failed",
            message=(
                f"automatic step: error estimate {estimate:.3g} still above tolerance {options.tolerance:.3g} "
                f"after {_MAX_REFINEMENTS} refinements (dt_s={h:.4g} s)"
            ),
        )
    result = fine.finish(stations, started, extra)
    return _with_extra(
        result,
        {},
        message=f"{result.message}; step {h:.4g} s chosen for tolerance "
        f"{options.tolerance:.3g} (estimated error {estimate:.2g})",
    )


def _whole_runs(
    problem: ImpactProblem,
    options: SEMOptions,
    coarse: SEMRun,
    fine: SEMRun,
    stations: tuple[float, ...],
    started: float,
    checks: int,
) -> ImpactResult:
    """The automatic step judged on whole runs: both runs finished, their contact time (first
    contact to last) and their first contact's largest force compared, the step halved until
    the estimate meets the tolerance."""
    period = problem.rod.reflection_period
    coarse_result = coarse.finish(stations, started, {})
    fine_result, h, ratio = fine.finish(stations, started, {}), fine.st.h, coarse.st.h / fine.st.h
    for refinement in range(_MAX_REFINEMENTS + 1):
        if not (fine_result.success and coarse_result.success):
            return _with_extra(fine_result, {"step_choice": "auto"})
        estimate = _whole_run_estimate(fine_result, coarse_result, ratio)
        if estimate <= options.tolerance or refinement == _MAX_REFINEMENTS:
            break
        h_new = commensurate_step(0.5 * h, period)
        log.info(
            "SEM auto step %.4g s: whole-run error estimate %.2g > tolerance %.2g, next step %.4g s",
            h,
            estimate,
            options.tolerance,
            h_new,
        )
        checks += coarse_result.n_steps
        coarse_result, ratio, h = fine_result, h / h_new, h_new
        fine_result = SEMRun(problem, options, h).finish(stations, started, {})
    checks += coarse_result.n_steps
    extra = {
        "step_choice": "auto",
        "tolerance": options.tolerance,
        "error_estimate": estimate,
        "error_estimate_basis": "Richardson (order 2) between two steps: whole-run contact time and the first "
        "contact's largest force (the first contact's end was ill-conditioned)",
        "n_steps_error_check": checks,
    }
    if estimate > options.tolerance:
        return _with_extra(
            fine_result,
            extra,
            status="failed",
            message=(
                f"automatic step: error estimate {estimate:.3g} still above tolerance {options.tolerance:.3g} "
                f"after {_MAX_REFINEMENTS} halvings (dt_s={h:.4g} s)"
            ),
        )
    return _with_extra(
        fine_result,
        extra,
        message=f"{fine_result.message}; step {h:.4g} s chosen for tolerance "
        f"{options.tolerance:.3g} (estimated error {estimate:.2g})",
    )


def _whole_run_estimate(fine: ImpactResult, coarse: ImpactResult, ratio: float) -> float:
    """Richardson error estimate (order 2) of the fine run's contact time and its first
    contact's largest force, from a run at ``ratio`` times its step."""

    def measures(result: ImpactResult) -> tuple[float, float]:
        maxima = first_contact_maxima(result.peak_time_s, result.peak_force_N, result.contact_end_s)
        return result.contact_time_s, float(np.max(maxima, initial=np.max(result.contact_force)))

    return _richardson(measures(fine), measures(coarse), ratio)


def _richardson(fine: tuple[float, float], coarse: tuple[float, float], ratio: float) -> float:
    """Richardson error estimate (order 2) of the fine run's first contact time and largest
    force, from a run at ``ratio`` times its step; the larger of the two relative errors."""
    tc = abs(fine[0] - coarse[0]) / fine[0]
    peak = abs(fine[1] - coarse[1]) / fine[1]
    return max(tc, peak) / (ratio**2 - 1.0)


def _with_extra(
    result: ImpactResult, extra: dict, status: str | None = None, message: str | None = None
) -> ImpactResult:
    status = result.status if status is None else status
    return dataclasses.replace(
        result,
        extra={**result.extra, **extra},
        status=status,
        success=status != "failed",
        message=result.message if message is None else message,
    )


def _check_stations(stations: Sequence[float], problem: ImpactProblem) -> tuple[float, ...]:
    stations = tuple(float(s) for s in stations)
    if any(not (0.0 <= s <= 1.0) for s in stations):
        raise ValueError(f"stations must be fractions of the rod length in [0, 1], got {stations}")
    if stations and not math.isfinite(problem.rod.length_m):
        raise ValueError("stations need a rod of finite length")
    return stations
