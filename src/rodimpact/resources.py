"""What one job needs: threads, memory and run time of a solver run, estimated from its case.

Closed forms only (no solve, no mesh): snakemake evaluates them for every job when it plans
the workflow. Each estimate is the job's cost model times :data:`SAFETY`:

    memory   = SAFETY * (SNAKEMAKE_MIB + PYTHON_MIB + solver's own memory)
    run time = SAFETY * (STARTUP_S + solve time * repeats)

with the solver's memory and time from the quantities that drive them:

- ``sem``, ``sem_paper``: the steps (the step from the case, or the automatic step's
  estimate; the steps of the step-doubling check on top) and, per step, one term per wave
  round trip 2T since the impact (the SEM's history sum): a contact of many round trips
  costs more per step;
- ``fem1d``: elements x steps (the element count and the step from the case, as the solver
  chooses them);
- ``fem_axi``: an upper bound of the mesh's DOFs (:func:`fem_axi_dofs`) for the memory,
  DOFs x steps for the time.

The steps run to the end of the contact plus the solver's end test; the contact's duration
is :meth:`rodimpact.sem.ImpactProblem.contact_time_estimate` (an upper-side estimate), the
run stops at ``max_time_factor`` of it (and at ``max_steps``) at the latest.

The per-unit costs are calibrated on the development machine (one core of a 2-core x86_64
VM): the cost model's time covers every one of the 303 stored runs of results/runs,
results/convergence, results/stress and results/stability_map (their ``wall_time_s``, 1.46
times at least), its step counts their ``n_steps``; its memory covers the peak resident
memory of fresh processes re-running the 15 heaviest (README, "Resources and running on a
cluster").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Iterable, Mapping

__all__ = ["JobResources", "PRESENTATION", "SAFETY", "estimate_resources", "estimate_sequence", "fem_axi_dofs"]

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
#: Every solve's fixed part, s: options, the end test's look-ahead, the result's arrays.
SOLVE_S = 0.5

#: SEM, s per step and s per step and wave round trip since the impact (history terms);
#: least-squares fits of the stored runs give 8 and 3 us (implicit), 2 and 2 us (paper);
#: the largest per step: 250 us at 17 round trips (a run spending its step budget).
SEM_STEP_S = 20e-6
SEM_REFLECTION_S = 10e-6
#: SEM memory per stored step (Python lists of the state and the history, then the
#: result's arrays; the step-doubling check's run is alive next to it), bytes: 750 at most
#: measured (613479 steps, 549 MiB).
SEM_STEP_BYTES = 1000.0
#: Hertz times within which a contact on a rod that carries the Hertz force is over.
SHORT_CONTACT = 1.5
#: The automatic step's total work in steps of its final run (the run at twice the step,
#: 1.37 measured at most with the step below).
SEM_AUTO_WORK = 1.5
#: fem1d: s per step, s per step and DOF (measured at most 330 us and 0.3 us with 47000
#: DOFs), bytes per step and per DOF (830 and 800 measured).
FEM1D_STEP_S = 150e-6
FEM1D_DOF_STEP_S = 0.5e-6
FEM1D_STEP_BYTES = 1000.0
FEM1D_DOF_BYTES = 2000.0
#: fem_axi: s per DOF of the set-up (meshes, factorisations), s per step and DOF (3.8e-7 to
#: 5.7e-7 measured), bytes per DOF of the bound (sparse factors, the contact columns G, the
#: meshes and bases: 3.7 KiB per actual DOF measured, 49511 DOFs in 281 MiB).
FEM_AXI_SETUP_DOF_S = 1e-4
FEM_AXI_DOF_STEP_S = 7e-7
FEM_AXI_DOF_BYTES = 6000.0
#: Triangles per (fine size)^2 of area in the refined zones of fem_axi's meshes: longest-edge
#: refinement leaves edges between half the target and the target (4 to 16 for right
#: triangles); 7 to 22 measured, the most at coarse levels, where constant terms weigh.
FEM_AXI_TRIANGLES = 16.0
#: Triangles a body's mesh has beyond the model (corners, the sphere's chords).
FEM_AXI_EXTRA_TRIANGLES = 600.0

_MIB = 2.0**20
_METHODS = ("sem", "sem_paper", "fem1d", "fem_axi")


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

    def for_attempt(self, attempt: int) -> "JobResources":
        """Memory and run time times ``attempt`` (1 for the first try; a retry gets more)."""
        if isinstance(attempt, bool) or not isinstance(attempt, int) or attempt < 1:
            raise ValueError(f"attempt must be an integer >= 1, got {attempt!r}")
        return replace(self, mem_mb=self.mem_mb * attempt, runtime_min=self.runtime_min * attempt)


#: A table or figure job: reads HDF5 runs and renders. Reading all 303 stored runs with
#: their series at once peaks at 340 MiB in 42 s (with the hash checks); the jobs took at
#: most 7.5 s.
PRESENTATION = JobResources(threads=1, mem_mb=1500, runtime_min=10)


@dataclass(frozen=True)
class _Cost:
    """The cost model of one solve: its steps, its time (s) and its own memory (MiB)."""

    steps: float
    solve_s: float
    mem_mib: float


def _job(costs: Iterable[tuple[_Cost, float]], threads: int = 1) -> JobResources:
    """A job running the (cost, repeats) solves one after another."""
    costs = list(costs)
    seconds = STARTUP_S + sum(cost.solve_s * repeats for cost, repeats in costs)
    mib = SNAKEMAKE_MIB + PYTHON_MIB + max(cost.mem_mib for cost, _ in costs)
    mem_mb = max(MIN_MEM_MB, 50 * math.ceil(SAFETY * mib * _MIB / 1e6 / 50))
    return JobResources(threads=threads, mem_mb=mem_mb,
                        runtime_min=max(MIN_RUNTIME_MIN, math.ceil(SAFETY * seconds / 60.0)))


def _timed_repeats(timing: Mapping[str, Any] | None, solve_s: float) -> float:
    """Solve times a timed run takes (see :class:`rodimpact.runner.Timing`): repeated to
    ``min_repeats`` runs and ``min_total_s``, but not past ``max_total_s``."""
    if timing is None:
        return 1.0
    from .runner import Timing

    try:
        spec = Timing(**timing)
    except (TypeError, ValueError) as error:
        raise ValueError(f"timing: {error}") from None
    total = max(spec.min_repeats * solve_s, spec.min_total_s + solve_s)
    total = min(total, spec.max_total_s + solve_s)
    return total / solve_s if solve_s > 0 else float(spec.min_repeats)


def _contact_s(problem: Any) -> float:
    """Upper-side duration of all contacts, s: :meth:`contact_time_estimate` (Hertz time,
    the rod's spring, a wave round trip 2T); on a rod that carries the Hertz force (Z v0 >=
    P_H) and whose round trip is longer than :data:`SHORT_CONTACT` Hertz times, that many
    Hertz times: the one contact is over before any reflection comes back (measured: at most
    1.23 Hertz times)."""
    estimate = problem.contact_time_estimate()
    hertz = problem.rigid_hertz
    short = SHORT_CONTACT * hertz.contact_time_s
    if problem.rod.impedance * problem.velocity_m_s >= hertz.peak_force_N and short < problem.rod.reflection_period:
        return min(estimate, short)
    return estimate


def _horizon(problem: Any, numerics: Mapping[str, Any], contact_s: float, end_test_s: float) -> float:
    """Time a run steps through, s: the contacts and the end test after them; at most the
    solver's limit, ``max_time_factor`` contact time estimates."""
    limit = float(numerics.get("max_time_factor") or 100.0) * problem.contact_time_estimate()
    return min(contact_s + end_test_s, limit)


