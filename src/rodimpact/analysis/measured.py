"""A measured record: the CSV file a case's ``measured`` block names, read and checked.

Three kinds of record (:data:`RECORDS`): the contact force (``force_history``), the axial
strain at a gauge on the rod (``strain_history``) and a velocity, of the impactor or of the
rod's far end (``velocity_history``). The file has a header and two columns, time then the
value. Their units come from the header (``time_s``, ``time_ms`` or ``time_us``; ``force_N``
or ``force_kN``; ``strain_strain`` or ``strain_microstrain``; ``velocity_m_s`` or
``velocity_mm_s``) or, for plain ``time`` and ``force`` (``strain``, ``velocity``), from the
block's ``time_unit`` and ``force_unit`` (``strain_unit``, ``velocity_unit``). The block may shift the time
(``time_offset_s``, added after the unit's scale) and thin a long record (``every``: keep
every k-th row) and multiply the value by its ``sign``. The file is refused, with one line
naming what is wrong and the block's key at fault, when it is missing, has no header or an
unknown unit, a unit that contradicts the block's, a time that does not increase (or an offset
that swamps its steps: ``time_offset_s``), a value that is not a finite number, fewer than
:data:`MIN_ROWS` rows (or a thinning that leaves fewer: ``every``), more than :data:`MAX_ROWS`
rows kept, or a value that is zero throughout. What a record can show of the impact it measures
(its pulse, sign, pre-trigger, timing and size) is checked against the case by
:mod:`.record_checks`.

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
    "RECORDS",
    "SIGNAL_RECORDS",
    "STRAIN_UNITS",
    "VELOCITY_UNITS",
    "RecordKind",
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
    "read_history",
]

#: What a case's ``measured`` block may give to compare with (``source`` and ``note`` describe it).
MEASURED_KEYS = (
    "contact_time_us",
    "peak_force_n",
    "rebound_velocity_m_s",
    "force_history",
    "strain_history",
    "velocity_history",
)

#: Time units a history may declare, and their size in s.
TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6}
#: Force units a history may declare, and their size in N.
FORCE_UNITS = {"N": 1.0, "kN": 1e3}
#: Strain units a history may declare, and their size (dimensionless).
STRAIN_UNITS = {"strain": 1.0, "microstrain": 1e-6}
#: Velocity units a history may declare, and their size in m/s.
VELOCITY_UNITS = {"m_s": 1.0, "mm_s": 1e-3}


@dataclass(frozen=True)
class RecordKind:
    """What one kind of record holds: its ``measured`` key, the header's name of its value
    column, the units that column may take (name -> size in SI) and the SI unit's symbol."""

    key: str
    quantity: str
    units: Mapping[str, float]
    si_unit: str
    words: str


#: The records a case's ``measured`` block may name, by key.
RECORDS: dict[str, RecordKind] = {
    kind.key: kind
    for kind in (
        RecordKind("force_history", "force", FORCE_UNITS, "N", "contact force"),
        RecordKind("strain_history", "strain", STRAIN_UNITS, "1", "axial strain at the gauge"),
        RecordKind("velocity_history", "velocity", VELOCITY_UNITS, "m/s", "velocity"),
    )
}
#: The records a comparison draws, each kind in a figure of its own
#: (``results/figures/compare_{set}_{ending}``, a row per case): ending -> key.
SIGNAL_RECORDS = {"force": "force_history", "strain": "strain_history", "velocity": "velocity_history"}
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
    """A record that cannot be used; ``field`` is the key of its block (``force_history``,
    ``strain_history`` or ``velocity_history``) it concerns (``file`` for the file's own faults)."""

    def __init__(self, field: str, message: str) -> None:
        self.field, self.reason = field, message
        super().__init__(f"{field}: {message}")


@dataclass(frozen=True)
class MeasuredHistory:
    """A measured record against time, in SI units.

    Attributes
    ----------
    time_s : ndarray, shape (n,)
        Strictly increasing times, s (with the declared offset).
    values : ndarray, shape (n,)
        The value in the kind's SI unit (force, N; strain, 1; velocity, m/s), times the
        block's ``sign``.
    path : Path
        The file it was read from.
    note : str
        How it was measured (the block's ``note``).
    kind : str
        The record's key in the ``measured`` block (:data:`RECORDS`).
    header : tuple of str
        The file's header, its two cells as written (``("time_us", "strain_microstrain")``).
    time_unit, value_unit : str
        The units the times and the values were read in (keys of :data:`TIME_UNITS` and of the
        kind's units), from the header or from the block.
    """

    time_s: NDArray[np.float64]
    values: NDArray[np.float64]
    path: Path
    note: str = ""
    kind: str = "force_history"
    header: tuple[str, str] = ("time_s", "force_N")
    time_unit: str = "s"
    value_unit: str = "N"

    def unit_from_header(self, column: int) -> bool:
        """Whether the header itself names the unit of ``column`` (0: the time, 1: the value),
        rather than the block's ``time_unit`` (or the value's unit key)."""
        return bool(self.header[column].strip().partition("_")[2])

    @property
    def force_N(self) -> NDArray[np.float64]:
        """The values of a force record, N."""
        return self.values


