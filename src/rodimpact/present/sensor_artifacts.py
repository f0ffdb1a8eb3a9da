"""The bands' artifacts: the table of the sensor's bands, and the tables of the axes of the
sensor's and of the film's bands (each constant along its range, ``make sensor-axes`` and ``make
film-axes``), from band files and case files only."""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from rodimpact.present.artifact_common import _cases_in, _outputs
from rodimpact.present.film_tables import write_provenance_with_files
from rodimpact.present.sensor_tables import band_axes_frame, sensor_band_frame
from rodimpact.present.table_formats import panels
from rodimpact.present.tables import write_table
from rodimpact.storage.bands import read_band

__all__ = ["AXES_TABLES", "make_axes_table", "make_sensor_band_table"]

log = logging.getLogger(__name__)


def _read(bands: Sequence[str | Path], case_files: Sequence[str | Path]) -> tuple[list, dict]:
    """(variant, CaseBand) of every case of the band files, and case id -> resolved case."""
    return [(variant, band) for variant, group in map(read_band, bands) for band in group], _cases_in(case_files)


def make_sensor_band_table(
    bands: Sequence[str | Path],
    case_files: Sequence[str | Path],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Every case's band (:func:`sensor_band_frame`); rows and masses from the case files."""
    frame = sensor_band_frame(*_read(bands, case_files))
    views = panels(
        frame,
        "The sensor as built: the continuum's prediction and its band",
        ["row"],
        [
            "measured_us",
            "band_min_us",
            "nominal_us",
            "band_max_us",
            "measured_in_band",
            "nominal_error_pct",
            "monotone",
        ],
        by="variant",
    )
    axes = "monotone" in frame.columns
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=views,
        caption=(
            "The sensor as built (electrodes, PVDF film, bond line; each constant from its source, none fitted): "
            "the contact time by the SEM with the contact law the continuum's static indentation gives on the "
            "stack, at the nominal constants and at the two corners of the box of their ranges where every "
            "constant lengthens (shortens) the contact (µs); whether the measurement lies inside; and the nominal's "
            "error (model − measured) / measured. "
            + (
                "Monotone: whether the time is monotone along each constant's range (then the corners bound it)."
                if axes
                else "Which end of a range lengthens the contact is the stack's analytic law's; that the continuum's "
                "time is monotone along every range and lengthens at the same ends is the table "
                "sensor_band_axes (make sensor-axes)."
            )
        ),
    )
    write_provenance_with_files(provenance, [], _outputs(csv, md, html), {"band": bands, "case file": case_files})
    log.info("sensor bands: %d cases, %d measurements inside", len(frame), int(frame["measured_in_band"].sum()))


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


def make_axes_table(
    bands: Sequence[str | Path],
    case_files: Sequence[str | Path],
    *,
    kind: str,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Every constant's range per case (:func:`band_axes_frame`) of the bands of ``kind`` (a key
    of :data:`AXES_TABLES`), computed with their axes; rows and masses from the case files.

    Raises
    ------
    ValueError
        No band has its axes (the band files are the default build's, not ``make sensor-axes``'
        or ``make film-axes``').
    """
    spec = AXES_TABLES[kind]
    frame = band_axes_frame(*_read(bands, case_files))
    if frame.empty:
        raise ValueError(f"bands: none of the {len(bands)} band files has its axes")
    frame = frame.rename(columns=dict(spec.rename))
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=panels(frame, spec.title, ["row", "constant"], list(spec.values), by="variant"),
        caption=spec.caption,
    )
    write_provenance_with_files(provenance, [], _outputs(csv, md, html), {"band": bands, "case file": case_files})
    agree = f", {int(frame['agree'].fillna(False).sum())} with the analytic law's direction" if "agree" in frame else ""
    log.info("%s axes: %d ranges, %d monotone%s", kind, len(frame), int(frame["monotone"].sum()), agree)
