"""A case's measured block: its records' files found, read and checked before any job.

Each record (a force, a strain at a gauge, a velocity: :data:`~rodimpact.analysis.measured.RECORDS`)
is named relative to the case file and must lie in that file's directory or below it, beside
the configuration it belongs to; every plan reads it whole (:func:`resolve_measured`), and the
comparison's rule lists it as an input, so a change to it reaches the plan and reruns what reads
it. The resolved block keeps the file as written and adds ``path``, the file relative to the
project root, which the jobs read. What a record shows is then checked against its case's impact
(:func:`check_records`, :mod:`rodimpact.analysis.record_checks`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path, PurePosixPath
from typing import Any

from rodimpact.analysis.measured import MEASURED_KEYS, RECORDS, HistoryError, MeasuredHistory, read_history
from rodimpact.analysis.record_checks import check_record, impact_bounds
from rodimpact.config.project import ConfigError
from rodimpact.model.gauges import Gauge, GaugeError
from rodimpact.model.problem import ImpactProblem

__all__ = ["check_measured_physics", "check_records", "record_outputs", "resolve_gauges", "resolve_measured"]


def resolve_measured(
    measured: Mapping[str, Any] | None,
    case_file: Path,
    case_label: str,
    error: Callable[..., ConfigError],
    checked: dict[tuple, tuple[str, MeasuredHistory]] | None = None,
) -> tuple[dict | None, dict[str, MeasuredHistory]]:
    """The case's ``measured`` block with its records (if any) checked as files and located,
    and the records read.

    Parameters
    ----------
    measured : mapping or None
        The case's block, schema-checked.
    case_file : Path
        The case file (its directory is where each record's ``file`` starts).
    case_label : str
        The case file's name relative to the project root (as messages show it).
    error : callable
        ``error(message, field=...)`` -> :class:`ConfigError` naming the file and the case.
    checked : dict, optional
        Records already read, (path, key, spec) -> (root-relative path, record): a file several
        variants share is read once.

    Returns
    -------
    block : dict or None
        The resolved block (None without one).
    records : dict
        Its records read, by key (:func:`check_records` checks them against the case).

    Raises
    ------
    ConfigError
        A record's file lies outside the case file's directory, or cannot be used
        (:class:`~rodimpact.analysis.measured.HistoryError`), with its field.
    """
    if measured is None:
        return None, {}
    resolved, records = dict(measured), {}
    for key in RECORDS:
        if measured.get(key):
            resolved[key], records[key] = _resolve_record(
                key, dict(measured[key]), case_file, case_label, error, checked
            )
    return resolved, records


def _resolve_record(
    key: str,
    history: dict[str, Any],
    case_file: Path,
    case_label: str,
    error: Callable[..., ConfigError],
    checked: dict[tuple, tuple[str, MeasuredHistory]] | None,
) -> tuple[dict[str, Any], MeasuredHistory]:
    """One record of the ``measured`` block, read and checked, with its ``path`` added; and the record."""
    directory = case_file.parent.resolve()
    path = (case_file.parent / history["file"]).resolve()
    if not path.is_relative_to(directory):
        raise error(
            f"{history['file']!r} lies outside the directory of its case file; keep a record "
            "beside its case file or below it, so that a change to it reaches the plan",
            field=f"measured.{key}.file",
        )
    cache_key = (str(path), key, tuple(sorted((k, str(v)) for k, v in history.items())))
    if checked is not None and cache_key in checked:
        label, record = checked[cache_key]
    else:
        try:
            record = read_history(path, history, key)
        except HistoryError as problem:
            raise error(problem.reason, field=f"measured.{key}.{problem.field}") from None
        label = (PurePosixPath(case_label).parent / path.relative_to(directory).as_posix()).as_posix()
        if checked is not None:
            checked[cache_key] = label, record
    return {**history, "path": label}, record


def resolve_gauges(
    case: Mapping[str, Any], declared: list[Mapping[str, Any]], error: Callable[..., ConfigError]
) -> list:
    """The case's gauges: those it declares (``gauges``), then its strain record's, each on
    the rod (:meth:`rodimpact.model.gauges.Gauge.check`), as ``{station_m, gauge_length_m}``.

    Raises
    ------
    ConfigError
        A gauge off the rod, longer than it or over one of its ends, naming its field.
    """
    length = float(case["rod"]["length_m"])
    gauges: list[tuple[str, Gauge]] = [
        (f"gauges[{index}]", Gauge.from_settings(settings)) for index, settings in enumerate(declared)
    ]
    record = (case.get("measured") or {}).get("strain_history")
    if record:
        gauges.append(("measured.strain_history", Gauge.from_settings(record)))
    for where, gauge in gauges:
        try:
            gauge.check(length)
        except GaugeError as problem:
            raise error(problem.reason.lstrip("="), field=f"{where}.{problem.field}") from None
    unique = list(dict.fromkeys(gauge for _, gauge in gauges))
    return [gauge.as_settings() for gauge in unique]


def record_outputs(case: Mapping[str, Any]) -> list[str]:
    """The outputs the case's records need its runs to store: the strain at its gauges for a
    strain record, the velocity a velocity record measures."""
    measured = case.get("measured") or {}
    needed = []
    if measured.get("force_history"):
        needed.append("contact_force")
    if measured.get("strain_history"):
        needed.append("gauge_strain")
    velocity = measured.get("velocity_history")
    if velocity:
        needed.append("impactor_velocity" if velocity["of"] == "impactor" else "far_end_velocity")
    return needed


def check_measured_physics(case: Mapping[str, Any], error: Callable[..., ConfigError]) -> None:
    """What a measurement cannot be, given the case it measures: nothing at all (a block with
    no value and no record); a rebound faster than the impact (an impactor cannot leave an
    elastic rod with more energy than it brought); the velocity of a fixed far end.

    Raises
    ------
    ConfigError
        Naming the field (``measured.rebound_velocity_m_s``) and the impact velocity; or
        ``measured.velocity_history.of`` for the far end of a rod whose far end is fixed.
    """
    measured = case.get("measured") or {}
    if case.get("measured") is not None and not any(measured.get(key) is not None for key in MEASURED_KEYS):
        raise error(f"gives nothing to compare with; give one of {', '.join(MEASURED_KEYS)}", field="measured")
    rebound = measured.get("rebound_velocity_m_s")
    impact = float(case["impactor"]["velocity_m_s"])
    if rebound is not None and float(rebound) > impact:
        raise error(
            f"a rebound of {float(rebound):g} m/s is faster than the impact at {impact:g} m/s: no impact on an "
            "elastic rod returns more energy than it brought (a restitution above 1); check the value and its unit",
            field="measured.rebound_velocity_m_s",
        )
    velocity = measured.get("velocity_history")
    if velocity and velocity["of"] == "far_end" and case["rod"].get("far_end", "fixed") != "free":
        raise error(
            "the far end's velocity of a rod whose far end is fixed is zero: a record of it needs rod.far_end: free",
            field="measured.velocity_history.of",
        )


def check_records(
    case: Mapping[str, Any], records: Mapping[str, MeasuredHistory], error: Callable[..., ConfigError]
) -> None:
    """What each record of a resolved case shows, against what the case's impact allows: a pulse
    above its noise, its sign, a pre-trigger, its size and its timing
    (:func:`rodimpact.analysis.record_checks.check_record`).

    Raises
    ------
    ConfigError
        Naming the record's key at fault (``measured.strain_history.sign``, ...).
    """
    if not records:
        return
    bounds = impact_bounds(ImpactProblem.from_case(case, estimate=True))
    for key, record in records.items():
        try:
            check_record(record, case["measured"][key], bounds)
        except HistoryError as problem:
            raise error(problem.reason, field=f"measured.{key}.{problem.field}") from None
