"""A measured force history: the CSV file a case's ``measured.force_history`` names, read and checked.

The file has a header and two columns, time then force. Their units come from the header
(``time_s``, ``time_ms`` or ``time_us``; ``force_N`` or ``force_kN``) or, for plain ``time``
and ``force``, from the block's ``time_unit`` and ``force_unit``. The block may shift the time
(``time_offset_s``, added after the unit's scale) and thin a long record (``every``: keep
every k-th row). The file is refused, with one line naming what is wrong, when it is missing,
has no header or an unknown unit, a time that does not increase, a value that is not a finite
number, fewer than :data:`MIN_ROWS` rows, or more than :data:`MAX_ROWS` rows kept.

Nothing here knows the workflow: :mod:`rodimpact.config.load` checks each history before any
job, and the comparison (:mod:`.history_compare`) reads it again in its job.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "FORCE_UNITS",
    "HistoryError",
    "MAX_ROWS",
    "MEASURED_KEYS",
    "MIN_ROWS",
    "MeasuredHistory",
    "TIME_UNITS",
    "measured_cases",
    "read_force_history",
]

#: What a case's ``measured`` block may give to compare with (``source`` and ``note`` describe it).
MEASURED_KEYS = ("contact_time_us", "peak_force_n", "rebound_velocity_m_s", "force_history")

#: Time units a history may declare, and their size in s.
TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6}
#: Force units a history may declare, and their size in N.
FORCE_UNITS = {"N": 1.0, "kN": 1e3}
#: The fewest rows a history must keep to be compared.
MIN_ROWS = 8
#: The most rows kept without a declared thinning (``every``): 10^6 rows read in well under a
#: second, a longer record is a raw oscilloscope dump that should be thinned on purpose.
MAX_ROWS = 1_000_000


def measured_cases(cases: list[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
    """The resolved cases that carry something measured to compare with (:data:`MEASURED_KEYS`)."""
    return [c for c in cases if any((c.get("measured") or {}).get(key) is not None for key in MEASURED_KEYS)]


class HistoryError(ValueError):
    """A force history that cannot be used; ``field`` is the key of the ``force_history``
    block it concerns (``file`` for the file's own faults)."""

    def __init__(self, field: str, message: str) -> None:
        self.field, self.reason = field, message
        super().__init__(f"{field}: {message}")


@dataclass(frozen=True)
class MeasuredHistory:
    """A measured contact force against time, in SI units.

    Attributes
    ----------
    time_s : ndarray, shape (n,)
        Strictly increasing times, s (with the declared offset).
    force_N : ndarray, shape (n,)
        Force, N.
    path : Path
        The file it was read from.
    note : str
        How it was measured (the block's ``note``).
    """

    time_s: NDArray[np.float64]
    force_N: NDArray[np.float64]
    path: Path
    note: str = ""


def _unit(name: str, quantity: str, declared: str | None, units: Mapping[str, float]) -> float:
    """The scale of a column from its header name (``time_ms``) or the declared unit."""
    base, _, suffix = name.strip().partition("_")
    if base != quantity:
        raise HistoryError(
            "file",
            f"the header must name a {quantity} column first as '{quantity}' or "
            f"'{quantity}_<unit>', got {name.strip()!r}",
        )
    if suffix and declared and suffix != declared:
        raise HistoryError(f"{quantity}_unit", f"{declared!r} contradicts the header's {name.strip()!r}")
    unit = suffix or declared
    if unit is None:
        raise HistoryError(
            f"{quantity}_unit",
            f"the header names no unit of {quantity} ({name.strip()!r}); "
            f"declare {quantity}_unit: one of {', '.join(units)}",
        )
    if unit not in units:
        raise HistoryError(f"{quantity}_unit", f"unknown unit {unit!r}; known: {', '.join(units)}")
    return units[unit]


def _rows_in(path: Path) -> int:
    with open(path, "rb") as handle:
        return sum(1 for line in handle if line.strip())


def read_force_history(path: str | Path, spec: Mapping[str, Any]) -> MeasuredHistory:
    """Read and check the force history ``path`` as the ``force_history`` block ``spec`` declares it.

    Parameters
    ----------
    path : path
        The CSV file (already resolved against the case file's directory).
    spec : mapping
        ``time_unit``, ``force_unit`` (optional where the header names them), ``time_offset_s``
        (default 0), ``every`` (default 1), ``note``.

    Returns
    -------
    MeasuredHistory

    Raises
    ------
    HistoryError
        Whatever makes the file unusable, with the block's key it concerns.
    """
    path = Path(path)
    if not path.is_file():
        raise HistoryError("file", f"no such file: {path}")
    every = int(spec.get("every") or 1)
    if every < 1:
        raise HistoryError("every", f"must be an integer >= 1, got {every}")
    rows = _rows_in(path) - 1
    if rows > MAX_ROWS * every:
        raise HistoryError(
            "every",
            f"{path.name} has {rows} rows, more than {MAX_ROWS} to keep: declare "
            f"every: {math.ceil(rows / MAX_ROWS)} (or more) to thin it",
        )
    with open(path, newline="", encoding="utf-8") as handle:
        reader = csv.reader(handle)
        header = next(reader, None)
        if not header or len(header) != 2 or any(_is_number(cell) for cell in header):
            raise HistoryError(
                "file",
                f"{path.name} must start with a header of two columns, time and force "
                f"(e.g. 'time_s,force_N'), got {header!r}",
            )
        time_scale = _unit(header[0], "time", spec.get("time_unit"), TIME_UNITS)
        force_scale = _unit(header[1], "force", spec.get("force_unit"), FORCE_UNITS)
        values = []
        for line, row in enumerate(reader, start=2):
            if not row or not "".join(row).strip():
                continue
            if len(row) != 2:
                raise HistoryError("file", f"{path.name} line {line}: expected 2 values, got {len(row)}")
            try:
                pair = (float(row[0]), float(row[1]))
            except ValueError:
                raise HistoryError("file", f"{path.name} line {line}: not a number: {row!r}") from None
            if not (math.isfinite(pair[0]) and math.isfinite(pair[1])):
                raise HistoryError("file", f"{path.name} line {line}: not a finite number: {row!r}")
            values.append(pair)
    data = np.asarray(values, dtype=float).reshape(-1, 2)[::every]
    if len(data) < MIN_ROWS:
        raise HistoryError("file", f"{path.name} keeps {len(data)} rows, fewer than {MIN_ROWS}")
    time = data[:, 0] * time_scale + float(spec.get("time_offset_s") or 0.0)
    steps = np.diff(time)
    if np.any(steps <= 0):
        bad = int(np.argmax(steps <= 0))
        raise HistoryError(
            "file",
            f"{path.name} line {2 + (bad + 1) * every}: the time must increase, "
            f"{time[bad + 1]:.6g} s follows {time[bad]:.6g} s",
        )
    return MeasuredHistory(time_s=time, force_N=data[:, 1] * force_scale, path=path, note=str(spec.get("note", "")))


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True
