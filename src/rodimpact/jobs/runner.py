"""Run one method on one resolved case and store it: the science behind the ``solve`` rule."""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

import numpy as np

from rodimpact.contact.laws import law_of
from rodimpact.jobs.timing import Timing
from rodimpact.solvers.registry import METHODS, UnknownMethod
from rodimpact.solvers.result import ImpactResult
from rodimpact.storage.casefile import case_file_reference
from rodimpact.storage.curves import ContactCurve, read_contact_curve
from rodimpact.storage.provenance import file_sha256
from rodimpact.storage.runs import write_run

__all__ = ["SolvedRun", "SolverFailed", "Timing", "run_case", "run_config", "run_to_file", "solve_run", "with_curve"]

log = logging.getLogger(__name__)


class SolverFailed(RuntimeError):
    """A solver returned ``success=False``: nothing is written."""


def run_config(case: Mapping[str, Any], method: str, level: int | None = None) -> dict[str, Any]:
    """The configuration a run is stored and hashed with: the resolved case plus the run."""
    run = {"method": method, "numerics": case["numerics"][method]}
    if level is not None:
        run["level"] = level
    return {**case, "run": run}


@dataclass(frozen=True)
class SolvedRun:
    """What a solved run stores (:func:`rodimpact.storage.runs.write_run`'s arguments): its
    config (the case with the run), method, series and summary, solver time (s), code version
    (None: the checkout's) and field."""

    config: dict[str, Any]
    method: str
    series: dict[str, tuple[np.ndarray, str, str]]
    summary: dict[str, Any]
    wall_time_s: float
    code_version: str | None
    field: dict[str, tuple[np.ndarray, str, str]]

    def arguments(self) -> dict[str, Any]:
        """The keyword arguments of :func:`~rodimpact.storage.runs.write_run` (but ``path``)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def run_case(case: Mapping[str, Any], method: str, *, keep_failed: bool = False) -> ImpactResult:
    """Solve ``case`` with ``method`` and return the solver's result object.

    ``keep_failed=True`` returns a failed result instead of raising (a study run).

    Raises
    ------
    UnknownMethod
        ``method`` is not in the registry.
    ValueError
        ``method`` is not among the case's methods.
    SolverFailed
        The solver reported failure (its status and message are in the error).
    """
    if method not in METHODS:
        raise UnknownMethod(method)
    if method not in case["methods"]:
        raise ValueError(f"method: case {case['id']!r} does not list {method!r} (it lists {case['methods']})")
    result = METHODS[method].solve(case, case["numerics"][method])
    if not (result.success or keep_failed):
        raise SolverFailed(f"case {case['id']!r}, method {method!r}: {result.status}: {result.message}")
    return result


#: Errors a solver may raise on a case it cannot take; a study run records them as data.
_STUDY_ERRORS = (ValueError, RuntimeError, ArithmeticError, MemoryError)


def _failure_record(error: BaseException) -> tuple[dict, dict]:
    """Series and summary of a run that raised: the error's type and message, no numbers."""
    summary = {
        "contact_time_s": math.nan,
        "peak_force_N": np.empty(0),
        "peak_time_s": np.empty(0),
        "rebound_velocity_m_s": math.nan,
        "energy_error": math.nan,
        "n_contacts": 0,
        "contact_start_s": np.empty(0),
        "contact_end_s": np.empty(0),
        "success": False,
        "status": "error",
        "message": f"{type(error).__name__}: {error}",
    }
    return {"time": (np.zeros(1), "s", "time since first contact")}, summary


def with_curve(case: Mapping[str, Any], curve: str | Path | ContactCurve | None) -> Mapping[str, Any]:
    """The case with its law's curve (read from the file ``curve``, or the curve itself,
    computed in the job) when the law needs one (its ``needs.curve_rule``), the case itself otherwise."""
    contact = case.get("contact") or {}
    law = law_of(contact)
    if law.needs.curve_rule is None:
        if curve is not None:
            raise ValueError(f"contact_curve: case {case['id']!r} has the {law.name} law, which takes no curve")
        return case
    if curve is None:
        raise ValueError(
            f"contact_curve: case {case['id']!r} has the {law.name} law and needs its curve file "
            f"(rule {law.needs.curve_rule})"
        )
    where = "the curve computed in this job" if isinstance(curve, ContactCurve) else str(curve)
    if not isinstance(curve, ContactCurve):
        curve = read_contact_curve(curve)
    if curve.case_id != case["id"]:
        raise ValueError(f"contact_curve: {where} is the curve of case {curve.case_id!r}, not {case['id']!r}")
    return {**case, "contact": {**contact, "curve": curve.law_curve()}}


