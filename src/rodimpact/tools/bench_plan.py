"""What the benchmarks run (``make bench``), as plain settings: the rules' resources read it
without loading a solver (:mod:`.bench` runs it)."""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from typing import Any

from rodimpact.model.problem import ImpactProblem

__all__ = ["fem_bench_runs", "sem_bench_runs", "sem_scaling_runs", "shortened_rod"]

#: Steps per Hertz time of the SEM benchmark: implicit scheme, paper scheme, the reference.
SEM_IMPLICIT_STEPS = (50, 100, 200, 400, 800, 1600, 2000, 3200)
SEM_PAPER_STEPS = (1000, 2000, 4000, 8000, 16000, 20000, 32000, 64000)
SEM_REFERENCE_STEPS = 64000
SEM_REPEATS = 3
#: fem1d benchmark: (element, elements or None, steps_per_contact), and its SEM reference.
FEM1D_SETTINGS = (
    ("P1", 20, 500),
    ("P1", 40, 1000),
    ("P1", 80, 2000),
    ("P2", 10, 500),
    ("P2", 20, 1000),
    ("P2", None, 2000),
    ("P2", 80, 4000),
)
FEM1D_REPEATS = 2
FEM1D_REFERENCE_STEPS = 16000
#: Steps per Hertz time of the SEM run each fem_axi run is compared with.
FEM_AXI_SEM_STEPS = 4000
#: fem_axi runs also computed with the whole rod as a continuum (continuum_diameters null), to
#: check the far bar: 'model' and the slowest Table 2 row.
FAR_BAR_CHECK_CASES = ("model", "ball_12.73mm-r1_l301")
#: SEM scaling benchmark: round trips 2T over the contact aimed at by shortening the rod of ``model``,
#: and the fewest repeats of each run.
SCALING_ROUND_TRIPS = (10, 100, 1_000, 10_000)
SCALING_MIN_REPEATS = 3


def _with_numerics(case: Mapping[str, Any], method: str, **settings: Any) -> dict[str, Any]:
    """``case`` run by ``method`` with some of its numerics replaced."""
    numerics = {**case["numerics"].get(method, {}), **settings}
    return {**case, "methods": [method], "numerics": {**case["numerics"], method: numerics}}


def sem_bench_runs(case: Mapping[str, Any]) -> list[tuple[dict[str, Any], str, int]]:
    """The solves :func:`rodimpact.tools.bench.benchmark_sem` makes with its defaults, as (case, method, repeats)
    for :func:`rodimpact.jobs.resources.estimate_sequence` (the rule's resources)."""
    fixed = {"dt_s": None}
    runs = [
        (_with_numerics(case, "sem", **fixed, steps_per_contact=n), "sem", 1)
        for n in (SEM_REFERENCE_STEPS, SEM_REFERENCE_STEPS // 2)
    ]
    runs += [
        (_with_numerics(case, "sem", **fixed, steps_per_contact=n), "sem", SEM_REPEATS) for n in SEM_IMPLICIT_STEPS
    ]
    runs += [
        (_with_numerics(case, "sem_paper", **fixed, steps_per_contact=n), "sem_paper", SEM_REPEATS)
        for n in SEM_PAPER_STEPS
    ]
    return runs


def fem_bench_runs(
    case: Mapping[str, Any], axi_cases: Sequence[Mapping[str, Any]]
) -> list[tuple[dict[str, Any], str, int]]:
    """The solves of :func:`rodimpact.tools.bench.benchmark_fem1d` on ``case`` and
    :func:`rodimpact.tools.bench.benchmark_fem_axi` on ``axi_cases`` with their defaults, as
    (case, method, repeats) (the rule's resources)."""
    fixed = {"dt_s": None}
    runs = [(_with_numerics(case, "sem", **fixed, steps_per_contact=FEM1D_REFERENCE_STEPS), "sem", 1)]
    runs += [
        (
            _with_numerics(case, "fem1d", **fixed, element=element, elements=n, steps_per_contact=steps),
            "fem1d",
            FEM1D_REPEATS,
        )
        for element, n, steps in FEM1D_SETTINGS
    ]
    for axi in axi_cases:
        runs += [
            (dict(axi), "fem_axi", 1),
            (_with_numerics(axi, "sem", **fixed, steps_per_contact=FEM_AXI_SEM_STEPS), "sem", 1),
        ]
        if axi["id"] in FAR_BAR_CHECK_CASES:
            runs.append((_with_numerics(axi, "fem_axi", continuum_diameters=None), "fem_axi", 1))
    return runs


def shortened_rod(model: Mapping[str, Any], round_trips: int) -> dict[str, Any]:
    """``model`` with its rod shortened to l = a t_H / (2 n): about n round trips in the contact."""
    base = ImpactProblem.from_case(model)
    case = copy.deepcopy(dict(model))
    case["rod"] = {
        **case["rod"],
        "length_m": base.rigid_contact.contact_time_s * base.rod.wave_speed / (2 * round_trips),
    }
    return case


def sem_scaling_runs(
    model: Mapping[str, Any], stress: Mapping[str, Any], round_trips: Sequence[int] = SCALING_ROUND_TRIPS
) -> list[tuple[dict[str, Any], str, int]]:
    """The solves :func:`rodimpact.tools.bench_scaling.benchmark_sem_scaling` makes, as (case, method,
    repeats), for the rule's resources (:func:`rodimpact.jobs.resources.estimate_sequence`)."""
    return [
        (case, "sem", 2 * SCALING_MIN_REPEATS)
        for case in (*(shortened_rod(model, n) for n in round_trips), dict(stress))
    ]
