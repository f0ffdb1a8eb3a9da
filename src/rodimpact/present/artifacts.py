"""One function per artifact of the workflow: read HDF5 runs, write tables and figures.

The workflow's scripts call these and nothing else; tests call them directly. The figure modules
(matplotlib) are imported by the functions that draw, so that a table's job does not load them.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rodimpact.analysis.stability_study import StudyViolation, map_frame, stability_frame, violations
from rodimpact.analysis.work_precision import ORDER_TOLERANCE, observed_orders, work_precision_frame
from rodimpact.present.film_tables import (
    film_band_frame,
    film_indentation_frame,
    film_table_frame,
    readings_frame,
    table2_panels,
    write_provenance_with_files,
)
from rodimpact.present.sensor_tables import sensor_band_frame
from rodimpact.present.table_views import (
    comparison_views,
    film_band_views,
    film_indentation_views,
    film_table_views,
    orders_views,
    reading_views,
    reading_words,
    stability_views,
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
from rodimpact.storage.casefile import read_case_file
from rodimpact.storage.curves import read_contact_curve
from rodimpact.storage.runs import read_run
from rodimpact.storage.sidecar import provenance_record, write_provenance

__all__ = [
    "make_comparison",
    "make_fig2",
    "make_fig4",
    "make_fig_film_force",
    "make_fig_readings",
    "make_film_band_table",
    "make_film_indentation_table",
    "make_stability",
    "make_stability_map",
    "make_sweep_table",
    "make_readings_table",
    "make_film_table",
    "make_readings_summary",
    "make_work_precision",
    "make_work_precision_figure",
    "make_fig_force_fit",
    "case_in_words",
]

log = logging.getLogger(__name__)

READING_CAPTION = (
    "{title}, rod reading {variant}: {reading}. Contact times in µs; errors |model − measured| / measured in %."
)


def _by_variant(runs: Sequence[str | Path], variants: Sequence[str]):
    records = load_records(runs)
    grouped = {v: [r for r in records if r.config.get("variant") == v] for v in variants}
    return records, {v: table2_frame(recs) for v, recs in grouped.items() if recs}


def _outputs(*paths: str | Path | None) -> list[str | Path]:
    return [p for p in paths if p is not None]


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


def _one_case(records: Sequence, what: str) -> str:
    """The single case id of ``records`` (a figure of one case)."""
    cases = sorted({r.case_id for r in records})
    if len(cases) != 1:
        raise ValueError(f"runs: {what} shows one case, got {cases}")
    return cases[0]


def _save_figure(
    fig, records: Sequence, *, pdf: str | Path, png: str | Path, provenance: str | Path, title: str
) -> None:
    """Save a figure (its provenance in the PDF/PNG metadata) and its provenance sidecar."""
    from rodimpact.present.figures import save_figure

    save_figure(fig, pdf=pdf, png=png, provenance=provenance_record(records, [pdf, png]), title=title)
    write_provenance(provenance, records, [pdf, png])


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


def case_in_words(config: Mapping[str, Any]) -> str:
    """A case in words for a title: its ``description`` and its rod (mm), e.g. ``Table 2 row 1:
    steel ball, diameter 3.16 mm, mass 0.13 g; rod radius 1 mm, length 30.1 mm``."""
    rod = config.get("rod") or {}
    if rod.get("radius_m") is not None:
        words = f"rod radius {1000 * float(rod['radius_m']):.3g} mm, length {1000 * float(rod['length_m']):.3g} mm"
    else:
        words = (
            f"rod length {1000 * float(rod['length_m']):.3g} mm, cross-section {1e6 * float(rod['area_m2']):.3g} mm²"
        )
    description = str(config.get("description") or "").strip()
    return f"{description}; {words}" if description else words[0].upper() + words[1:]


def make_fig2(runs: Sequence[str | Path], *, pdf: str | Path, png: str | Path, provenance: str | Path) -> None:
    """Fig. 2: contact force against time for one case, every method stored."""
    from rodimpact.present.figures import plot_contact_force

    records = [read_run(p) for p in runs]
    case = _one_case(records, "Fig. 2")
    fig = plot_contact_force(records, title=f"Contact force, case {case!r} (Fig. 2 of the paper)")
    _save_figure(fig, records, pdf=pdf, png=png, provenance=provenance, title="Fig. 2: contact force against time")


def make_fig4(
    runs: Sequence[str | Path], fraction: float, *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """Fig. 4: displacement of the cross-section at ``fraction`` of the rod length, every
    stored run of one case that recorded stations."""
    from rodimpact.present.figures import plot_station_displacement

    records = [read_run(p) for p in runs]
    records = [r for r in records if "station_displacement" in r.series]
    case = _one_case(records, "Fig. 4 (runs with station histories)")
    fig = plot_station_displacement(
        records,
        fraction,
        title=(f"Displacement at {fraction:g} of the rod length, case {case!r} (Fig. 4 of the paper)"),
    )
    _save_figure(
        fig,
        records,
        pdf=pdf,
        png=png,
        provenance=provenance,
        title="Fig. 4: displacement of a cross-section of the rod against time",
    )


def make_fig_readings(
    runs: Sequence[str | Path],
    variants: Sequence[str],
    *,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
    sweep_runs: Sequence[str | Path] = (),
    film_variants: Sequence[str] = (),
    band_files: Sequence[str | Path] = (),
    descriptions: Mapping[str, str] | None = None,
    sensors: Mapping[str, bool] | None = None,
    sensor_band_files: Sequence[str | Path] = (),
    title: str,
) -> None:
    """Contact time against ball mass, one panel per rod, with the sweeps' curves; the readings
    with the film (``film_variants``) on the panel of their rod, with their bands (``band_files``).

    ``descriptions`` (variant -> the reading in words, the case file's ``description``) title
    the panels; the measured points are grouped by their source, and the runs with more than
    one contact ringed, both read from the runs. ``sensors`` (variant -> calibrated by the
    continuum) are the readings with the sensor as built, drawn on their rod's panel with the
    bands of ``sensor_band_files``. ``title``: the set in words (its ``compare.title``)."""
    from rodimpact.present.figures import save_figure
    from rodimpact.present.table2_figures import plot_table2_contact_time

    records, frames = _by_variant(runs, variants)
    sweeps = load_records(sweep_runs)
    readings = readings_frame(records)
    bands = film_band_frame(dict(read_band(p) for p in band_files), {r.case_id: r.config for r in records})
    sources = {r.case_id: str((r.config.get("measured") or {}).get("source", "")) for r in records}
    contacts = {(r.case_id, r.method): int(r.summary.get("n_contacts", 1)) for r in records}
    sensors = dict(sensors or {})
    sensor_bands = sensor_band_frame(
        [(v, b) for p in sensor_band_files for v, group in [read_band(p)] for b in group],
        {r.case_id: r.config for r in records},
    )
    fig = plot_table2_contact_time(
        frames,
        sweep_results_frame(sweeps),
        panels=table2_panels(readings, [*film_variants, *sensors]),
        readings=readings,
        bands=bands,
        descriptions=descriptions,
        sources=sources,
        contacts=contacts,
        sensors=sensors,
        sensor_bands=sensor_bands,
        set_title=title,
    )
    artifacts = [pdf, png]
    save_figure(
        fig,
        pdf=pdf,
        png=png,
        provenance=provenance_record([*records, *sweeps], artifacts),
        title=f"{title}: contact time against ball mass",
    )
    write_provenance_with_files(
        provenance, [*records, *sweeps], artifacts, {"band": band_files, "sensor band": sensor_band_files}
    )


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
    cases = {record["case_id"]: record["case"] for path in case_files for record in read_case_file(path)["cases"]}
    frame = film_band_frame(dict(read_band(p) for p in bands), cases)
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=film_band_views(frame),
        caption=(
            "The sensor film's prediction band per Table 2 row and film reading: the SEM's contact time at the "
            "film's nominal constants and its min and max over the box of their ranges (µs), whether the "
            "measurement lies inside, and whether the time is monotone along each range (the corners bound it)."
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


def make_fig_film_force(
    runs: Sequence[str | Path], rows: Sequence[str], *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """The contact force with and without the film, one panel per row of ``rows``."""
    from rodimpact.present.film_figures import plot_film_force

    records = [read_run(p) for p in runs]
    rod = records[0].config["rod"]
    fig = plot_film_force(
        records,
        rows,
        title=(
            f"Contact force with and without the sensor film, rod radius {1000 * rod['radius_m']:g} mm, "
            f"length {1000 * rod['length_m']:g} mm"
        ),
    )
    _save_figure(
        fig, records, pdf=pdf, png=png, provenance=provenance, title="Contact force with and without the sensor film"
    )


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


WORK_PRECISION_CAPTION = (
    "Error against run time: relative errors of each method's levels against the reference (the "
    "Richardson extrapolation of the reference method's finest two levels; ref_err_* is its own "
    "error estimate), wall time of one solve (median of the repeats) on the machine named."
)


def make_work_precision(
    runs: Sequence[str | Path],
    methods: Mapping[str, Any],
    fit_levels: int,
    *,
    arrival_window: float,
    csv: str | Path,
    orders_csv: str | Path,
    orders_md: str | Path,
    provenance: str | Path,
    orders_html: str | Path | None = None,
    per_case: Mapping[str, Any] | None = None,
) -> None:
    """The work-precision table, and the orders: expected, observed with the fit's standard
    error, the levels fitted, monotone or not, and the three-level uncertainty of a method that
    is its own reference by its finest level (config.yaml ``work_precision``)."""
    records = [read_run(p) for p in runs]
    frame = work_precision_frame(records, methods)
    orders = observed_orders(frame, methods, fit_levels, arrival_window=arrival_window, per_case=per_case)
    write_table(frame, csv=csv)
    write_table(
        orders,
        csv=orders_csv,
        md=orders_md,
        html=orders_html,
        views=orders_views(orders),
        caption=(
            f"Orders of convergence: expected (from the scheme and the solution's regularity; none "
            f"stated: a dash) and observed (log-log fit of the error against h = 1/resolution on the "
            f"finest {fit_levels} levels whose error exceeds 10x the reference's, with its standard "
            f"error); whether the errors fall at every fitted level and whether their signs change "
            f"there; whether the order is within {ORDER_TOLERANCE:g} of the expected one; and, for a "
            f"method measured against its own finest level, the grid convergence index of its finest "
            f"three levels (safety factor 1.25) or, where they oscillate, half their range."
        ),
    )
    write_provenance(provenance, records, _outputs(csv, orders_csv, orders_md, orders_html))
    log.info("work precision: %d runs, %d cases", len(records), frame["case_id"].nunique())


def make_work_precision_figure(
    runs: Sequence[str | Path],
    methods: Mapping[str, Any],
    fit_levels: int,
    *,
    arrival_window: float,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
    per_case: Mapping[str, Any] | None = None,
) -> None:
    """Error against wall time for one case: every method and quantity, the observed and
    expected orders in the legends, a slope guide of the expected order, the fitted levels filled."""
    from rodimpact.present.study_figures import plot_work_precision

    records = [read_run(p) for p in runs]
    case = _one_case(records, "a work-precision figure")
    frame = work_precision_frame(records, methods)
    orders = observed_orders(frame, methods, fit_levels, arrival_window=arrival_window, per_case=per_case)
    fig = plot_work_precision(frame, orders, case, title=case_in_words(records[0].config))
    _save_figure(fig, records, pdf=pdf, png=png, provenance=provenance, title=f"Error against run time, case {case}")


def make_stability(
    runs: Sequence[str | Path],
    references: Sequence[str | Path],
    tolerances: Mapping[str, Mapping[str, float]],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """The stress runs checked against the stated tolerances; raises when one is a violation
    (a silent wrong answer), after logging the whole table."""
    records = [read_run(p) for p in runs]
    refs = {r.case_id: r for r in (read_run(p) for p in references)}
    frame = stability_frame(records, refs, tolerances)
    bad = violations(frame)
    if bad:
        log.error("stability table:\n%s", frame.to_string())
        raise StudyViolation(
            "stability study: runs that neither met their tolerances nor failed clearly:\n  " + "\n  ".join(bad)
        )
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=stability_views(frame),
        caption=(
            "Stress cases: every method's result checked (finite, force >= 0, energy balance and first "
            "contact time within the method's stated tolerances against a sem reference at tolerance "
            "1e-8), or its failure message."
        ),
    )
    write_provenance(provenance, [*records, *refs.values()], _outputs(csv, md, html))
    log.info(
        "stability: %d runs, %d ok, %d failed clearly",
        len(frame),
        (frame["verdict"] == "ok").sum(),
        frame["verdict"].str.startswith("failed").sum(),
    )


def make_stability_map(
    runs: Sequence[str | Path],
    references: Sequence[str | Path],
    spec: Mapping[str, Any],
    *,
    csv: str | Path,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
) -> None:
    """The stability map: the table of its points and the figure."""
    from rodimpact.present.figures import save_figure
    from rodimpact.present.study_figures import plot_stability_map

    records = [read_run(p) for p in runs]
    refs = {r.config["row"]: r for r in (read_run(p) for p in references)}
    frame = map_frame(records, refs, float(spec["accuracy"]))
    write_table(frame, csv=csv)
    fig = plot_stability_map(frame, int(spec["steps_per_contact"]), float(spec["accuracy"]))
    prov = provenance_record([*records, *refs.values()], [csv, pdf, png])
    save_figure(fig, pdf=pdf, png=png, provenance=prov, title="Stability map of the SEM schemes")
    write_provenance(provenance, [*records, *refs.values()], [csv, pdf, png])


def make_fig_force_fit(
    runs: Sequence[str | Path], jsons: Sequence[str | Path], *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """The exported closed forms (``jsons``, one per run) over the computed forces of one case,
    and their errors."""
    from rodimpact.present.figures import plot_force_fits
    from rodimpact.present.forces import read_force_json

    records = [read_run(p) for p in runs]
    case = _one_case(records, "the force's closed form")
    fig = plot_force_fits(
        records,
        [read_force_json(p) for p in jsons],
        title=f"Contact force and its Chebyshev closed form, case {case!r}",
    )
    _save_figure(
        fig, records, pdf=pdf, png=png, provenance=provenance, title="Contact force and its Chebyshev closed form"
    )
