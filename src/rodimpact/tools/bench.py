"""Benchmarks of the solvers: wall time against accuracy (``make bench``, not tests)."""

from __future__ import annotations

import logging
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.jobs.machine import machine_info
from rodimpact.jobs.resources import estimate_resources
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.fem1d.solver import solve_fem1d
from rodimpact.solvers.fem_axi.cost import fem_axi_dofs
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import solve_fem_axi
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.solver import solve_sem
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.sidecar import write_provenance
from rodimpact.tools.bench_plan import (
    FAR_BAR_CHECK_CASES,
    FEM1D_REFERENCE_STEPS,
    FEM1D_REPEATS,
    FEM1D_SETTINGS,
    FEM_AXI_SEM_STEPS,
    SEM_IMPLICIT_STEPS,
    SEM_PAPER_STEPS,
    SEM_REFERENCE_STEPS,
    SEM_REPEATS,
)

__all__ = [
    "STACK_RUN_TARGET_S",
    "benchmark_fem1d",
    "benchmark_fem_axi",
    "benchmark_sem",
    "resource_margins",
    "stack_runs",
    "write_benchmark",
]

log = logging.getLogger(__name__)

#: The speed target of a fem_axi run of a row with a stack of several layers (the sensor as
#: built) at the shipped level, s, on the 2-core machine the project is built on.
STACK_RUN_TARGET_S = 15.0


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


def benchmark_sem(
    case: Mapping[str, Any],
    *,
    implicit_steps: Sequence[int] = SEM_IMPLICIT_STEPS,
    paper_steps: Sequence[int] = SEM_PAPER_STEPS,
    reference_steps: int = SEM_REFERENCE_STEPS,
    repeats: int = SEM_REPEATS,
) -> pd.DataFrame:
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
    for options_class, steps in ((SEMOptions, implicit_steps), (PaperSEMOptions, paper_steps)):
        scheme = options_class.scheme
        for n in steps:
            result, wall = _timed(problem, options_class(steps_per_contact=n), repeats)
            tc, peak = _rel_errors(result, ref)
            rows.append(
                {
                    "case": case["id"],
                    "scheme": scheme,
                    "steps_per_contact": n,
                    "dt_s": result.dt_s,
                    "n_steps": result.n_steps,
                    "wall_time_s": wall,
                    "contact_time_rel_error": tc,
                    "peak_force_rel_error": peak,
                    "energy_error": result.energy_error,
                    "reference_error": ref_error,
                    **machine_info(),
                }
            )
            log.info("%s n=%d: %.4f s, errors %.2e %.2e", scheme, n, wall, tc, peak)
    return pd.DataFrame(rows)


def benchmark_fem1d(
    case: Mapping[str, Any],
    *,
    settings: Sequence[tuple[str, int | None, int]] = FEM1D_SETTINGS,
    repeats: int = FEM1D_REPEATS,
) -> pd.DataFrame:
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
    ref = solve_sem(problem, SEMOptions(steps_per_contact=FEM1D_REFERENCE_STEPS))
    rows = []
    for element, n, steps in settings:
        options = FEM1DOptions(element=element, elements=n, steps_per_contact=steps)
        result, wall = _timed(problem, options, repeats, solver=solve_fem1d)
        tc, peak = _rel_errors(result, ref)
        rows.append(
            {
                "case": case["id"],
                "method": "fem1d",
                "element": element,
                "n_elements": result.extra["n_elements"],
                "n_dofs": result.extra["n_dofs"],
                "steps_per_contact": steps,
                "n_steps": result.n_steps,
                "wall_time_s": wall,
                "contact_time_rel_diff": tc,
                "peak_force_rel_diff": peak,
                **machine_info(),
            }
        )
        log.info("fem1d %s n=%s steps=%d: %.3f s, diffs %.2e %.2e", element, n, steps, wall, tc, peak)
    return pd.DataFrame(rows)


