"""The sensor's artifact: the table of its bands, from band files and case files only."""

from __future__ import annotations

import logging
from collections.abc import Sequence
from pathlib import Path

from rodimpact.present.film_tables import write_provenance_with_files
from rodimpact.present.sensor_tables import sensor_band_frame
from rodimpact.present.table_formats import panels
from rodimpact.present.tables import write_table
from rodimpact.storage.bands import read_band
from rodimpact.storage.casefile import read_case_file

__all__ = ["make_sensor_band_table"]

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
            "constant lengthens (shortens) the contact (µs); whether the measurement lies inside; the nominal's "
            "error (model − measured) / measured; and whether the time is monotone along each constant's range "
            "(then the corners bound it)."
        ),
    )
    write_provenance_with_files(provenance, [], _outputs(csv, md, html), {"band": bands, "case file": case_files})
    log.info("sensor bands: %d cases, %d measurements inside", len(frame), int(frame["measured_in_band"].sum()))
