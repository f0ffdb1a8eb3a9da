"""Benchmark: the SEM's cost per step against the number of wave round trips in the contact.

The case ``model`` with its rod shortened so that the contact spans about 10, 100, 1,000
and 10,000 round trips 2T, at the automatic step for ``tolerance``; and the stress case
``seconds_contact``. Each row times the automatic run and a fixed-step run at the step it
chose (best of a few repeats), so that the table shows

* the time per step of the fixed run, and the slope of its logarithm against the
  logarithm of the round trips (0 for a constant cost per step);
* the automatic step's cost over the fixed run's (its check runs).

``make bench`` writes it to ``results/benchmarks/sem_scaling.csv``.
"""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.jobs.machine import machine_info
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.sem.options import SEMOptions
from rodimpact.solvers.sem.solver import solve_sem
from rodimpact.tools.bench_plan import SCALING_MIN_REPEATS, SCALING_ROUND_TRIPS, shortened_rod

__all__ = ["benchmark_sem_scaling"]

log = logging.getLogger(__name__)

#: Each run is repeated until this much time has passed (at least SCALING_MIN_REPEATS times), s.
MIN_TOTAL_S = 1.0


def _best_time(problem: ImpactProblem, options: SEMOptions) -> tuple[Any, float]:
    best, result, spent, repeats = math.inf, None, 0.0, 0
    while repeats < SCALING_MIN_REPEATS or spent < MIN_TOTAL_S:
        started = time.perf_counter()
        result = solve_sem(problem, options)
        elapsed = time.perf_counter() - started
        best, spent, repeats = min(best, elapsed), spent + elapsed, repeats + 1
    if not result.success:
        raise RuntimeError(f"benchmark run failed: {result.message}")
    return result, best


def _row(label: str, problem: ImpactProblem, tolerance: float) -> dict[str, Any]:
    auto, auto_s = _best_time(problem, SEMOptions(tolerance=tolerance))
    fixed, fixed_s = _best_time(problem, SEMOptions(dt_s=auto.dt_s))
    period = problem.rod.reflection_period
    return {
        "case": label,
        "rod_length_m": problem.rod.length_m,
        "round_trips": auto.contact_time_s / period,
        "tolerance": tolerance,
        "dt_s": auto.dt_s,
        "steps": fixed.n_steps,
        "fixed_step_s": fixed_s,
        "auto_step_s": auto_s,
        "us_per_step": 1e6 * fixed_s / fixed.n_steps,
        "auto_over_fixed": auto_s / fixed_s,
        "contact_time_s": auto.contact_time_s,
        "same_contact_time": auto.contact_time_s == fixed.contact_time_s,
    }


def benchmark_sem_scaling(
    model: Mapping[str, Any],
    stress: Mapping[str, Any],
    *,
    round_trips: Sequence[int] = SCALING_ROUND_TRIPS,
    tolerance: float = 1e-6,
) -> pd.DataFrame:
    """Time per step of the SEM against the round trips during the contact.

    Parameters
    ----------
    model : mapping
        The resolved case ``model``; its rod is shortened to l = a t_H / (2 n) for each n
        of ``round_trips`` (t_H its rigid-rod contact time, a the wave speed).
    stress : mapping
        A resolved long-contact case (``seconds_contact``), timed as it is.
    round_trips : sequence of int
        Round trips aimed at.
    tolerance : float
        The automatic step's tolerance.

    Returns
    -------
    pandas.DataFrame
        One row per run (``case``, ``round_trips``, ``steps``, ``us_per_step``,
        ``auto_over_fixed``, ...), with ``slope`` (the least-squares slope of
        log(us_per_step) against log(round_trips) over the shortened rods, on every row)
        and the machine's description.
    """
    rows = []
    for n in round_trips:
        rows.append(
            _row(f"{model['id']}, rod for {n} round trips", ImpactProblem.from_case(shortened_rod(model, n)), tolerance)
        )
        log.info(
            "%s: %.2f us a step, automatic step x%.2f",
            rows[-1]["case"],
            rows[-1]["us_per_step"],
            rows[-1]["auto_over_fixed"],
        )
    frame = pd.DataFrame(rows)
    slope = float(np.polyfit(np.log(frame["round_trips"]), np.log(frame["us_per_step"]), 1)[0])
    stress_row = _row(str(stress["id"]), ImpactProblem.from_case(stress), tolerance)
    log.info("%s: %.3f s automatic", stress_row["case"], stress_row["auto_step_s"])
    frame = pd.concat([frame, pd.DataFrame([stress_row])], ignore_index=True)
    frame["slope"] = slope
    for key, value in machine_info().items():
        frame[key] = value
    return frame