def _fem_axi_task(case: Mapping[str, Any]) -> dict[str, Any]:
    """One fem_axi run in a fresh process: its wall time and its own peak memory."""
    import resource

    started = time.perf_counter()
    problem = AxiImpact.from_case(case)
    result = solve_fem_axi(
        problem, FEMAxiOptions.from_settings(case["numerics"]["fem_axi"]), stations=case.get("stations", ())
    )
    wall = time.perf_counter() - started
    sem = solve_sem(ImpactProblem.from_case(case), SEMOptions(steps_per_contact=FEM_AXI_SEM_STEPS))
    full = _far_bar_check(case, result) if case["id"] in FAR_BAR_CHECK_CASES else {}
    return {
        "case": case["id"],
        "method": "fem_axi",
        "success": result.success,
        "elements_across": case["numerics"]["fem_axi"]["elements_across"],
        "layers": 0 if problem.stack is None else len(problem.stack.layers),
        "steps_per_contact": case["numerics"]["fem_axi"]["steps_per_contact"],
        "n_dofs": result.extra["rod_dofs"] + result.extra["impactor_dofs"],
        "n_steps": result.n_steps,
        "wall_time_s": wall,
        "peak_memory_MiB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        "contact_time_us": 1e6 * result.contact_time_s,
        "contact_time_vs_sem_pct": 100 * (result.contact_time_s / sem.contact_time_s - 1),
        **full,
        **machine_info(),
    }


def _far_bar_check(case: Mapping[str, Any], result: Any) -> dict[str, Any]:
    """The same run with the whole rod a continuum: its time, and how far the far bar's run is
    from it (contact time, each force maximum, the first station's displacement), percent."""
    options = FEMAxiOptions.from_settings({**case["numerics"]["fem_axi"], "continuum_diameters": None})
    started = time.perf_counter()
    full = solve_fem_axi(AxiImpact.from_case(case), options, stations=case.get("stations", ()))
    row = {
        "wall_time_full_continuum_s": time.perf_counter() - started,
        "n_dofs_full_continuum": full.extra["rod_dofs"] + full.extra["impactor_dofs"],
        "contact_time_vs_full_continuum_pct": 100 * (result.contact_time_s / full.contact_time_s - 1),
    }
    if len(result.peak_force_N) == len(full.peak_force_N):
        deviation = 100 * (result.peak_force_N / full.peak_force_N - 1)
        row["maxima_vs_full_continuum_pct"] = " ".join(f"{d:.3g}" for d in deviation)
    else:
        row["maxima_vs_full_continuum_pct"] = f"{len(result.peak_force_N)} maxima against {len(full.peak_force_N)}"
    station = "station_displacement"
    if station in result.extra_series and station in full.extra_series:
        ours, theirs = result.extra_series[station][0][:, 0], full.extra_series[station][0][:, 0]
        n = min(len(ours), len(theirs))
        row["station_vs_full_continuum_pct"] = 100 * np.max(np.abs(ours[:n] - theirs[:n])) / np.max(np.abs(theirs))
    return row


def benchmark_fem_axi(cases: Sequence[Mapping[str, Any]]) -> pd.DataFrame:
    """fem_axi at each case's shipped numerics, one fresh process per run (one at a time).

    Returns
    -------
    DataFrame
        One row per case: DOFs (rod + impactor), steps, wall time, the process's peak
        resident memory (MiB, includes the Python interpreter and libraries), contact time
        and its difference from the SEM; next to them what the workflow requests for the
        run's job (:func:`rodimpact.jobs.resources.estimate_resources`): ``n_dofs_estimate``,
        ``mem_estimate_MiB``, ``runtime_estimate_s`` and the margins ``mem_margin`` and
        ``runtime_margin`` (estimate over measured; the estimate covers the whole job, with
        snakemake's process and start-up, the measurement the solve).
    """
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import get_context

    rows = []
    for case in cases:
        # fork, not spawn: a spawned child would re-run the calling (snakemake) script
        with ProcessPoolExecutor(max_workers=1, mp_context=get_context("fork")) as pool:
            row = pool.submit(_fem_axi_task, dict(case)).result()
        estimate = estimate_resources(case, "fem_axi")
        row.update(
            n_dofs_estimate=fem_axi_dofs(case),
            mem_estimate_MiB=estimate.mem_mb * 1e6 / 2**20,
            runtime_estimate_s=60.0 * estimate.runtime_min,
        )
        row.update(
            mem_margin=row["mem_estimate_MiB"] / row["peak_memory_MiB"],
            runtime_margin=row["runtime_estimate_s"] / row["wall_time_s"],
        )
        log.info(
            "fem_axi %s: %.1f s, %d DOFs, %.0f MiB; requested %.0f s (x%.1f), %.0f MiB (x%.1f)",
            row["case"],
            row["wall_time_s"],
            row["n_dofs"],
            row["peak_memory_MiB"],
            row["runtime_estimate_s"],
            row["runtime_margin"],
            row["mem_estimate_MiB"],
            row["mem_margin"],
        )
        rows.append(row)
    return pd.DataFrame(rows)


