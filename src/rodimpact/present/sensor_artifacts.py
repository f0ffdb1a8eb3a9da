"""The sensor's artifacts (its tables and the fit's figure), each from band files and case files only."""

from __future__ import annotations

import json
import logging
from collections.abc import Mapping, Sequence
from pathlib import Path

from rodimpact.present.film_tables import write_provenance_with_files
from rodimpact.present.sensor_tables import sensor_band_frame, sensor_fit_frame
from rodimpact.present.table_formats import panels
from rodimpact.present.tables import write_table
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.bands import read_band
from rodimpact.storage.casefile import read_case_file
from rodimpact.storage.sidecar import provenance_record

__all__ = ["make_fig_sensor_fit", "make_sensor_band_table", "make_sensor_fit_table"]

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


def _fit(fitted: Sequence[str | Path], applied: Sequence[str | Path], case_files: Sequence[str | Path], layer: str):
    cases = {record["case_id"]: record["case"] for path in case_files for record in read_case_file(path)["cases"]}
    variants, bands = {}, {}
    for path in [*fitted, *applied]:
        variant, group = read_band(path)
        for band in group:
            variants[band.case_id], bands[str(path)] = variant, band
    return sensor_fit_frame([bands[str(p)] for p in fitted], [bands[str(p)] for p in applied], cases, layer, variants)


def make_fig_sensor_fit(
    fitted: Sequence[str | Path],
    applied: Sequence[str | Path],
    case_files: Sequence[str | Path],
    layer: str,
    *,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
    descriptions: Mapping[str, str] | None = None,
) -> None:
    """The fit's figure (:func:`~rodimpact.present.sensor_figures.plot_sensor_fit`)."""
    from rodimpact.present.figures import save_figure
    from rodimpact.present.sensor_figures import plot_sensor_fit

    frame, facts = _fit(fitted, applied, case_files, layer)
    artifacts = [pdf, png]
    record = provenance_record([], artifacts)
    record["input_files"] = [str(p) for p in [*fitted, *applied, *case_files]]
    save_figure(
        plot_sensor_fit(frame, facts, descriptions),
        pdf=pdf,
        png=png,
        provenance=record,
        title="A fit of the sensor's bond line",
    )
    write_provenance_with_files(provenance, [], artifacts, {"band": [*fitted, *applied], "case file": case_files})


def make_sensor_fit_table(
    fitted: Sequence[str | Path],
    applied: Sequence[str | Path],
    case_files: Sequence[str | Path],
    layer: str,
    *,
    csv: str | Path,
    md: str | Path,
    summary: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """The inverse analysis (:func:`sensor_fit_frame`), its table and its summary (JSON)."""
    frame, facts = _fit(fitted, applied, case_files, layer)
    views = panels(
        frame,
        f"A fit, not a prediction: the {layer}'s thickness fitted to the measurements",
        ["row"],
        [
            "measured_us",
            "nominal_us",
            "fitted_us",
            "held_out_us",
            "nominal_error_pct",
            "fitted_error_pct",
            "held_out_error_pct",
        ],
        by="variant",
    )
    inside = "inside" if facts["inside_source_range"] else "outside"
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=views,
        caption=(
            f"A fit, labelled as such: the {layer}'s thickness fitted by least squares (relative errors) to the "
            f"{facts['rows']} measured contact times is {facts['fitted_thickness_um']:.1f} ± "
            f"{facts['standard_error_um']:.1f} µm, {inside} its sourced range "
            f"{facts['source_low_um']:.0f}–{facts['source_high_um']:.0f} µm (status {facts['status']}). Per row: the "
            f"measured time, the sourced stack's (nominal), the fitted stack's, and for the fitted reading the "
            f"prediction of a fit on the other rows (held out; mean |error| {facts['loo_mean_abs_error_pct']:.2f} %); "
            f"the applied reading takes the fitted thickness. Times by the SEM with the continuum's law (µs)."
        ),
    )
    with atomic_output(summary) as tmp:
        tmp.write_text(json.dumps(facts, indent=2) + "\n", encoding="utf-8")
    write_provenance_with_files(
        provenance, [], _outputs(csv, md, html, summary), {"band": [*fitted, *applied], "case file": case_files}
    )
