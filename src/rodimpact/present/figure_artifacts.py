"""The workflow's figures drawn from stored runs (and the band files and force fits beside
them): Fig. 2, Fig. 4, contact time against ball mass per reading, the contact force with and
without the film, the force's closed form; each with its provenance in the files and a sidecar;
and the paper's model case as its job writes it (:func:`make_paper_model`: Fig. 2, its numbers,
Fig. 4 and the closed form).

The figure modules (matplotlib) are imported by the functions that draw, so that importing this
module does not load them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from rodimpact.present.fig2_table import make_comparison
from rodimpact.present.film_tables import film_band_frame
from rodimpact.present.inputs import load_records, one_case
from rodimpact.present.readings import by_variant, readings_frame, table2_panels
from rodimpact.present.sensor_tables import sensor_band_frame
from rodimpact.present.sweep_table import sweep_results_frame
from rodimpact.present.table import write_artifact
from rodimpact.storage.bands import read_band
from rodimpact.storage.runs import read_run
from rodimpact.storage.sidecar import provenance_record, write_provenance

__all__ = [
    "make_fig2",
    "make_fig4",
    "make_fig_film_force",
    "make_fig_force_fit",
    "make_fig_readings",
    "make_paper_model",
]


def make_fig2(runs: Sequence[str | Path], *, pdf: str | Path, png: str | Path, provenance: str | Path) -> None:
    """Fig. 2: contact force against time for one case, every method stored."""
    from rodimpact.present.figures import plot_contact_force, save_figure_of_runs

    records = [read_run(p) for p in runs]
    case = one_case(records, "Fig. 2")
    fig = plot_contact_force(records, title=f"Contact force, case {case!r} (Fig. 2 of the paper)")
    save_figure_of_runs(
        fig, records, pdf=pdf, png=png, provenance=provenance, title="Fig. 2: contact force against time"
    )


def make_fig4(
    runs: Sequence[str | Path], fraction: float, *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """Fig. 4: displacement of the cross-section at ``fraction`` of the rod length, every
    stored run of one case that recorded stations."""
    from rodimpact.present.figures import plot_station_displacement, save_figure_of_runs

    records = [read_run(p) for p in runs]
    records = [r for r in records if "station_displacement" in r.series]
    case = one_case(records, "Fig. 4 (runs with station histories)")
    fig = plot_station_displacement(
        records,
        fraction,
        title=(f"Displacement at {fraction:g} of the rod length, case {case!r} (Fig. 4 of the paper)"),
    )
    save_figure_of_runs(
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
    companion_pdf: str | Path,
    companion_png: str | Path,
    companion_provenance: str | Path,
    sweep_runs: Sequence[str | Path] = (),
    film_variants: Sequence[str] = (),
    band_files: Sequence[str | Path] = (),
    descriptions: Mapping[str, str] | None = None,
    sensors: Mapping[str, bool] | None = None,
    sensor_band_files: Sequence[str | Path] = (),
    title: str,
) -> None:
    """Contact time against ball mass: the headline figure and its companion, one story each.

    The headline (``pdf``, ``png``) is the rod the sensor was built on: one panel per rod with
    a reading of the sensor as built (``sensors``), with the measurements, the sensor as built
    (the continuum's points, the calibrated SEM's line and rows, the band over the sourced
    ranges) and the models without the sensor; no approximation, and no published result. Where
    the set has no such reading, every rod without its approximations. The companion
    (``companion_pdf``, ``companion_png``) is every rod, one panel each, with the sweeps' curves,
    the published results, and every approximation: the readings with the thin-layer film
    (``film_variants``) on the panel of their rod, with their bands (``band_files``). The
    headline's rod is the one whose sensor as built has its band (``sensor_band_files``), else
    every rod with one.

    ``descriptions`` (variant -> the reading in words, the case file's ``description``) title
    the panels; the measured points are grouped by their source, and the runs with more than
    one contact ringed, both read from the runs. ``sensors`` (variant -> calibrated by the
    continuum) are the readings with the sensor as built, drawn on their rod's panel with the
    bands of ``sensor_band_files``. ``title``: the set in words (its ``compare.title``)."""
    from rodimpact.present.figures import save_figure
    from rodimpact.present.table2_figures import plot_table2_contact_time

    records, frames = by_variant(runs, variants)
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
    results = sweep_results_frame(sweeps)
    common = dict(
        readings=readings,
        bands=bands,
        descriptions=descriptions,
        sources=sources,
        contacts=contacts,
        sensors=sensors,
        sensor_bands=sensor_bands,
        set_title=title,
    )
    # the headline's rod: the one whose sensor as built has its band (else any with the sensor)
    with_sensor = {
        rod: [v for v in drawn if v in sensors] for rod, drawn in table2_panels(readings, list(sensors)).items()
    }
    banded = set() if sensor_bands.empty else set(sensor_bands["variant"])
    headline = (
        {rod: drawn for rod, drawn in with_sensor.items() if banded & set(drawn)}
        or {rod: drawn for rod, drawn in with_sensor.items() if drawn}
        or {rod: [] for rod in with_sensor}
    )
    # the companion: every rod, with the approximations (the sensor as built on another rod is in
    # the set's comparison figure, compare_{set})
    companion = table2_panels(readings, film_variants)
    figures = (
        (
            plot_table2_contact_time(frames, results, panels=headline, published=False, **common),
            pdf,
            png,
            provenance,
            f"{title}: contact time against ball mass, the sensor as built",
        ),
        (
            plot_table2_contact_time(frames, results, panels=companion, **common),
            companion_pdf,
            companion_png,
            companion_provenance,
            f"{title}: contact time against ball mass, every reading and approximation",
        ),
    )
    for fig, fig_pdf, fig_png, fig_provenance, fig_title in figures:
        artifacts = [fig_pdf, fig_png]
        save_figure(
            fig, pdf=fig_pdf, png=fig_png, provenance=provenance_record([*records, *sweeps], artifacts), title=fig_title
        )
        write_provenance(
            fig_provenance, [*records, *sweeps], artifacts, {"band": band_files, "sensor band": sensor_band_files}
        )


def make_fig_film_force(
    runs: Sequence[str | Path], rows: Sequence[str], *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """The contact force with and without the film, one panel per row of ``rows``."""
    from rodimpact.present.figures import save_figure_of_runs
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
    save_figure_of_runs(
        fig, records, pdf=pdf, png=png, provenance=provenance, title="Contact force with and without the sensor film"
    )


def make_fig_force_fit(
    runs: Sequence[str | Path], jsons: Sequence[str | Path], *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """The exported closed forms (``jsons``, one per run) over the computed forces of one case,
    and their errors."""
    from rodimpact.present.figures import plot_force_fits, save_figure_of_runs
    from rodimpact.present.forces import read_force_json

    records = [read_run(p) for p in runs]
    case = one_case(records, "the force's closed form")
    fig = plot_force_fits(
        records,
        [read_force_json(p) for p in jsons],
        title=f"Contact force and its Chebyshev closed form, case {case!r}",
    )
    save_figure_of_runs(
        fig, records, pdf=pdf, png=png, provenance=provenance, title="Contact force and its Chebyshev closed form"
    )


def make_paper_model(
    runs: Sequence[str | Path],
    fraction: float,
    jsons: Sequence[str | Path],
    *,
    fig2_pdf: str | Path,
    fig2_png: str | Path,
    fig2_provenance: str | Path,
    csv: str | Path,
    md: str | Path,
    html: str | Path,
    table_provenance: str | Path,
    fig4_pdf: str | Path,
    fig4_png: str | Path,
    fig4_provenance: str | Path,
    force_fit_pdf: str | Path,
    force_fit_png: str | Path,
    force_fit_provenance: str | Path,
) -> None:
    """The paper's model case as its job writes it, from one read of its runs' files: Fig. 2
    (:func:`make_fig2`), its numbers (:func:`~rodimpact.present.fig2_table.make_comparison`), Fig. 4
    at ``fraction`` of the rod (:func:`make_fig4`) and the force's closed form over the force
    (:func:`make_fig_force_fit`, the exported ``jsons``)."""
    make_fig2(runs, pdf=fig2_pdf, png=fig2_png, provenance=fig2_provenance)
    write_artifact(make_comparison(runs), csv=csv, md=md, html=html, provenance=table_provenance)
    make_fig4(runs, fraction, pdf=fig4_pdf, png=fig4_png, provenance=fig4_provenance)
    make_fig_force_fit(runs, jsons, pdf=force_fit_pdf, png=force_fit_png, provenance=force_fit_provenance)