def _sem(case: Mapping[str, Any], method: str) -> _Cost:
    from .sem import ImpactProblem, SEMOptions
    from .sem.stability import tolerance_step

    problem = ImpactProblem.from_case(case)
    options = SEMOptions.from_mapping(case["numerics"][method], "implicit" if method == "sem" else "paper")
    period = problem.rod.reflection_period
    # the run ends with the contact (its end test looks ahead without stepping)
    horizon = _horizon(problem, case["numerics"][method], _contact_s(problem), 0.0)
    step, work = options.step(problem), 1.0
    if options.automatic_step:
        # the first guess may be floored at a step count; the check halves it down to the
        # step the tolerance asks for
        step, work = min(step, tolerance_step(problem, options.tolerance)), SEM_AUTO_WORK
    stored = min(horizon / step, float(options.max_steps)) + 1.0
    rounds = 1.0 + (0.5 * horizon / period if math.isfinite(period) else 0.0)
    stations = len(case.get("stations", ()))
    return _Cost(steps=stored, solve_s=SOLVE_S + work * stored * (SEM_STEP_S + SEM_REFLECTION_S * rounds),
                 mem_mib=stored * (SEM_STEP_BYTES + 64.0 * stations) / _MIB)


def _fem1d(case: Mapping[str, Any]) -> _Cost:
    from .fem import FEM1DOptions
    from .sem import ImpactProblem

    problem = ImpactProblem.from_case(case)
    options = FEM1DOptions.from_mapping(case["numerics"]["fem1d"])
    elements, step, _ = options.resolve(problem)
    dofs = (1 if options.element == "P1" else 2) * elements + 1
    # its end test: a fixed rod's energy bound (measured: within 2 contact times and half a
    # round trip), a free rod's 4 round trips
    contact, period = _contact_s(problem), problem.rod.reflection_period
    end_test = min(3.0 * contact, period) if problem.rod.far_end == "fixed" else 4.0 * period
    horizon = _horizon(problem, case["numerics"]["fem1d"], contact, end_test)
    steps = horizon / step + 1.0
    stations = len(case.get("stations", ()))
    return _Cost(steps=steps, solve_s=SOLVE_S + steps * (FEM1D_STEP_S + FEM1D_DOF_STEP_S * dofs),
                 mem_mib=(steps * (FEM1D_STEP_BYTES + 64.0 * stations) + dofs * FEM1D_DOF_BYTES) / _MIB)


