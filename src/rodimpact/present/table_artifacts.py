"""The workflow's tables written from stored runs, band files and curve files: Table 2 per
reading and its summary over the readings, Table 2 with the sensor film and the film's bands and
indentation curves, the sweep table and Fig. 2's numbers; each with its provenance sidecar.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from pathlib import Path

from rodimpact.present.artifact_common import _by_variant, _cases_in, _outputs
from rodimpact.present.film_tables import (
    film_band_frame,
    film_indentation_frame,
    film_table_frame,
    readings_frame,
    write_provenance_with_files,
)
from rodimpact.present.table_views import (
    comparison_views,
    film_band_views,
    film_indentation_views,
    film_table_views,
    reading_views,
    reading_words,
    sweep_views,
    variants_views,
)
from rodimpact.present.tables import (
    comparison_frame,
    load_records,
    sweep_results_frame,
    table2_frame,
    variants_summary,
    write_table,
)
from rodimpact.storage.bands import read_band
from rodimpact.storage.curves import read_contact_curve
from rodimpact.storage.sidecar import write_provenance

__all__ = [
    "make_comparison",
    "make_film_band_table",
    "make_film_indentation_table",
    "make_film_table",
    "make_readings_summary",
    "make_readings_table",
    "make_sweep_table",
]

log = logging.getLogger(__name__)

READING_CAPTION = (
    "{title}, rod reading {variant}: {reading}. Contact times in µs; errors |model − measured| / measured in %."
)


def make_readings_table(
    runs: Sequence[str | Path],
    variant: str,
    *,
    title: str,
    csv: str | Path,
    md: str | Path,
    tex: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
    reference: str = "",
) -> None:
    """One reading of a set with variants (for the paper's set, ``title`` "Table 2": Table 2 for
    one reading of the rod), the LaTeX and HTML in two panels: the contact times, the errors; with
    its provenance sidecar. ``reference``: the work the set comes from, in the LaTeX caption."""
    records = load_records(runs)
    wrong = sorted({r.case_id for r in records if r.config.get("variant") != variant})
    if wrong:
        raise ValueError(f"runs: cases {wrong} do not belong to variant {variant!r}")
    frame = table2_frame(records)
    caption = READING_CAPTION.format(
        title=title, variant=variant, reading=reading_words(records[0].config) if records else ""
    )
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        tex=tex,
        caption=caption,
        views=reading_views(frame, variant, records, title, reference),
    )
    write_provenance(provenance, records, _outputs(csv, md, html, tex))
    log.info("%s (%s): %d rows from %d runs", title, variant, len(frame), len(records))


def make_readings_summary(
    runs: Sequence[str | Path],
    variants: Sequence[str],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Per variant and method, the mean and max error against the measurements."""
    records, frames = _by_variant(runs, variants)
    readings = readings_frame(records).set_index("variant").to_dict("index")
    summary = variants_summary(frames, readings)
    write_table(
        summary,
        csv=csv,
        md=md,
        html=html,
        views=variants_views(summary),
        caption=(
            "Error against the measured contact times, per rod geometry reading (with or without the sensor "
            "film, and its contact law) and method, next to the paper's own errors (%)."
        ),
    )
    write_provenance(provenance, records, _outputs(csv, md, html))


def _table_artifact(
    runs: Sequence[str | Path],
    build,
    views,
    *,
    csv: str | Path,
    md: str | Path,
    html: str | Path | None,
    provenance: str | Path,
    caption: str,
) -> None:
    """Read the runs, build a frame from them, write it as CSV, Markdown and HTML (its panels
    ``views(frame)``) with provenance."""
    records = load_records(runs)
    frame = build(records)
    write_table(frame, csv=csv, md=md, html=html, caption=caption, views=views(frame))
    write_provenance(provenance, records, _outputs(csv, md, html))


