"""Benchmarks of the solvers: wall time against accuracy (``make bench``, not tests)."""

from __future__ import annotations

import logging
import os
import platform
import time
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd

from .fem import FEM1DOptions, solve_fem1d
from .sem import ImpactProblem, SEMOptions, solve_sem

__all__ = ["benchmark_fem1d", "benchmark_fem_axi", "benchmark_sem", "machine_info"]

log = logging.getLogger(__name__)


def machine_info() -> dict[str, Any]:
    """Where a benchmark ran."""
    return {"machine": platform.node(), "processor": platform.processor() or platform.machine(),
            "cpu_count": os.cpu_count(), "python": platform.python_version()}


def _timed(problem: ImpactProblem, options: Any, repeats: int, solver=solve_sem):
    best, result = np.inf, None
    for _ in range(repeats):
        started = time.perf_counter()
        result = solver(problem, options)
        best = min(best, time.perf_counter() - started)
    return result, best


def _rel_errors(result, ref) -> tuple[float, float]:
    tc = abs(result.contact_time_s / ref.contact_time_s - 1.0)
    if len(result.peak_force_N) != len(ref.peak_force_N):
        return tc, np.inf
    return tc, float(np.max(np.abs(result.peak_force_N / ref.peak_force_N - 1.0)))


def benchmark_sem(case: Mapping[str, Any], *, implicit_steps: Sequence[int] = (50, 100, 200, 400, 800, 1600, 2000, 3200),
                  paper_steps: Sequence[int] = (1000, 2000, 4000, 8000, 16000, 20000, 32000, 64000),
                  reference_steps: int = 64000, repeats: int = 3) -> pd.DataFrame:
    """Wall time and relative error of both SEM schemes at several steps.

    The reference is the implicit scheme at ``reference_steps`` steps per Hertz time; its
    own error is estimated by Richardson from the run at half as many steps (second order)
    and reported in the ``reference_error`` column.

    Returns
    -------
    DataFrame
        One row per (scheme, steps_per_contact): dt_s, n_steps, wall_time_s (best of
        ``repeats``), contact_time_rel_error, peak_force_rel_error (max over maxima),
        energy_error, reference_error, and the machine it ran on.
    """
    problem = ImpactProblem.from_case(case)
    ref = solve_sem(problem, SEMOptions(steps_per_contact=reference_steps))
    half = solve_sem(problem, SEMOptions(steps_per_contact=reference_steps // 2))
    ref_error = max(_rel_errors(half, ref)) / 3.0
    rows = []
    for scheme, steps in (("implicit", implicit_steps), ("paper", paper_steps)):
        for n in steps:
            result, wall = _timed(problem, SEMOptions(scheme=scheme, steps_per_contact=n), repeats)
            tc, peak = _rel_errors(result, ref)
            rows.append({"case": case["id"], "scheme": scheme, "steps_per_contact": n, "dt_s": result.dt_s,
                         "n_steps": result.n_steps, "wall_time_s": wall, "contact_time_rel_error": tc,
                         "peak_force_rel_error": peak, "energy_error": result.energy_error,
                         "reference_error": ref_error, **machine_info()})
            log.info("%s n=%d: %.4f s, errors %.2e %.2e", scheme, n, wall, tc, peak)
    return pd.DataFrame(rows)


def benchmark_fem1d(case: Mapping[str, Any], *, settings: Sequence[tuple[str, int | None, int]] = (
        ("P1", 20, 500), ("P1", 40, 1000), ("P1", 80, 2000), ("P2", 10, 500), ("P2", 20, 1000),
        ("P2", None, 2000), ("P2", 80, 4000)), repeats: int = 2) -> pd.DataFrame:
    """Wall time of fem1d and its agreement with a converged SEM run, per setting.

    Parameters
    ----------
    settings : sequence of (element, elements or None, steps_per_contact)
        None elements: the shipped rule (points_per_wavelength).

    Returns
    -------
    DataFrame
        One row per setting: element, n_elements, n_dofs, steps_per_contact, n_steps,
        wall_time_s (best of ``repeats``), contact_time_rel_diff and peak_force_rel_diff
        (max over maxima; inf when the number of maxima differs) against the SEM at 16000
        steps per Hertz time, and the machine.
    """
    problem = ImpactProblem.from_case(case)
    ref = solve_sem(problem, SEMOptions(steps_per_contact=16000))
    rows = []
    for element, n, steps in settings:
        options = FEM1DOptions(element=element, elements=n, steps_per_contact=steps)
        result, wall = _timed(problem, options, repeats, solver=solve_fem1d)
        tc, peak = _rel_errors(result, ref)
        rows.append({"case": case["id"], "method": "fem1d", "element": element,
                     "n_elements": result.extra["n_elements"], "n_dofs": result.extra["n_dofs"],
                     "steps_per_contact": steps, "n_steps": result.n_steps, "wall_time_s": wall,
                     "contact_time_rel_diff": tc, "peak_force_rel_diff": peak, **machine_info()})
        log.info("fem1d %s n=%s steps=%d: %.3f s, diffs %.2e %.2e", element, n, steps, wall, tc, peak)
    return pd.DataFrame(rows)


def _fem_axi_task(case: Mapping[str, Any]) -> dict[str, Any]:
    """One fem_axi run in a fresh process: its wall time and its own peak memory."""
    import resource

    from .fem.fem_axi import AxiImpact, FEMAxiOptions, solve_fem_axi

    started = time.perf_counter()
    result = solve_fem_axi(AxiImpact.from_case(case), FEMAxiOptions.from_mapping(case["numerics"]["fem_axi"]),
                           stations=case.get("stations", ()))
    wall = time.perf_counter() - started
    sem = solve_sem(ImpactProblem.from_case(case), SEMOptions(steps_per_contact=4000))
    return {"case": case["id"], "method": "fem_axi", "success": result.success,
            "elements_across": case["numerics"]["fem_axi"]["elements_across"],
            "steps_per_contact": case["numerics"]["fem_axi"]["steps_per_contact"],
            "n_dofs": result.extra["rod_dofs"] + result.extra["impactor_dofs"], "n_steps": result.n_steps,
            "wall_time_s": wall, "peak_memory_MiB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
            "contact_time_us": 1e6 * result.contact_time_s,
            "contact_time_vs_sem_pct": 100 * (result.contact_time_s / sem.contact_time_s - 1), **machine_info()}


def benchmark_fem_axi(cases: Sequence[Mapping[str, Any]]) -> pd.DataFrame:
    """fem_axi at each case's shipped numerics, one fresh process per run (one at a time).

    Returns
    -------
    DataFrame
        One row per case: DOFs (rod + impactor), steps, wall time, the process's peak
        resident memory (MiB, includes the Python interpreter and libraries), contact time
        and its difference from the SEM.
    """
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import get_context

    rows = []
    for case in cases:
        # fork, not spawn: a spawned child would re-run the calling (snakemake) script
        with ProcessPoolExecutor(max_workers=1, mp_context=get_context("fork")) as pool:
            row = pool.submit(_fem_axi_task, dict(case)).result()
        log.info("fem_axi %s: %.1f s, %d DOFs, %.0f MiB", row["case"], row["wall_time_s"], row["n_dofs"],
                 row["peak_memory_MiB"])
        rows.append(row)
    return pd.DataFrame(rows)