def _refined_triangles(extent: float, coarse: float) -> float:
    """Triangles, per :data:`FEM_AXI_TRIANGLES`, of a quarter plane meshed at the fine size
    (the unit of length) within ``extent`` of the corner, then growing by half the distance
    beyond it up to ``coarse``: pi/4 extent^2 + pi ((extent - 2)(1 - 1/coarse) + 2 ln coarse)."""
    count = math.pi / 4.0 * extent**2
    if coarse > 1.0:
        count += math.pi * (max(extent - 2.0, 0.0) * (1.0 - 1.0 / coarse) + 2.0 * math.log(coarse))
    return count


def fem_axi_dofs(case: Mapping[str, Any]) -> int:
    """Upper-side estimate of the DOFs of fem_axi's two meshes (rod and impactor), closed form.

    The meshes (:mod:`rodimpact.fem.meshes`) are fine (a_H / ``elements_across``, a_H the
    Hertz contact radius) within ``contact_extent`` a_H of the contact point, graded beyond
    at half the distance up to a coarse size (a/4 by a/2 cells in the rod of radius a, R/4
    in the impactor), and coarse elsewhere. Vector P2 elements carry about 4 DOFs per
    triangle, P1 about 1. The 40 stored fem_axi runs have 0.48 to 0.90 of it (free DOFs).

    Parameters
    ----------
    case : mapping
        A resolved case (``numerics.fem_axi``, ``impactor``, ``rod``).

    Returns
    -------
    int
        DOFs (rod + impactor), before the fixed ones are removed.
    """
    from .fem.fem_axi import AxiImpact, FEMAxiOptions

    problem = AxiImpact.from_case(case)
    options = FEMAxiOptions.from_mapping(case["numerics"]["fem_axi"])
    _, contact_radius = problem.hertz_estimates()
    fine = contact_radius / options.elements_across
    extent = options.contact_extent * options.elements_across
    a, length = problem.rod_radius_m, problem.rod_length_m
    rod = (_refined_triangles(extent, a / 4.0 / fine) * FEM_AXI_TRIANGLES
           + 2.0 * 4.0 * math.ceil(2.0 * length / a))
    height = 2.0 if problem.body == "sphere" else min(options.cap_height, 1.0)
    radius = problem.sphere_radius_m
    area = math.pi / 4.0 * (2.0 if problem.body == "sphere" else 1.0)  # R^2
    impactor = (_refined_triangles(extent, radius * min(height, 1.0) / 4.0 / fine) * FEM_AXI_TRIANGLES
                + 2.0 * area * 16.0 / min(height, 1.0) ** 2)
    per_triangle = 4.0 if options.element == "P2" else 1.0
    return int(math.ceil(per_triangle * (rod + impactor + 2.0 * FEM_AXI_EXTRA_TRIANGLES)))


