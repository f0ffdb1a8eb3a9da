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
from typing import Sequence

import numpy as np

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.stepper import run_fixed_step

__all__ = ["solve_sem"]

log = logging.getLogger(__name__)

#: Step doublings the automatic step may take after its first choice.
_MAX_REFINEMENTS = 8


def solve_sem(problem: ImpactProblem, options: SEMOptions | PaperSEMOptions | None = None,
              stations: Sequence[float] = ()) -> ImpactResult:
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
    """
    options = SEMOptions() if options is None else options
    stations = _check_stations(stations, problem)
    started = _time.perf_counter()
    h = options.step(problem)
    options.check(problem)
    if not (options.automatic_step and options.scheme == "implicit"):
        choice = "dt_s" if options.dt_s is not None else "steps_per_contact"
        return run_fixed_step(problem, options, h, stations, started, {"step_choice": choice})
    coarse = run_fixed_step(problem, options, 2.0 * h, stations, started, {})
    checks = coarse.n_steps
    for refinement in range(_MAX_REFINEMENTS + 1):
        fine = run_fixed_step(problem, options, h, stations, started, {})
        if not (fine.success and coarse.success):
            return fine if not fine.success else _with_extra(fine, {"step_choice": "auto"})
        estimate = _doubling_estimate(fine, coarse)
        if refinement == 0 and 4.0 * estimate <= 0.5 * options.tolerance:
            # the first guess was finer than needed: the run at twice the step meets the
            # tolerance with its own (Richardson) estimate, 4 times the fine run's
            checks, fine, estimate, h = fine.n_steps, coarse, 4.0 * estimate, 2.0 * h
            break
        if estimate <= options.tolerance or refinement == _MAX_REFINEMENTS:
            break
        log.info("SEM auto step %.4g s: error estimate %.2g > tolerance %.2g, halving", h, estimate,
                 options.tolerance)
        checks += fine.n_steps
        coarse, h = fine, 0.5 * h
    extra = {"step_choice": "auto", "tolerance": options.tolerance, "error_estimate": estimate,
             "error_estimate_basis": "step doubling (Richardson, order 2): first contact time and its largest force",
             "n_steps_error_check": checks}
    if estimate > options.tolerance:
        return _with_extra(fine, extra, status="failed", message=(
            f"automatic step: error estimate {estimate:.3g} still above tolerance {options.tolerance:.3g} "
            f"after {_MAX_REFINEMENTS} halvings (dt_s={h:.4g} s)"))
    return _with_extra(fine, extra, message=f"{fine.message}; step {h:.4g} s chosen for tolerance "
                       f"{options.tolerance:.3g} (estimated error {estimate:.2g})")


def _doubling_estimate(fine: ImpactResult, coarse: ImpactResult) -> float:
    """Richardson error estimate of ``fine`` from a run at twice its step (order 2)."""
    def first_peak(result: ImpactResult) -> float:
        inside = result.peak_time_s <= result.contact_end_s[0]
        return float(np.max(result.peak_force_N[inside], initial=np.max(result.contact_force)))

    tc = abs(fine.contact_time_s - coarse.contact_time_s) / fine.contact_time_s
    peak = abs(first_peak(fine) - first_peak(coarse)) / first_peak(fine)
    return max(tc, peak) / 3.0


def _with_extra(result: ImpactResult, extra: dict, status: str | None = None,
                message: str | None = None) -> ImpactResult:
    status = result.status if status is None else status
    return dataclasses.replace(result, extra={**result.extra, **extra}, status=status,
                               success=status != "failed",
                               message=result.message if message is None else message)


def _check_stations(stations: Sequence[float], problem: ImpactProblem) -> tuple[float, ...]:
    stations = tuple(float(s) for s in stations)
    if any(not (0.0 <= s <= 1.0) for s in stations):
        raise ValueError(f"stations must be fractions of the rod length in [0, 1], got {stations}")
    if stations and not math.isfinite(problem.rod.length_m):
        raise ValueError("stations need a rod of finite length")
    return stations


