"""Run one method on one resolved case and store it: the science behind the ``solve`` rule."""

from __future__ import annotations

import contextlib
import logging
import math
import os
import platform
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np

from .fem import FEM1DOptions, solve_fem1d
from .fem.fem_axi import AxiImpact, FEMAxiOptions, solve_fem_axi
from .sem import ImpactProblem, SEMOptions, solve_sem
from .sem.solver import check_paper_step
from .store import write_run

__all__ = ["RUNNERS", "SolverFailed", "Timing", "check_run", "machine_description", "run_case",
           "run_to_file", "run_config"]

log = logging.getLogger(__name__)


class SolverFailed(RuntimeError):
    """A solver returned ``success=False``: nothing is written."""


def _sem(scheme: str) -> Callable[[Mapping[str, Any], Mapping[str, Any]], Any]:
    def run(case: Mapping[str, Any], numerics: Mapping[str, Any]) -> Any:
        return solve_sem(ImpactProblem.from_case(case), SEMOptions.from_mapping(numerics, scheme),
                         stations=case.get("stations", ()))

    return run


def _fem1d(case: Mapping[str, Any], numerics: Mapping[str, Any]) -> Any:
    return solve_fem1d(ImpactProblem.from_case(case), FEM1DOptions.from_mapping(numerics),
                       stations=case.get("stations", ()))


#: method name (as in the case's ``methods``) -> callable(case, numerics) -> result object
#: with ``success``, ``status``, ``message``, ``summary()`` and ``series(outputs)``.
RUNNERS: dict[str, Callable[[Mapping[str, Any], Mapping[str, Any]], Any]] = {
    "sem": _sem("implicit"),
    "sem_paper": _sem("paper"),
    "fem1d": _fem1d,
    "fem_axi": lambda case, numerics: solve_fem_axi(AxiImpact.from_case(case), FEMAxiOptions.from_mapping(numerics),
                                                    stations=case.get("stations", ())),
}


#: method -> callable(numerics) building its options object (raises ValueError on a bad one)
_OPTIONS: dict[str, Callable[[Mapping[str, Any]], Any]] = {
    "sem": lambda numerics: SEMOptions.from_mapping(numerics, "implicit"),
    "sem_paper": lambda numerics: SEMOptions.from_mapping(numerics, "paper"),
    "fem1d": FEM1DOptions.from_mapping,
    "fem_axi": FEMAxiOptions.from_mapping,
}


def check_run(case: Mapping[str, Any], method: str) -> None:
    """Check, without solving, that ``method`` can run ``case`` with its numerics.

    Builds the method's options; for ``sem_paper`` also checks its step against the
    scheme's stability limit.

    Raises
    ------
    ValueError
        The message starts with the name of the offending setting.
    """
    numerics = case["numerics"][method]
    options = _OPTIONS[method](numerics)
    if method == "sem_paper":
        problem = ImpactProblem.from_case(case)
        try:
            check_paper_step(problem, options, options.step(problem))
        except ValueError as error:
            setting = "dt_s" if numerics.get("dt_s") is not None else "steps_per_contact"
            raise ValueError(f"{setting}: {error}") from None


def run_config(case: Mapping[str, Any], method: str, level: int | None = None) -> dict[str, Any]:
    """The configuration a run is stored and hashed with: the resolved case plus the run."""
    run = {"method": method, "numerics": case["numerics"][method]}
    if level is not None:
        run["level"] = level
    return {**case, "run": run}


def run_case(case: Mapping[str, Any], method: str, *, keep_failed: bool = False) -> Any:
    """Solve ``case`` with ``method`` and return the solver's result object.

    ``keep_failed=True`` returns a failed result instead of raising (a study run).

    Raises
    ------
    ValueError
        ``method`` is unknown or not among the case's methods.
    SolverFailed
        The solver reported failure (its status and message are in the error).
    """
    if method not in RUNNERS:
        raise ValueError(f"method: unknown method {method!r}; known: {sorted(RUNNERS)}")
    if method not in case["methods"]:
        raise ValueError(f"method: case {case['id']!r} does not list {method!r} (it lists {case['methods']})")
    result = RUNNERS[method](case, case["numerics"][method])
    if not (result.success or keep_failed):
        raise SolverFailed(f"case {case['id']!r}, method {method!r}: {result.status}: {result.message}")
    return result


