"""Run one method on one resolved case and store it: the science behind the ``solve`` rule."""

from __future__ import annotations

import logging
import time
from pathlib import Path
from typing import Any, Callable, Mapping

from .fem import FEM1DOptions, solve_fem1d
from .fem.fem_axi import AxiImpact, FEMAxiOptions, solve_fem_axi
from .sem import ImpactProblem, SEMOptions, solve_sem
from .store import write_run

__all__ = ["RUNNERS", "SolverFailed", "case_at_level", "run_case", "run_to_file", "run_config"]

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


def run_config(case: Mapping[str, Any], method: str, level: int | None = None) -> dict[str, Any]:
    """The configuration a run is stored and hashed with: the resolved case plus the run."""
    run = {"method": method, "numerics": case["numerics"][method]}
    if level is not None:
        run["level"] = level
    return {**case, "run": run}


def case_at_level(case: Mapping[str, Any], method: str, overrides: Mapping[str, Any]) -> dict[str, Any]:
    """The case with ``overrides`` on its numerics for ``method`` (a convergence level)."""
    numerics = {**case["numerics"], method: {**case["numerics"][method], **overrides}}
    return {**case, "numerics": numerics}


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


def run_to_file(case: Mapping[str, Any], method: str, path: str | Path, level: int | None = None) -> Path:
    """Solve and write ``path`` (HDF5, atomically); returns the path.

    Only the outputs the case lists are stored.
    """
    started = time.perf_counter()
    result = run_case(case, method)
    wall = time.perf_counter() - started
    log.info("case %s, method %s: %s in %.3f s", case["id"], method, result.message, wall)
    return write_run(
        path,
        config=run_config(case, method, level),
        method=method,
        series=result.series(case["outputs"]),
        summary=result.summary(),
        wall_time_s=wall,
    )