def _fem_axi(case: Mapping[str, Any]) -> _Cost:
    from .fem.fem_axi import AxiImpact, FEMAxiOptions
    from .sem import ImpactProblem

    numerics = case["numerics"]["fem_axi"]
    options = FEMAxiOptions.from_mapping(numerics)
    axi = AxiImpact.from_case(case)
    t_hertz, _ = axi.hertz_estimates()
    problem = ImpactProblem.from_case(case)
    step = options.dt_s if options.dt_s is not None else t_hertz / options.steps_per_contact
    # its end test waits max(2T, a quarter of the contact) after the contact
    contact = _contact_s(problem)
    horizon = _horizon(problem, numerics, contact, max(problem.rod.reflection_period, 0.25 * contact))
    dofs = fem_axi_dofs(case)
    steps = horizon / step + 1.0
    return _Cost(steps=steps, solve_s=SOLVE_S + dofs * (FEM_AXI_SETUP_DOF_S + FEM_AXI_DOF_STEP_S * steps),
                 mem_mib=dofs * FEM_AXI_DOF_BYTES / _MIB)


def _cost(case: Mapping[str, Any], method: str) -> _Cost:
    if not isinstance(method, str) or method not in _METHODS:
        raise ValueError(f"method: unknown method {method!r}; known: {', '.join(_METHODS)}")
    if not isinstance(case, Mapping):
        raise ValueError(f"case: expected a resolved case mapping, got {type(case).__name__}")
    numerics = case.get("numerics")
    if not isinstance(numerics, Mapping) or not isinstance(numerics.get(method), Mapping):
        raise ValueError(f"case: case {case.get('id')!r} has no numerics for method {method!r}")
    try:
        if method == "fem1d":
            return _fem1d(case)
        if method == "fem_axi":
            return _fem_axi(case)
        return _sem(case, method)
    except (KeyError, TypeError, ArithmeticError, ValueError) as error:
        raise ValueError(f"case: case {case.get('id')!r} cannot be estimated for {method!r}: {error}") from None


def estimate_resources(case: Mapping[str, Any], method: str, *,
                       timing: Mapping[str, Any] | None = None) -> JobResources:
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
        :class:`rodimpact.runner.Timing`): the solve is repeated.

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
    cost = _cost(case, method)
    return _job([(cost, _timed_repeats(timing, cost.solve_s))])


def estimate_sequence(runs: Iterable[tuple[Mapping[str, Any], str, int]]) -> JobResources:
    """Resources of one job that solves several runs one after another (a benchmark).

    Parameters
    ----------
    runs : iterable of (case, method, repeats)
        Each solve and how many times it runs (>= 1).

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
        costs.append((_cost(case, method), float(repeats)))
    if not costs:
        raise ValueError("runs: no run given")
    return _job(costs)
