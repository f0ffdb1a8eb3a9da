"""The cost model of a ``fem1d`` run: elements times steps."""

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
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.field import FIELD_OUTPUT, FieldGrid
from rodimpact.solvers.stepping import SEPARATION_ROUND_TRIPS

__all__ = ["fem1d_cost"]

#: fem1d: s per step, s per step and DOF (measured at most 330 us and 0.3 us with 47000
#: DOFs), bytes per step and per DOF (830 and 800 measured).
FEM1D_STEP_S = 150e-6
FEM1D_DOF_STEP_S = 0.5e-6
FEM1D_STEP_BYTES = 1000.0
FEM1D_DOF_BYTES = 2000.0
#: Measured over modelled solve time, median of the stored runs (``Cost.typical_share``;
#: ``python -m rodimpact.tools.cost_share``).
FEM1D_TYPICAL_SHARE = 0.084


def fem1d_cost(case: Mapping[str, Any], options: FEM1DOptions) -> Cost:
    """The steps, time and memory of one ``fem1d`` solve of ``case`` (a resolved case)."""
    problem = ImpactProblem.from_case(case, estimate=True)
    elements, step, _ = options.resolve(problem)
    dofs = (1 if options.element == "P1" else 2) * elements + 1
    # its end test: a fixed rod's energy bound (measured: within 2 contact times and half a
    # round trip), a free rod's separation window
    contact, period = contact_duration(problem), problem.rod.reflection_period
    end_test = min(3.0 * contact, period) if problem.rod.far_end == "fixed" else SEPARATION_ROUND_TRIPS * period
    # a run that records gauges or the far end's velocity steps on to its recording's end
    # (beyond the time limit)
    span = max(horizon(problem, options.max_time_factor, contact, end_test), recording_end(case, problem, contact))
    steps = span / step + 1.0
    if FIELD_OUTPUT in case.get("outputs", ()) and math.isfinite(problem.rod.reflection_period):
        # the strain field: the bar stepped alone for its round trips after the last contact
        steps += (
            FieldGrid.from_settings(case.get("field_grid", {})).round_trips_after * problem.rod.reflection_period / step
        )
    stations = recorded_probes(case)  # stations, gauges and the far end, when asked for
    return Cost(
        time_step_s=step,
        steps=steps,
        solve_s=SOLVE_S + steps * (FEM1D_STEP_S + FEM1D_DOF_STEP_S * dofs),
        mem_mib=(steps * (FEM1D_STEP_BYTES + STATION_STEP_BYTES * stations) + dofs * FEM1D_DOF_BYTES) / MIB,
        typical_share=FEM1D_TYPICAL_SHARE,
    )