def write_benchmark(frame: pd.DataFrame, *, csv: str | Path, provenance: str | Path) -> None:
    """Write a benchmark table (CSV, atomically) and its provenance sidecar (code version and
    the SHA-256 of the CSV; a benchmark reads no stored run)."""
    with atomic_output(csv) as tmp:
        frame.to_csv(tmp, index=False, float_format="%.6g")
    write_provenance(provenance, [], [csv])


def resource_margins(frame: pd.DataFrame) -> pd.DataFrame:
    """The fem_axi rows of a ``fem.csv`` benchmark: measured time and memory, what the
    workflow requests, and the margins (estimate over measured)."""
    missing = {"mem_estimate_MiB", "runtime_estimate_s"} - set(frame.columns)
    if missing:
        raise ValueError(f"frame: no resource estimates (columns {sorted(missing)}); rerun make bench")
    columns = [
        "case",
        "n_dofs",
        "n_dofs_estimate",
        "wall_time_s",
        "runtime_estimate_s",
        "runtime_margin",
        "peak_memory_MiB",
        "mem_estimate_MiB",
        "mem_margin",
    ]
    return frame.loc[frame["method"] == "fem_axi", columns].reset_index(drop=True)


def stack_runs(frame: pd.DataFrame) -> pd.DataFrame:
    """The fem_axi rows of a ``fem.csv`` benchmark whose case has a stack of several layers,
    with ``within_target`` (wall time at most :data:`STACK_RUN_TARGET_S`)."""
    if "layers" not in frame.columns:
        raise ValueError("frame: no 'layers' column; rerun make bench")
    rows = frame.loc[
        (frame["method"] == "fem_axi") & (frame["layers"] > 1), ["case", "layers", "n_dofs", "wall_time_s"]
    ]
    return rows.assign(within_target=rows["wall_time_s"] <= STACK_RUN_TARGET_S).reset_index(drop=True)


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m rodimpact.tools.bench results/benchmarks/fem.csv``: log the resource margins,
    and check the stack rows' speed target (exit status 1 when a row misses it)."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m rodimpact.tools.bench", description=main.__doc__)
    parser.add_argument("csv", help="a fem.csv written by the bench_fem rule")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    try:
        frame = pd.read_csv(args.csv)
        table, stacks = resource_margins(frame), stack_runs(frame)
    except (OSError, ValueError) as error:
        log.error("rodimpact.tools.bench: %s: %s", args.csv, error)
        return 1
    log.info(
        "fem_axi: measured against requested (margin = requested / measured)\n%s",
        table.to_string(index=False, float_format=lambda x: f"{x:.4g}"),
    )
    log.info("smallest margins: run time x%.1f, memory x%.1f", table["runtime_margin"].min(), table["mem_margin"].min())
    if not stacks.empty:
        log.info(
            "fem_axi with a stack of layers: at most %.1f s a run (target %g s)\n%s",
            stacks["wall_time_s"].max(),
            STACK_RUN_TARGET_S,
            stacks.to_string(index=False, float_format=lambda x: f"{x:.4g}"),
        )
        if not stacks["within_target"].all():
            log.error(
                "rodimpact.tools.bench: %d stack run(s) over the %g s target",
                int((~stacks["within_target"]).sum()),
                STACK_RUN_TARGET_S,
            )
            return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