@dataclass(frozen=True)
class Timing:
    """How a run is timed: repeated until ``min_repeats`` runs and ``min_total_s`` seconds,
    but no more once ``max_total_s`` seconds are spent (a long run is timed once)."""

    min_repeats: int = 1
    min_total_s: float = 0.0
    max_total_s: float = 0.0

    def __post_init__(self) -> None:
        if int(self.min_repeats) != self.min_repeats or self.min_repeats < 1:
            raise ValueError(f"min_repeats must be an integer >= 1, got {self.min_repeats!r}")
        if not (self.min_total_s >= 0 and self.max_total_s >= 0):
            raise ValueError(f"min_total_s and max_total_s must be >= 0, got {self.min_total_s!r}, {self.max_total_s!r}")


#: Errors a solver may raise on a case it cannot take; a study run records them as data.
_STUDY_ERRORS = (ValueError, RuntimeError, ArithmeticError, MemoryError)


def _failure_record(error: BaseException) -> tuple[dict, dict]:
    """Series and summary of a run that raised: the error's type and message, no numbers."""
    summary = {"contact_time_s": math.nan, "peak_force_N": np.empty(0), "peak_time_s": np.empty(0),
               "rebound_velocity_m_s": math.nan, "energy_error": math.nan, "n_contacts": 0,
               "contact_start_s": np.empty(0), "contact_end_s": np.empty(0), "success": False,
               "status": "error", "message": f"{type(error).__name__}: {error}"}
    return {"time": (np.zeros(1), "s", "time since first contact")}, summary


def run_to_file(case: Mapping[str, Any], method: str, path: str | Path, level: int | None = None, *,
                keep_failed: bool = False, timing: Timing | None = None,
                study: Mapping[str, Any] | None = None) -> Path:
    """Solve and write ``path`` (HDF5, atomically); returns the path.

    Only the outputs the case lists are stored.

    Parameters
    ----------
    keep_failed : bool
        Write the file also when the solver fails or raises (a study's run: failure is
        data, the summary's ``success``/``status``/``message`` say what happened).
        Otherwise a failure raises :class:`SolverFailed` and nothing is written.
    timing : Timing, optional
        Repeat the solve to time it; the summary gets ``wall_time_repeats``,
        ``wall_time_min_s``, ``wall_time_median_s`` and ``wall_time_max_s`` (s) and the
        ``machine`` it ran on.
    study : mapping, optional
        The study this run belongs to and its sweep parameters, stored in the config.
    """
    timed, timing = timing is not None, Timing() if timing is None else timing
    config = run_config(case, method, level)
    if study is not None:
        config["run"]["study"] = dict(study)
    walls: list[float] = []
    result = error = None
    while True:
        started = time.perf_counter()
        try:
            result = run_case(case, method, keep_failed=keep_failed)
        except _STUDY_ERRORS as caught:
            if not keep_failed:
                raise
            error = caught
        walls.append(time.perf_counter() - started)
        if error is not None or (len(walls) >= timing.min_repeats and sum(walls) >= timing.min_total_s) \
                or sum(walls) >= timing.max_total_s:
            break
    wall = float(np.median(walls))
    if error is not None:
        log.warning("case %s, method %s raised %s: recorded as a failed run", case["id"], method, error)
        series, summary = _failure_record(error)
    else:
        log.info("case %s, method %s: %s: %s in %.3f s", case["id"], method, result.status, result.message, wall)
        series, summary = result.series(case["outputs"]), result.summary()
    if timed:
        summary.update(wall_time_repeats=len(walls), wall_time_min_s=min(walls), wall_time_median_s=wall,
                       wall_time_max_s=max(walls), machine=machine_description())
    return write_run(path, config=config, method=method, series=series, summary=summary, wall_time_s=wall)


def machine_description() -> str:
    """The machine a timing ran on: processor, logical CPUs, CPUs this process may use."""
    model = platform.processor() or platform.machine()
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return f"{model}; {os.cpu_count()} logical CPUs, {usable} usable; {platform.system()} {platform.release()}"
