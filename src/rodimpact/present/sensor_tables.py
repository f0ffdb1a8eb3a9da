"""The tables of the sensor as built and of the bands' axes, from band files and case files only.

:func:`sensor_band_table`: each row's contact time by the SEM with the law the continuum
calibrates on the stack, at the sourced nominal constants and over their ranges (the band), and
whether the measurement lies inside. :func:`axes_table`: each constant's range, the others
nominal, for any bands computed with their axes (the sensor's, ``make sensor-axes``; the film's,
``make film-axes``). Each table is declared here once, its columns beside its frame.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.errors import relative_error_pct
from rodimpact.present.columns import shared
from rodimpact.present.inputs import cases_in
from rodimpact.present.table import Column, Table, TableArtifact, panels
from rodimpact.storage.bands import CaseBand, read_band

__all__ = [
    "AXES_TABLES",
    "CALIBRATED_METHOD",
    "axes_table",
    "band_axes_frame",
    "make_axes_table",
    "make_sensor_band_table",
    "sensor_band_frame",
    "sensor_band_table",
]

log = logging.getLogger(__name__)

#: How the band's times are computed, in words.
CALIBRATED_METHOD = "SEM with the law of the continuum's indentation"


def _row(case: Mapping[str, Any], case_id: str) -> tuple[str, float]:
    mass = 1000.0 * float(case["impactor"]["mass_kg"]) if case else math.nan
    return str(case.get("row", case_id)), mass


def sensor_band_frame(bands: Sequence[tuple[str, CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """One row per case: ``variant, row, case_id, mass_g, method, measured_us, band_min_us,
    nominal_us, band_max_us, measured_in_band, nominal_error_pct, constants``, and ``monotone``
    where some band has its axes.

    Parameters
    ----------
    bands : sequence of (variant, CaseBand)
        The band of each case (``read_band`` of each ``sensor_band`` file).
    cases : mapping
        Case id -> resolved case (row and mass).
    """
    rows = []
    for variant, band in bands:
        row, mass = _row(cases.get(band.case_id) or {}, band.case_id)
        measured = band.measured_us
        rows.append(
            {
                "variant": variant,
                "row": row,
                "case_id": band.case_id,
                "mass_g": mass,
                "method": CALIBRATED_METHOD,
                "measured_us": measured,
                "band_min_us": band.band_min_us,
                "nominal_us": band.nominal_us,
                "band_max_us": band.band_max_us,
                "measured_in_band": bool(math.isfinite(measured) and band.band_min_us <= measured <= band.band_max_us),
                "nominal_error_pct": relative_error_pct(band.nominal_us, measured),
                "monotone": band.monotone,
                "constants": len(band.parameters),
            }
        )
    columns = [column.name for column in _SENSOR_BAND]
    if all(band.monotone is None for _, band in bands):
        columns.remove("monotone")
    frame = pd.DataFrame(rows, columns=columns)
    return frame.sort_values(["variant", "mass_g"], kind="stable").reset_index(drop=True)


def _end(high: bool) -> str:
    return "high" if high else "low"


def band_axes_frame(bands: Sequence[tuple[str, CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """One row per case and constant of the bands that have their axes: ``variant, row, case_id,
    mass_g, constant, low, high`` (the constant's range, SI), ``low_us, nominal_us, high_us``
    (the time with the constant at its low end, every constant nominal, the constant at its high
    end), ``monotone`` (along this range), ``continuum_lengthens_at`` (the end, ``high`` or
    ``low``, that lengthens the contact by the band's own model: the sensor's continuum, the
    film's thin-layer law), and, where some band records the direction of the bodies' analytic
    law (the sensor's), ``law_lengthens_at`` and ``agree``. Bands without axes give no row."""
    rows = []
    for variant, band in bands:
        row, mass = _row(cases.get(band.case_id) or {}, band.case_id)
        for index, name in enumerate(band.parameters):
            if name not in band.axis_us:
                continue
            values, times = np.asarray(band.axis_values[name]), np.asarray(band.axis_us[name])
            steps = np.diff(times)
            continuum = bool(times[-1] >= times[0])
            law = band.law_longer_high[index] if band.law_longer_high else None
            rows.append(
                {
                    "variant": variant,
                    "row": row,
                    "case_id": band.case_id,
                    "mass_g": mass,
                    "constant": name,
                    "low": float(values[0]),
                    "high": float(values[-1]),
                    "low_us": float(times[0]),
                    "nominal_us": band.nominal_us,
                    "high_us": float(times[-1]),
                    "monotone": bool(np.all(steps >= 0) or np.all(steps <= 0)),
                    "continuum_lengthens_at": _end(continuum),
                    "law_lengthens_at": None if law is None else _end(law),
                    "agree": None if law is None else bool(law == continuum),
                }
            )
    frame = pd.DataFrame(rows)
    if not any(band.law_longer_high for _, band in bands):
        frame = frame.drop(columns=["law_lengthens_at", "agree"], errors="ignore")
    return frame.sort_values(["variant", "mass_g"], kind="stable").reset_index(drop=True) if rows else frame


#: The columns of the sensor's and the axes' tables that no other table has.
_BAND_COLUMNS = {
    c.name: c
    for c in (
        Column("nominal_error_pct", "Nominal error", "%"),
        Column("constants", "Constants", fmt=""),
        Column("constant", "Constant", fmt=""),
        Column("low", "Least", fmt=".4g"),
        Column("high", "Largest", fmt=".4g"),
        Column("low_us", "At the low end", "µs"),
        Column("high_us", "At the high end", "µs"),
        Column("continuum_lengthens_at", "Continuum lengthens at", fmt=""),
        Column("lengthens_at", "Lengthens at", fmt=""),
        Column("law_lengthens_at", "Analytic law lengthens at", fmt=""),
        Column("agree", "Same end", fmt=""),
    )
}


#: The sensor band table's columns, in order.
_SENSOR_BAND = (
    *shared(["variant", "row", "case_id", "mass_g", "method", "measured_us", "band_min_us", "nominal_us"]),
    *shared(["band_max_us", "measured_in_band"]),
    _BAND_COLUMNS["nominal_error_pct"],
    *shared(["monotone"]),
    _BAND_COLUMNS["constants"],
)


def _read(bands: Sequence[str | Path], case_files: Sequence[str | Path]) -> tuple[list, dict]:
    """(variant, CaseBand) of every case of the band files, and case id -> resolved case."""
    return [(variant, band) for variant, group in map(read_band, bands) for band in group], cases_in(case_files)


def sensor_band_table(bands: Sequence[tuple[str, CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> Table:
    """Every case's band (:func:`sensor_band_frame`), a panel per reading."""
    frame = sensor_band_frame(bands, cases)
    axes = (
        "Monotone: whether the time is monotone along each constant's range (then the corners bound it)."
        if "monotone" in frame.columns
        else "Which end of a range lengthens the contact is the stack's analytic law's; that the continuum's "
        "time is monotone along every range and lengthens at the same ends is the table "
        "sensor_band_axes (make sensor-axes)."
    )
    table = Table(
        frame,
        _SENSOR_BAND,
        "The sensor as built (electrodes, PVDF film, bond line; each constant from its source, none fitted): "
        "the contact time by the SEM with the contact law the continuum's static indentation gives on the "
        "stack, at the nominal constants and at the two corners of the box of their ranges where every "
        "constant lengthens (shortens) the contact (µs); whether the measurement lies inside; and the nominal's "
        f"error (model − measured) / measured. {axes}",
    )
    return table.showing(
        panels(
            table,
            "The sensor as built: the continuum's prediction and its band",
            ["row"],
            [
                c.name
                for c in _SENSOR_BAND
                if c.name not in ("variant", "row", "case_id", "mass_g", "method", "constants")
            ],
            by="variant",
        )
    )


@dataclass(frozen=True)
class _AxesTable:
    """What one kind of band's axes table shows: its title, value columns and caption, and the
    frame's columns it renames."""

    title: str
    values: tuple[str, ...]
    caption: str
    rename: tuple[tuple[str, str], ...] = ()


#: The bands whose axes have a table: the sensor's (make sensor-axes) and the film's (make film-axes).
AXES_TABLES = {
    "sensor": _AxesTable(
        "The sensor as built: each constant's range by the continuum",
        (
            "low",
            "high",
            "low_us",
            "nominal_us",
            "high_us",
            "monotone",
            "continuum_lengthens_at",
            "law_lengthens_at",
            "agree",
        ),
        "The sensor as built, each constant of the stack along its sourced range with the others nominal: "
        "the contact time by the SEM with the law of the continuum's static indentation at the range's low end, "
        "at the nominal and at its high end (µs); whether it is monotone along the range; and which end "
        "lengthens the contact by the continuum and by the stack's analytic (thin-layer) law, which the "
        "default build's band takes for its corners.",
    ),
    "film": _AxesTable(
        "The sensor film: each constant's range by the thin-layer law",
        ("low", "high", "low_us", "nominal_us", "high_us", "monotone", "lengthens_at"),
        "The sensor film, each constant (Young's modulus, Poisson's ratio, thickness) along its range with the "
        "others nominal: the SEM's contact time with the thin-layer law at the range's low end, at the nominal "
        "and at its high end (µs), whether it is monotone along the range (then the corners of the box, the "
        "band of film_band, bound it) and which end lengthens the contact.",
        # the film's band is the thin-layer law's, not the continuum's
        (("continuum_lengthens_at", "lengthens_at"),),
    ),
}


def axes_table(bands: Sequence[tuple[str, CaseBand]], cases: Mapping[str, Mapping[str, Any]], kind: str) -> Table:
    """Every constant's range per case (:func:`band_axes_frame`) of the bands of ``kind`` (a key
    of :data:`AXES_TABLES`), a panel per reading.

    Raises
    ------
    ValueError
        No band has its axes (the band files are the default build's, not ``make sensor-axes``'
        or ``make film-axes``').
    """
    spec = AXES_TABLES[kind]
    frame = band_axes_frame(bands, cases)
    if frame.empty:
        raise ValueError(f"bands: none of the {len(bands)} band files has its axes")
    frame = frame.rename(columns=dict(spec.rename))
    table = Table(
        frame,
        (*shared(["variant", "row", "case_id", "mass_g", "nominal_us", "monotone"]), *_BAND_COLUMNS.values()),
        spec.caption,
    )
    return table.showing(panels(table, spec.title, ["row", "constant"], list(spec.values), by="variant"))


def make_sensor_band_table(bands: Sequence[str | Path], case_files: Sequence[str | Path]) -> TableArtifact:
    """Every case's band (:func:`sensor_band_table`); rows and masses from the case files."""
    table = sensor_band_table(*_read(bands, case_files))
    frame = table.frame
    log.info("sensor bands: %d cases, %d measurements inside", len(frame), int(frame["measured_in_band"].sum()))
    return TableArtifact(table, (), {"band": bands, "case file": case_files})


def make_axes_table(bands: Sequence[str | Path], case_files: Sequence[str | Path], kind: str) -> TableArtifact:
    """Every constant's range per case of the bands of ``kind`` (:func:`axes_table`); rows and
    masses from the case files."""
    table = axes_table(*_read(bands, case_files), kind)
    frame = table.frame
    agree = f", {int(frame['agree'].fillna(False).sum())} with the analytic law's direction" if "agree" in frame else ""
    log.info("%s axes: %d ranges, %d monotone%s", kind, len(frame), int(frame["monotone"].sum()), agree)
    return TableArtifact(table, (), {"band": bands, "case file": case_files})