def _unit(name: str, quantity: str, declared: str | None, units: Mapping[str, float], where: str) -> str:
    """The unit of a column from its header name (``time_ms``) or the declared unit; ``where``
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
    return unit


def read_force_history(path: str | Path, spec: Mapping[str, Any]) -> MeasuredHistory:
    """Read and check the force history ``path`` as the ``force_history`` block ``spec`` declares
    it (:func:`read_history` of that kind)."""
    return read_history(path, spec, "force_history")


def read_history(path: str | Path, spec: Mapping[str, Any], key: str) -> MeasuredHistory:
    """Read and check the record ``path`` as the ``measured`` block's ``key`` (one of
    :data:`RECORDS`) ``spec`` declares it.

    The file is read as :func:`rodimpact.inputs.files.read_text` reads a user's file: a regular
    file only (never a FIFO or a device), at most :data:`MAX_HISTORY_BYTES`, UTF-8 (a bad byte
    named by its line and column); a cell longer than :data:`MAX_CELL_CHARS` is refused by its
    line and column.

    Parameters
    ----------
    path : path
        The CSV file (already resolved against the case file's directory).
    spec : mapping
        ``time_unit`` and the value's unit (``force_unit``, ``strain_unit``, ``velocity_unit``;
        optional where the header names them), ``sign`` (default 1), ``time_offset_s``
        (default 0), ``every`` (default 1), ``note``.
    key : str
        The kind of record, a key of :data:`RECORDS`.

    Returns
    -------
    MeasuredHistory

    Raises
    ------
    HistoryError
        Whatever makes the file unusable, with the block's key it concerns.
    """
    kind = RECORDS[key]
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
                f"{path.name} must start with a header of two columns, time and {kind.quantity} "
                f"(e.g. 'time_s,{kind.quantity}_{next(iter(kind.units))}'), got {quoted(header)}",
            )
        time_unit = _unit(header[0], "time", spec.get("time_unit"), TIME_UNITS, f"{path.name} line 1, column 1")
        value_unit = _unit(
            header[1], kind.quantity, spec.get(f"{kind.quantity}_unit"), kind.units, f"{path.name} line 1, column 2"
        )
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
    read = np.asarray(values, dtype=float).reshape(-1, 2)
    data = read[::every]
    if len(data) < MIN_ROWS:
        if len(read) >= MIN_ROWS:  # the file has the rows; the thinning leaves too few
            raise HistoryError(
                "every",
                f"every: {every} keeps {len(data)} of the {len(read)} rows of {path.name}, fewer than "
                f"{MIN_ROWS}; keep every {max(len(read) // MIN_ROWS, 1)}-th row at most",
            )
        raise HistoryError("file", f"{path.name} keeps {len(data)} rows, fewer than {MIN_ROWS}")
    scaled = data[:, 0] * TIME_UNITS[time_unit]
    offset = float(spec.get("time_offset_s") or 0.0)
    steps = np.diff(scaled)
    if np.any(steps <= 0):
        bad = int(np.argmax(steps <= 0))
        raise HistoryError(
            "file",
            f"{path.name} line {2 + (bad + 1) * every}: the time must increase, "
            f"{scaled[bad + 1]:.6g} s follows {scaled[bad]:.6g} s",
        )
    time = scaled + offset
    if not np.all(np.isfinite(time)) or np.any(np.diff(time) <= 0):
        raise HistoryError(
            "time_offset_s",
            f"an offset of {offset:.6g} s swamps the times of {path.name}: their steps of {float(np.min(steps)):.3g} s "
            "vanish in double precision once it is added; the offset moves the impact to time zero, a shift of the "
            "order of the record's own span",
        )
    value = data[:, 1] * kind.units[value_unit] * float(spec.get("sign") or 1)
    high, low = float(value.max()), float(value.min())
    if high <= 0.0 and low >= 0.0:
        what = "no contact" if key == "force_history" else "nothing"
        raise HistoryError("file", f"{path.name}: the {kind.quantity} is zero throughout: {what} was recorded")
    return MeasuredHistory(
        time_s=time,
        values=value,
        path=path,
        note=str(spec.get("note", "")),
        kind=key,
        header=(header[0], header[1]),
        time_unit=time_unit,
        value_unit=value_unit,
    )


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