FILM_TABLE_CAPTION = (
    "Table 2 on the rod of the text, without the sensor, with the film alone and with the sensor as built "
    "(electrodes, film and bond line, each from its source): measured and published contact times, ours by "
    "every method (no film: Hertz; film and sensor: the layers bonded in the continuum, the thin-layer law "
    "for the 1-D methods, an approximation; calibrated: the law of the continuum's static indentation), "
    "the sensor's prediction band from the continuum (calibrated SEM over the stack's sourced ranges), the "
    "film's band with the thin-layer law (approximation), each model's |model - measured| / measured, the "
    "contact radius over the film thickness (thin-layer law, SEM), and the model-form error of the "
    "quasi-static contact: (calibrated SEM - continuum) / continuum, with the film and with the sensor."
)


def make_film_table(
    runs: Sequence[str | Path],
    variants: Mapping[str, str],
    band: str | Path,
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
    sensor_bands: Sequence[str | Path] = (),
) -> None:
    """Table 2 on one rod without and with the film and the sensor as built
    (:func:`film_table_frame`), and its sidecar."""
    records = load_records(runs)
    band_variant, bands = read_band(band)
    if band_variant != variants.get("film"):
        raise ValueError(f"{band}: the band of {band_variant!r}, not of the film reading {variants.get('film')!r}")
    sensor = [b for p in sensor_bands for b in read_band(p)[1]]
    frame = film_table_frame(records, variants, bands, sensor_bands=sensor)
    write_table(frame, csv=csv, md=md, html=html, caption=FILM_TABLE_CAPTION, views=film_table_views(frame))
    write_provenance_with_files(
        provenance, records, _outputs(csv, md, html), {"band": [band], "sensor band": sensor_bands}
    )
    log.info("table 2 with the film: %d rows from %d runs", len(frame), len(records))


def make_film_band_table(
    bands: Sequence[str | Path],
    case_files: Sequence[str | Path],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Every case of every band file (:func:`film_band_frame`); rows and masses from the case files."""
    frame = film_band_frame(dict(read_band(p) for p in bands), _cases_in(case_files))
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=film_band_views(frame),
        caption=(
            "The sensor film's prediction band per Table 2 row and film reading: the SEM's contact time at the "
            "film's nominal constants and its min and max over the corners of the box of their ranges (µs), and "
            "whether the measurement lies inside. "
            + (
                "Monotone: whether the time is monotone along each range (then the corners bound it)."
                if "monotone" in frame.columns
                else "That the time is monotone along each range, so that the corners bound it, is the table "
                "film_band_axes (make film-axes)."
            )
        ),
    )
    write_provenance_with_files(provenance, [], _outputs(csv, md, html), {"band": bands, "case file": case_files})
    log.info(
        "film bands: %d cases of %d readings, %d measurements inside",
        len(frame),
        len(bands),
        int(frame["measured_in_band"].sum()),
    )


def make_film_indentation_table(
    curves: Sequence[str | Path],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Every point of every indentation curve against its analytic law (:func:`film_indentation_frame`)."""
    frame = film_indentation_frame([read_contact_curve(p) for p in curves])
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=film_indentation_views(frame),
        caption=(
            "The continuum's static indentation (the calibrated contact laws) against the analytic law at the "
            "same force (hertz_film with the film, hertz without): approaches (µm), the law's error "
            "(law − continuum) / continuum (%), the contact radius (µm) and its ratio to the film thickness, and "
            "the tabulated law's interpolation error (every other point)."
        ),
    )
    write_provenance_with_files(provenance, [], _outputs(csv, md, html), {"contact curve": curves})


def make_sweep_table(
    runs: Sequence[str | Path],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Every sweep point's contact time and force, one row per point and method."""
    _table_artifact(
        runs,
        sweep_results_frame,
        sweep_views,
        csv=csv,
        md=md,
        html=html,
        provenance=provenance,
        caption="Parameter sweeps: contact time (first contact, µs) and force maxima (N) at every point.",
    )


def make_comparison(
    runs: Sequence[str | Path],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """Fig. 2's numbers: contact time and each maximum per method, differences from the SEM,
    and the paper's 11 % and 9 % beside them."""
    _table_artifact(
        runs,
        comparison_frame,
        comparison_views,
        csv=csv,
        md=md,
        html=html,
        provenance=provenance,
        caption=(
            "Fig. 2, case 'model': contact time (µs) and force maxima (kN) of the first contact "
            "per method; differences from our SEM (%), next to the paper's FEM-SEM differences (%)."
        ),
    )
