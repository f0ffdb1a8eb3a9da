"""A case's measured block: its force history's file found, read and checked before any job.

The file is named relative to the case file and must lie in that file's directory or below it:
the plan's cache (:mod:`rodimpact.plumbing.plan_cache`) reads the cases directory's whole tree,
so a history there that changes reaches the plan, and the comparison's rule lists it as an
input. The resolved block keeps the file as written and adds ``path``, the file relative to
the project root, which the jobs read.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path, PurePosixPath
from typing import Any

from rodimpact.analysis.measured import HistoryError, read_force_history
from rodimpact.config.project import ConfigError

__all__ = ["check_measured_physics", "resolve_measured"]


def resolve_measured(
    measured: Mapping[str, Any] | None,
    case_file: Path,
    case_label: str,
    error: Callable[..., ConfigError],
    checked: dict[tuple, str] | None = None,
) -> dict | None:
    """The case's ``measured`` block with its force history (if any) checked and located.

    Parameters
    ----------
    measured : mapping or None
        The case's block, schema-checked.
    case_file : Path
        The case file (its directory is where ``force_history.file`` starts).
    case_label : str
        The case file's name relative to the project root (as messages show it).
    error : callable
        ``error(message, field=...)`` -> :class:`ConfigError` naming the file and the case.
    checked : dict, optional
        Histories already checked, (path, spec) -> root-relative path: a file several variants
        share is read once.

    Raises
    ------
    ConfigError
        The history's file lies outside the case file's directory, or cannot be used
        (:class:`~rodimpact.analysis.measured.HistoryError`), with its field.
    """
    if not measured or not measured.get("force_history"):
        return None if measured is None else dict(measured)
    history = dict(measured["force_history"])
    directory = case_file.parent.resolve()
    path = (case_file.parent / history["file"]).resolve()
    if not path.is_relative_to(directory):
        raise error(
            f"{history['file']!r} lies outside the directory of its case file; keep a history "
            "beside its case file or below it, so that a change to it reaches the plan",
            field="measured.force_history.file",
        )
    key = (str(path), tuple(sorted((k, str(v)) for k, v in history.items())))
    if checked is not None and key in checked:
        label = checked[key]
    else:
        try:
            read_force_history(path, history)
        except HistoryError as problem:
            raise error(problem.reason, field=f"measured.force_history.{problem.field}") from None
        label = (PurePosixPath(case_label).parent / path.relative_to(directory).as_posix()).as_posix()
        if checked is not None:
            checked[key] = label
    return {**measured, "force_history": {**history, "path": label}}


def check_measured_physics(case: Mapping[str, Any], error: Callable[..., ConfigError]) -> None:
    """What a measurement cannot be, given the case it measures: a rebound faster than the
    impact (an impactor cannot leave an elastic rod with more energy than it brought).

    Raises
    ------
    ConfigError
        Naming the field (``measured.rebound_velocity_m_s``) and the impact velocity.
    """
    measured = case.get("measured") or {}
    rebound = measured.get("rebound_velocity_m_s")
    impact = float(case["impactor"]["velocity_m_s"])
    if rebound is not None and float(rebound) > impact:
        raise error(
            f"a rebound of {float(rebound):g} m/s is faster than the impact at {impact:g} m/s: no impact on an "
            "elastic rod returns more energy than it brought (a restitution above 1); check the value and its unit",
            field="measured.rebound_velocity_m_s",
        )
