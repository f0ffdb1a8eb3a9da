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

from rodimpact.inputs.files import InputFileError, quoted, read_text

__all__ = [
    "FORCE_UNITS",
    "HistoryError",
    "MAX_CELL_CHARS",
    "MAX_HISTORY_BYTES",
    "MAX_LINE_CHARS",
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
#: The largest history file read, bytes (10^6 rows of two numbers take about 40 MB).
MAX_HISTORY_BYTES = 128 * 1024 * 1024
#: The longest cell of a history: a number, or a header's name and unit.
MAX_CELL_CHARS = 64
#: The longest line of a history: two cells and their separator, with room to spare.
MAX_LINE_CHARS = 256


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


def _unit(name: str, quantity: str, declared: str | None, units: Mapping[str, float], where: str) -> float:
    """The scale of a column from its header name (``time_ms``) or the declared unit; ``where``
    names the header's cell (``x.csv line 1, column 2``): a unit the header gives is the
    header's fault, one the block declares the block's."""
    base, _, suffix = name.strip().partition("_")
    if base != quantity:
        raise HistoryError(
            "file",
            f"{where}: the header must name a {quantity} column as '{quantity}' or "
            f"'{quantity}_<unit>', got {quoted(name.strip())}",
        )
    if suffix and suffix not in units:
        raise HistoryError(
            "file",
            f"{where}: unknown unit {quoted(suffix)} in the header {quoted(name.strip())}; known: {', '.join(units)}",
        )
    if suffix and declared and suffix != declared:
        raise HistoryError(f"{quantity}_unit", f"{declared!r} contradicts the header's {name.strip()!r} ({where})")
    unit = suffix or declared
    if unit is None:
        raise HistoryError(
            f"{quantity}_unit",
            f"the header names no unit of {quantity} ({name.strip()!r}, {where}); "
            f"declare {quantity}_unit: one of {', '.join(units)}",
        )
    if unit not in units:
        raise HistoryError(f"{quantity}_unit", f"unknown unit {quoted(unit)}; known: {', '.join(units)}")
    return units[unit]


def read_force_history(path: str | Path, spec: Mapping[str, Any]) -> MeasuredHistory:
    """Read and check the force history ``path`` as the ``force_history`` block ``spec`` declares it.

    The file is read as :func:`rodimpact.inputs.files.read_text` reads a user's file: a regular
    file only (never a FIFO or a device), at most :data:`MAX_HISTORY_BYTES`, UTF-8 (a bad byte
    named by its line and column); a cell longer than :data:`MAX_CELL_CHARS` is refused by its
    line and column.

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
    try:
        text = read_text(path, limit=MAX_HISTORY_BYTES)
    except InputFileError as error:
        raise HistoryError("file", f"{path.name}: {error.reason}") from None
    every = int(spec.get("every") or 1)
    if every < 1:
        raise HistoryError("every", f"must be an integer >= 1, got {every}")
    lines = text.splitlines()
    for number, line in enumerate(lines, start=1):
        if len(line) > MAX_LINE_CHARS:
            raise HistoryError(
                "file",
                f"{path.name} line {number}: a line of {len(line)} characters, more than the {MAX_LINE_CHARS} "
                "a row of two numbers takes",
            )
    rows = sum(1 for line in lines if line.strip()) - 1
    if rows > MAX_ROWS * every:
        raise HistoryError(
            "every",
            f"{path.name} has {rows} rows, more than {MAX_ROWS} to keep: declare "
            f"every: {math.ceil(rows / MAX_ROWS)} (or more) to thin it",
        )
    reader = csv.reader(lines)
    try:
        header = next(reader, None)
        if header is not None:
            _short_cells(header, 1, path)
        if not header or len(header) != 2 or any(_is_number(cell) for cell in header):
            raise HistoryError(
                "file",
                f"{path.name} must start with a header of two columns, time and force "
                f"(e.g. 'time_s,force_N'), got {quoted(header)}",
            )
        time_scale = _unit(header[0], "time", spec.get("time_unit"), TIME_UNITS, f"{path.name} line 1, column 1")
        force_scale = _unit(header[1], "force", spec.get("force_unit"), FORCE_UNITS, f"{path.name} line 1, column 2")
        values = []
        for line, row in enumerate(reader, start=2):
            if not row or not "".join(row).strip():
                continue
            _short_cells(row, line, path)
            if len(row) != 2:
                raise HistoryError("file", f"{path.name} line {line}: expected 2 values, got {len(row)}")
            try:
                pair = (float(row[0]), float(row[1]))
            except ValueError:
                raise HistoryError("file", f"{path.name} line {line}: not a number: {quoted(row)}") from None
            if not (math.isfinite(pair[0]) and math.isfinite(pair[1])):
                raise HistoryError("file", f"{path.name} line {line}: not a finite number: {quoted(row)}")
            values.append(pair)
    except csv.Error as error:
        raise HistoryError("file", f"{path.name} line {reader.line_num}: not CSV: {error}") from None
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
    force = data[:, 1] * force_scale * float(spec.get("sign") or 1)
    high, low = float(force.max()), float(force.min())
    if high <= 0.0 and low >= 0.0:
        raise HistoryError("file", f"{path.name}: the force is zero throughout: no contact was recorded")
    if high <= 0.0 or -low > high:
        flip = "declare sign: 1 (or remove sign: -1)" if spec.get("sign") == -1 else "declare sign: -1"
        raise HistoryError(
            "file",
            f"{path.name}: the force is mostly negative (from {low:.6g} N to {high:.6g} N): a contact force "
            f"pushes; if the sensor reads compression as negative, {flip} in the force_history block",
        )
    return MeasuredHistory(time_s=time, force_N=force, path=path, note=str(spec.get("note", "")))


def _short_cells(row: list[str], line: int, path: Path) -> None:
    """Refuse a cell longer than :data:`MAX_CELL_CHARS`, by its line and column."""
    for column, cell in enumerate(row, start=1):
        if len(cell) > MAX_CELL_CHARS:
            raise HistoryError(
                "file",
                f"{path.name} line {line}, column {column}: a cell of {len(cell)} characters, more than the "
                f"{MAX_CELL_CHARS} a number or a header takes",
            )


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True
