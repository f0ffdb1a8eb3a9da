"""The cost model of an SEM run (``sem``, ``sem_paper``): steps, at a constant cost a step
on a step commensurate with the wave round trip 2T (every step the solver chooses), and one
history term per round trip since the impact on a fixed ``dt_s`` that is not."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.cost import (
    MIB,
    SOLVE_S,
    STATION_STEP_BYTES,
    Cost,
    contact_duration,
    horizon,
    recorded_probes,
    recording_end,
)
from rodimpact.solvers.sem.grid import CommensurateGrid
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.stability import tolerance_step

__all__ = ["sem_cost"]

#: SEM, s per step and s per step and wave round trip since the impact (history terms);
#: least-squares fits of the stored runs give 8 and 3 us (implicit), 2 and 2 us (paper);
#: the largest per step: 250 us at 17 round trips (a run spending its step budget).
SEM_STEP_S = 20e-6
SEM_REFLECTION_S = 10e-6
#: Measured over modelled solve time, median of the stored runs (``Cost.typical_share``;
#: ``python -m rodimpact.tools.cost_share``): the implicit scheme, the paper's explicit one.
SEM_TYPICAL_SHARE = 0.034
SEM_PAPER_TYPICAL_SHARE = 0.023
#: SEM memory per stored step (Python lists of the state and the history, then the
#: result's arrays; the step-doubling check's run is alive next to it), bytes: 750 at most
#: measured (613479 steps, 549 MiB).
SEM_STEP_BYTES = 1000.0
#: The automatic step's total work in steps of its final run (the run at twice the step,
#: 1.37 measured at most with the step below).
SEM_AUTO_WORK = 1.5


def sem_cost(case: Mapping[str, Any], options: SEMOptions | PaperSEMOptions) -> Cost:
    """The steps, time and memory of one SEM solve of ``case`` (a resolved case)."""
    problem = ImpactProblem.from_case(case, estimate=True)
    period = problem.rod.reflection_period
    # the run ends with the contact (its end test looks ahead without stepping)
    contact = contact_duration(problem)
    span = horizon(problem, options.max_time_factor, contact, 0.0)
    step, work = options.step(problem), 1.0
    if options.automatic_step:
        # the first guess may be floored at a step count; the check halves it down to the
        # step the tolerance asks for
        step, work = min(step, tolerance_step(problem, options.tolerance)), SEM_AUTO_WORK
    raw = span / step
    # a run that records gauges or the far end's velocity is continued at its step to its
    # recording's end: nodes evaluated from d'Alembert's solution, not stepped (counted at a
    # step's cost, upper side; outside the step budget)
    extension = max(recording_end(case, problem, contact) - span, 0.0) / step
    stepped, needed = min(raw, float(options.max_steps)) + 1.0, raw + 1.0
    stored = stepped + extension
    # a step commensurate with the round trip costs the same at every round trip; only a
    # fixed dt_s that is not sums one history term per round trip since the impact
    commensurate = options.dt_s is None or CommensurateGrid.of(step, period, -1, True) is not None
    rounds = 1.0 + (0.5 * span / period if math.isfinite(period) and not commensurate else 0.0)
    stations = recorded_probes(case)  # stations, gauges and the far end, when asked for
    return Cost(
        time_step_s=step,
        steps=stored,
        solve_s=SOLVE_S + work * stepped * (SEM_STEP_S + SEM_REFLECTION_S * rounds) + extension * SEM_STEP_S,
        mem_mib=stored * (SEM_STEP_BYTES + STATION_STEP_BYTES * stations) / MIB,
        steps_needed=needed,
        step_limit=float(options.max_steps),
        typical_share=SEM_PAPER_TYPICAL_SHARE if isinstance(options, PaperSEMOptions) else SEM_TYPICAL_SHARE,
    )
