"""Run one method on one resolved case and store it: the science behind the ``solve`` rule."""

from __future__ import annotations

import logging
import time
from pathlib import Path
from typing import Any, Callable, Mapping

from .fem import FEM1DOptions, solve_fem1d
from .sem import ImpactProblem, SEMOptions, solve_sem
from .store import write_run

__all__ = ["RUNNERS", "SolverFailed", "run_case", "run_to_file", "run_config"]

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
}


def run_config(case: Mapping[str, Any], method: str) -> dict[str, Any]:
    """The configuration a run is stored and hashed with: the resolved case plus the run."""
    return {**case, "run": {"method": method, "numerics": case["numerics"][method]}}


def run_case(case: Mapping[str, Any], method: str) -> Any:
    """Solve ``case`` with ``method`` and return the solver's result object.

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
    if not result.success:
        raise SolverFailed(f"case {case['id']!r}, method {method!r}: {result.status}: {result.message}")
    return result


def run_to_file(case: Mapping[str, Any], method: str, path: str | Path) -> Path:
    """Solve and write ``path`` (HDF5, atomically); returns the path.

    Only the outputs the case lists are stored.
    """
    started = time.perf_counter()
    result = run_case(case, method)
    wall = time.perf_counter() - started
    log.info("case %s, method %s: %s in %.3f s", case["id"], method, result.message, wall)
    return write_run(
        path,
        config=run_config(case, method),
        method=method,
        series=result.series(case["outputs"]),
        summary=result.summary(),
        wall_time_s=wall,
    )