def solve_run(
    case: Mapping[str, Any],
    method: str,
    level: int | None = None,
    *,
    keep_failed: bool = False,
    timing: Timing | None = None,
    study: Mapping[str, Any] | None = None,
    case_file: str | Path | Mapping[str, str] | None = None,
    contact_curve: str | Path | ContactCurve | None = None,
    code_version: str | None = None,
) -> SolvedRun:
    """Solve ``case`` with ``method``: what its stored run holds (:func:`run_to_file` writes it).

    Only the outputs the case lists are stored (the strain field, ``strain_field``, by the
    methods that record it; the others skip it).

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
    case_file : path or mapping, optional
        The case file the run was made from (``results/cases/{name}.yaml``): its path, its
        SHA-256 and its case's hash are stored in the config (``run.case_file``); a mapping
        is that record already read (:func:`rodimpact.storage.casefile.case_file_reference`).
    contact_curve : path or ContactCurve, optional
        The curve file of a case whose contact law needs one (``needs.curve_rule``: the indentation rule's
        output, :mod:`rodimpact.storage.curves`): read, checked against its hash and against
        the case, and given to the law; its path and SHA-256 are stored in the config
        (``run.contact_curve``). A :class:`~rodimpact.storage.curves.ContactCurve` is a curve
        the job computed itself (a sweep point's): its summary is stored instead.
    code_version : str, optional
        The code version stored with the run (default: :func:`rodimpact.storage.provenance.code_version`).

    Raises
    ------
    ValueError
        ``case_file`` holds another case than this run's (stale or edited); the case's law
        needs a curve and no ``contact_curve`` is given, or the curve is another case's.
    """
    timed, timing = timing is not None, Timing() if timing is None else timing
    config = run_config(case, method, level)
    if study is not None:
        config["run"]["study"] = dict(study)
    if case_file is not None:
        config["run"]["case_file"] = (
            dict(case_file) if isinstance(case_file, Mapping) else case_file_reference(case_file, case["id"])
        )
    case = with_curve(case, contact_curve)
    if isinstance(contact_curve, ContactCurve):
        config["run"]["contact_curve"] = {"computed_in_job": True, "summary": dict(contact_curve.summary)}
    elif contact_curve is not None:
        config["run"]["contact_curve"] = {"path": str(contact_curve), "sha256": file_sha256(contact_curve)}
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
        if (
            error is not None
            or (len(walls) >= timing.min_repeats and sum(walls) >= timing.min_total_s)
            or sum(walls) >= timing.max_total_s
        ):
            break
    wall = float(np.median(walls))
    if error is not None:
        log.warning("case %s, method %s raised %s: recorded as a failed run", case["id"], method, error)
        (series, summary), field = _failure_record(error), {}
    else:
        log.info("case %s, method %s: %s: %s in %.3f s", case["id"], method, result.status, result.message, wall)
        series, summary, field = result.series(case["outputs"]), result.summary(), result.field_of(case["outputs"])
    if timed:
        from rodimpact.jobs.machine import machine_description  # only a timed run names its machine

        summary.update(
            wall_time_repeats=len(walls),
            wall_time_min_s=min(walls),
            wall_time_median_s=wall,
            wall_time_max_s=max(walls),
            machine=machine_description(),
        )
    return SolvedRun(config, method, series, summary, wall, code_version, field)


def run_to_file(
    case: Mapping[str, Any], method: str, path: str | Path, level: int | None = None, **options: Any
) -> Path:
    """Solve (:func:`solve_run`, which takes the same ``options``) and write ``path`` (HDF5,
    atomically); returns the path."""
    return write_run(path, **solve_run(case, method, level, **options).arguments())
