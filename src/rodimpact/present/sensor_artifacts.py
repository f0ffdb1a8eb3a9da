"""The sensor's artifacts: the table of its bands and the table of their axes, from band files and
case files only."""

from __future__ import annotations

import logging
from collections.abc import Sequence
from pathlib import Path

from rodimpact.present.film_tables import write_provenance_with_files
from rodimpact.present.sensor_tables import band_axes_frame, sensor_band_frame
from rodimpact.present.table_formats import panels
from rodimpact.present.tables import write_table
from rodimpact.storage.bands import read_band
from rodimpact.storage.casefile import read_case_file

__all__ = ["make_sensor_axes_table", "make_sensor_band_table"]

log = logging.getLogger(__name__)


def _outputs(*paths: str | Path | None) -> list[str | Path]:
    return [p for p in paths if p is not None]


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
    cases = {record["case_id"]: record["case"] for path in case_files for record in read_case_file(path)["cases"]}
    read = [read_band(p) for p in bands]
    frame = sensor_band_frame([(variant, band) for variant, group in read for band in group], cases)
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


def make_sensor_axes_table(
    bands: Sequence[str | Path],
    case_files: Sequence[str | Path],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Every constant's range by the continuum, per case (:func:`band_axes_frame`), from bands
    computed with their axes; rows and masses from the case files.

    Raises
    ------
    ValueError
        No band has its axes (the band files are the default build's, not ``make sensor-axes``').
    """
    cases = {record["case_id"]: record["case"] for path in case_files for record in read_case_file(path)["cases"]}
    read = [read_band(p) for p in bands]
    frame = band_axes_frame([(variant, band) for variant, group in read for band in group], cases)
    if frame.empty:
        raise ValueError(f"bands: none of the {len(bands)} band files has its axes")
    views = panels(
        frame,
        "The sensor as built: each constant's range by the continuum",
        ["row", "constant"],
        [
            "low",
            "high",
            "low_us",
            "nominal_us",
            "high_us",
            "monotone",
            "continuum_lengthens_at",
            "law_lengthens_at",
            "agree",
        ],
        by="variant",
    )
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=views,
        caption=(
            "The sensor as built, each constant of the stack along its sourced range with the others nominal: "
            "the contact time by the SEM with the law of the continuum's static indentation at the range's low end, "
            "at the nominal and at its high end (µs); whether it is monotone along the range; and which end "
            "lengthens the contact by the continuum and by the stack's analytic (thin-layer) law, which the "
            "default build's band takes for its corners."
        ),
    )
    write_provenance_with_files(provenance, [], _outputs(csv, md, html), {"band": bands, "case file": case_files})
    log.info(
        "sensor axes: %d ranges, %d monotone, %d with the analytic law's direction",
        len(frame),
        int(frame["monotone"].sum()),
        int(frame["agree"].fillna(False).sum()),
    )
