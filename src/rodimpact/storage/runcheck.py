"""What a run file may hold: the checks of a run's case configuration, time series and summary
before :func:`rodimpact.storage.runs.write_run` writes them (the schema is in :mod:`.runs`).

Imports only :mod:`rodimpact.storage.provenance` (canonical JSON) and numpy.
"""

from __future__ import annotations

from collections.abc import Mapping
from numbers import Integral, Real
from typing import Any

import numpy as np

from rodimpact.storage import provenance

__all__ = ["REQUIRED_SUMMARY", "SUMMARY_GROUP", "all_str", "check_config", "check_series", "check_summary"]

#: Summary attributes every run must provide; the two peak arrays have equal length.
REQUIRED_SUMMARY: tuple[str, ...] = (
    "contact_time_s", "peak_force_N", "peak_time_s", "rebound_velocity_m_s", "energy_error",
)  # fmt: skip
#: The group of a run file holding its summary attributes (not a series name).
SUMMARY_GROUP = "summary"
_SUMMARY_ARRAYS = ("peak_force_N", "peak_time_s")


def check_config(config: Mapping[str, Any]) -> tuple[str, str]:
    """Return ``(case_id, config_json)`` of a resolved case configuration."""
    if "id" not in config:
        raise ValueError("config must contain the case identifier 'id'")
    if not isinstance(config["id"], str) or not config["id"]:
        raise ValueError(f"config['id'] must be a non-empty str, got {config['id']!r}")
    try:
        return config["id"], provenance.canonical_json(dict(config))
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"config is not plain JSON data: {exc}") from exc


def all_str(values: tuple) -> bool:
    """Whether every value is a str (units and descriptions)."""
    return all(isinstance(value, str) for value in values)


def check_series(
    series: Mapping[str, tuple[np.ndarray, str, str]],
) -> list[tuple[str, np.ndarray, str, str]]:
    """Validate the series and return them as float64 arrays, ``time`` first."""
    if "time" not in series:
        raise ValueError("series must contain 'time'")
    checked: list[tuple[str, np.ndarray, str, str]] = []
    for name in ["time", *(name for name in series if name != "time")]:
        if not isinstance(name, str) or not name or "/" in name or name in (".", SUMMARY_GROUP):
            raise ValueError(f"series name {name!r} is not a valid dataset name")
        entry = series[name]
        if not (isinstance(entry, tuple) and len(entry) == 3 and all_str(entry[1:])):
            raise TypeError(f"series[{name!r}] must be a tuple (array, units, description)")
        values, units, description = entry
        array = np.asarray(values)
        if array.dtype.kind not in "biuf":
            raise TypeError(f"series[{name!r}] must be real numeric, got dtype {array.dtype}")
        array = np.ascontiguousarray(array, dtype=np.float64)
        n_time = checked[0][1].shape[0] if checked else -1
        if name == "time" and array.ndim != 1:
            raise ValueError(f"series['time'] must be 1-D, got shape {array.shape}")
        if name != "time" and (array.ndim not in (1, 2) or array.shape[0] != n_time):
            raise ValueError(
                f"series[{name!r}] has shape {array.shape}; expected 1-D or 2-D with "
                f"first dimension len(time) = {n_time}"
            )
        checked.append((name, array, units, description))
    return checked


def _summary_value(key: str, value: Any) -> Any:
    """Normalise one summary value to a type h5py stores faithfully."""
    if isinstance(value, (bool, np.bool_, str)):
        return np.bool_(value) if not isinstance(value, str) else value
    if isinstance(value, (Integral, Real)):
        return np.int64(value) if isinstance(value, Integral) else np.float64(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        array = np.asarray(value)
        if array.ndim != 1:
            raise ValueError(f"summary[{key!r}] must be scalar or 1-D, got shape {array.shape}")
        if array.size == 0 or array.dtype.kind in "biuf":
            kinds = {"b": np.bool_, "i": np.int64, "u": np.int64}
            return array.astype(kinds.get(array.dtype.kind, np.float64))
    raise TypeError(
        f"summary[{key!r}] has unsupported type {type(value).__name__}; "
        "use float, int, bool, str or a 1-D numeric array"
    )


def check_summary(summary: Mapping[str, Any]) -> dict[str, Any]:
    """Validate the summary attributes and return normalised values."""
    if missing := [key for key in REQUIRED_SUMMARY if key not in summary]:
        raise ValueError(f"summary is missing required key(s) {missing}")
    checked: dict[str, Any] = {}
    for key, value in summary.items():
        if not isinstance(key, str) or not key:
            raise TypeError(f"summary keys must be non-empty str, got {key!r}")
        checked[key] = _summary_value(key, value)
    for key in REQUIRED_SUMMARY:
        value, is_array = checked[key], key in _SUMMARY_ARRAYS
        if is_array != isinstance(value, np.ndarray) or np.asarray(value).dtype.kind not in "iuf":
            kind = "a 1-D float array" if is_array else "a real number"
            raise TypeError(f"summary[{key!r}] must be {kind}, got {type(summary[key]).__name__}")
        checked[key] = value.astype(np.float64)
    n_force, n_time = checked["peak_force_N"].size, checked["peak_time_s"].size
    if n_force != n_time:
        raise ValueError(f"summary peak_force_N/peak_time_s lengths differ: {n_force} != {n_time}")
    return checked
