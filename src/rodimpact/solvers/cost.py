"""The cost model every solver's estimate is built from: its steps, time and memory.

Closed forms only (no solve, no mesh): the workflow evaluates them for every job when it
plans the build (:mod:`rodimpact.jobs.resources`). Each method's own model lives in its
package (``cost.py``) and is named by its registry entry. The per-unit costs are calibrated
on the development machine (one core of a 2-core x86_64 VM) against the stored runs
(docs/cluster.md, "Resources").
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.gauge_series import FAR_END_OUTPUT, GAUGE_OUTPUT, case_gauges, record_until_s, recorded_reach_m

__all__ = [
    "Cost",
    "MIB",
    "SHORT_CONTACT",
    "SOLVE_S",
    "STATION_STEP_BYTES",
    "contact_duration",
    "horizon",
    "recorded_probes",
    "recording_end",
]

MIB = 2.0**20

#: Every solve's fixed part, s: options, the end test's look-ahead, the result's arrays.
SOLVE_S = 0.5
#: Memory per stored step and station, bytes: the station's two histories (displacement and
#: strain, 8 bytes each a step), allowed four times over for the copies they pass through (what
#: the solver records or computes them from, the result's arrays, the run's file).
STATION_STEP_BYTES = 64.0
#: Rigid-rod contact times within which a contact on a rod that carries the rigid-rod force is over.
SHORT_CONTACT = 1.5


@dataclass(frozen=True)
class Cost:
    """The cost model of one solve: its time step (s), its steps, its time (s) and its own
    memory (MiB); with a step budget (``step_limit``, the solver fails on reaching it),
    ``steps`` and the time stop there and ``steps_needed`` is what the run's span asks for.

    ``solve_s`` is upper-side (it covers every stored run: a job's request); ``typical_share``
    is the share of it a solve of the method typically takes (the median of measured over
    modelled time of the stored runs, ``python -m rodimpact.tools.cost_share``), so that
    :attr:`typical_s` is a central estimate: what a study is cut into jobs by
    (:mod:`rodimpact.jobs.parts`)."""

    time_step_s: float
    steps: float
    solve_s: float
    mem_mib: float
    steps_needed: float | None = None
    step_limit: float = math.inf
    typical_share: float = 1.0

    @property
    def typical_s(self) -> float:
        """Central estimate of the solve's time, s: ``typical_share * solve_s``."""
        return self.typical_share * self.solve_s

    @property
    def exceeds_step_limit(self) -> bool:
        """The run's span needs more steps than the solver's budget allows: it would fail."""
        return self.steps_needed is not None and self.steps_needed > self.step_limit


def contact_duration(problem: ImpactProblem) -> float:
    """Upper-side duration of all contacts, s: :meth:`contact_time_estimate` (rigid-rod
    contact time, the rod's spring, a wave round trip 2T); on a rod that carries the rigid-rod
    force (Z v0 >= P_H) and whose round trip is longer than :data:`SHORT_CONTACT` rigid-rod
    contact times, that many of them: the one contact is over before any reflection comes
    back (measured: at most 1.23 Hertz times)."""
    estimate = problem.contact_time_estimate()
    rigid = problem.rigid_contact
    short = SHORT_CONTACT * rigid.contact_time_s
    if problem.rod.impedance * problem.velocity_m_s >= rigid.peak_force_N and short < problem.rod.reflection_period:
        return min(estimate, short)
    return estimate


def recorded_probes(case: Mapping[str, Any]) -> int:
    """The probes a run of ``case`` records at every stored step, each counted at a station's
    :data:`STATION_STEP_BYTES`: its stations, its gauges when its outputs list ``gauge_strain``
    (one history each, two with ``fem_axi``'s mean) and the far end when they list
    ``far_end_velocity`` (one history)."""
    outputs = case.get("outputs", ())
    gauges = len(case.get("gauges", ())) if GAUGE_OUTPUT in outputs else 0
    return len(case.get("stations", ())) + gauges + (1 if FAR_END_OUTPUT in outputs else 0)


def recording_end(case: Mapping[str, Any], problem: ImpactProblem, contact_s: float) -> float:
    """The time a run of ``case`` that records gauges or the far end's velocity goes on to after
    contacts that end by ``contact_s`` (s; the time limit does not cut it short), s:
    :func:`~rodimpact.solvers.gauge_series.record_until_s` of the farthest section it records;
    0 when it records neither (or the section is not at a finite distance)."""
    outputs = case.get("outputs", ())
    gauges = case_gauges(case)
    reach = recorded_reach_m(gauges, FAR_END_OUTPUT in outputs, problem.rod.length_m)
    if reach is None or not math.isfinite(reach):
        return 0.0
    return record_until_s(contact_s, reach, problem.rod.wave_speed)


def horizon(problem: ImpactProblem, max_time_factor: float, contact_s: float, end_test_s: float) -> float:
    """Time a run steps through, s: the contacts and the end test after them; at most the
    solver's limit, ``max_time_factor`` contact time estimates."""
    limit = max_time_factor * problem.contact_time_estimate()
    return min(contact_s + end_test_s, limit)
