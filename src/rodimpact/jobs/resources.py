"""What one job needs: threads, memory and run time of a solver run, estimated from its case.

Closed forms only (no solve, no mesh): snakemake evaluates them for every job when it plans
the workflow. Each estimate is the job's cost model times :data:`SAFETY`:

    memory   = SAFETY * (SNAKEMAKE_MIB + PYTHON_MIB + solver's own memory)
    run time = SAFETY * (STARTUP_S + solve time * repeats)

with the solver's steps, time and memory from its method's cost model (the registry's
``cost``, in each method's ``cost.py``; the shared pieces in :mod:`rodimpact.solvers.cost`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from typing import Any

from rodimpact.jobs.timing import Timing
from rodimpact.solvers.cost import Cost
from rodimpact.solvers.registry import METHODS

__all__ = ["JobResources", "PRESENTATION", "SAFETY", "estimate_resources", "estimate_sequence", "job_resources"]
__all__ += ["run_cost", "timed_cost"]

#: Factor between every estimate and the cost model (which covers what was measured).
SAFETY = 2.0
#: Floors of every estimate: MB of memory, minutes of run time.
MIN_MEM_MB = 500
MIN_RUNTIME_MIN = 1
#: Memory of the snakemake process that runs a job on a cluster node (it parses the
#: workflow), MiB: 223 MiB measured for ``snakemake -n``.
SNAKEMAKE_MIB = 230.0
#: The job's Python process with numpy, scipy, scikit-fem and h5py imported, MiB (115 measured).
PYTHON_MIB = 130.0
#: Start-up of a job, s: snakemake parsing the workflow (7 s measured), the imports (1.5 s),
#: writing the HDF5 file.
STARTUP_S = 15.0
_MIB = 2.0**20


@dataclass(frozen=True)
class JobResources:
    """Resources of one job, as snakemake's ``threads`` and ``resources`` take them.

    Parameters
    ----------
    threads : int
        Cores (>= 1).
    mem_mb : int
        Memory, MB (>= 1).
    runtime_min : int
        Wall time, minutes (>= 1).
    """

    threads: int
    mem_mb: int
    runtime_min: int

    def __post_init__(self) -> None:
        for name in ("threads", "mem_mb", "runtime_min"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ValueError(f"{name} must be an integer >= 1, got {value!r}")

    def for_attempt(self, attempt: int) -> JobResources:
        """Memory and run time times ``attempt`` (1 for the first try; a retry gets more)."""
        if isinstance(attempt, bool) or not isinstance(attempt, int) or attempt < 1:
            raise ValueError(f"attempt must be an integer >= 1, got {attempt!r}")
        return replace(self, mem_mb=self.mem_mb * attempt, runtime_min=self.runtime_min * attempt)


#: A table or figure job: reads HDF5 runs and renders. Reading all 303 stored runs with
#: their series at once peaks at 340 MiB in 42 s (with the hash checks); the jobs took at
#: most 7.5 s.
PRESENTATION = JobResources(threads=1, mem_mb=1500, runtime_min=10)


def job_resources(costs: Iterable[tuple[Cost, float]], threads: int = 1) -> JobResources:
    """A job running the (cost, repeats) solves one after another: the run times summed, the
    largest memory, :data:`SAFETY` times the cost models, with the floors."""
    costs = list(costs)
    seconds = STARTUP_S + sum(cost.solve_s * repeats for cost, repeats in costs)
    mib = SNAKEMAKE_MIB + PYTHON_MIB + max(cost.mem_mib for cost, _ in costs)
    mem_mb = max(MIN_MEM_MB, 50 * math.ceil(SAFETY * mib * _MIB / 1e6 / 50))
    return JobResources(
        threads=threads, mem_mb=mem_mb, runtime_min=max(MIN_RUNTIME_MIN, math.ceil(SAFETY * seconds / 60.0))
    )


def _timed_repeats(timing: Mapping[str, Any] | None, solve_s: float) -> float:
    """Solve times a timed run takes (see :class:`rodimpact.jobs.timing.Timing`): repeated
    to ``min_repeats`` runs and ``min_total_s``, but not past ``max_total_s``."""
    if timing is None:
        return 1.0
    try:
        spec = Timing(**timing)
    except (TypeError, ValueError) as error:
        raise ValueError(f"timing: {error}") from None
    total = max(spec.min_repeats * solve_s, spec.min_total_s + solve_s)
    total = min(total, spec.max_total_s + solve_s)
    return total / solve_s if solve_s > 0 else float(spec.min_repeats)


def timed_cost(cost: Cost, timing: Mapping[str, Any] | None) -> Cost:
    """The cost of a run timed by ``timing`` (repeated, see :class:`rodimpact.jobs.timing.Timing`)
    as one :class:`Cost`: ``solve_s`` the repeats of the upper-side solve, ``typical_s`` the
    repeats a typical solve takes (a short solve is repeated more often to reach
    ``min_total_s``); ``cost`` itself when ``timing`` is None.

    Raises
    ------
    ValueError
        ``timing`` is invalid (the message starts with ``timing``).
    """
    if timing is None:
        return cost
    upper = cost.solve_s * _timed_repeats(timing, cost.solve_s)
    typical = cost.typical_s * _timed_repeats(timing, cost.typical_s)
    return replace(cost, solve_s=upper, typical_share=typical / upper if upper > 0 else cost.typical_share)


def run_cost(case: Mapping[str, Any], method: str) -> Cost:
    """The cost model of one run of ``method`` on the resolved ``case``.

    Raises
    ------
    ValueError
        As :func:`estimate_resources`.
    """
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method: unknown method {method!r}; known: {', '.join(METHODS)}")
    if not isinstance(case, Mapping):
        raise ValueError(f"case: expected a resolved case mapping, got {type(case).__name__}")
    numerics = case.get("numerics")
    if not isinstance(numerics, Mapping) or not isinstance(numerics.get(method), Mapping):
        raise ValueError(f"case: case {case.get('id')!r} has no numerics for method {method!r}")
    spec = METHODS[method]
    try:
        return spec.estimate(case, numerics[method])
    except (KeyError, TypeError, ArithmeticError, ValueError) as error:
        raise ValueError(f"case: case {case.get('id')!r} cannot be estimated for {method!r}: {error}") from None


def estimate_resources(
    case: Mapping[str, Any], method: str, *, timing: Mapping[str, Any] | None = None
) -> JobResources:
    """Threads, memory and run time of the job that runs ``method`` on ``case``.

    Parameters
    ----------
    case : mapping
        A resolved case (as the rules pass it in ``params.case``), with
        ``numerics[method]``, ``impactor`` and ``rod``.
    method : str
        One of ``sem``, ``sem_paper``, ``fem1d``, ``fem_axi``.
    timing : mapping, optional
        The run is timed (``min_repeats``, ``min_total_s``, ``max_total_s``, s; see
        :class:`rodimpact.jobs.timing.Timing`): the solve is repeated.

    Returns
    -------
    JobResources
        One thread (the solvers are serial; snakemake gives the BLAS libraries the job's
        threads); memory in MB and run time in minutes, :data:`SAFETY` times the cost model,
        at least :data:`MIN_MEM_MB` and :data:`MIN_RUNTIME_MIN`.

    Raises
    ------
    ValueError
        ``method`` is unknown, ``case`` is not a resolved case with numerics for it, or
        ``timing`` is invalid; the message starts with the argument's name.
    """
    cost = run_cost(case, method)
    return job_resources([(cost, _timed_repeats(timing, cost.solve_s))])


def estimate_sequence(
    runs: Iterable[tuple[Mapping[str, Any], str, int]],
    *,
    timing: Mapping[str, Any] | None = None,
    extra: Iterable[Cost] = (),
) -> JobResources:
    """Resources of one job that solves several runs one after another (a benchmark, a batch).

    Parameters
    ----------
    runs : iterable of (case, method, repeats)
        Each solve and how many times it runs (>= 1).
    timing : mapping, optional
        The runs are timed (as in :func:`estimate_resources`): each is repeated on top.
    extra : iterable of Cost
        What the job computes besides its solves, once each (a curve a sweep point's law needs,
        :func:`rodimpact.solvers.fem_axi.cost.fem_axi_indentation_cost`).

    Returns
    -------
    JobResources
        The run times summed, the largest memory (each solve's memory is freed after it).

    Raises
    ------
    ValueError
        ``runs`` is empty, or one of its cases or methods is invalid (as
        :func:`estimate_resources`).
    """
    costs = []
    for case, method, repeats in runs:
        if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
            raise ValueError(f"runs: repeats must be an integer >= 1, got {repeats!r}")
        cost = run_cost(case, method)
        costs.append((cost, repeats * _timed_repeats(timing, cost.solve_s)))
    if not costs:
        raise ValueError("runs: no run given")
    return job_resources([*costs, *((cost, 1.0) for cost in extra)])
