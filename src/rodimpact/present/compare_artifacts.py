"""A case set's comparison with its measurements, written: its table, its figure, and a
figure per kind of measured record, force, strain at a gauge or velocity, a row per case
(:mod:`.compare`, :mod:`.compare_figures`), from the set's stored runs and measured files only."""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rodimpact.analysis.history_compare import DEFAULT_THRESHOLD, HistoryComparison
from rodimpact.analysis.measured import RECORDS, MeasuredHistory, read_history
from rodimpact.analysis.observations import signal_comparison
from rodimpact.analysis.wave_compare import SignalComparison
from rodimpact.present.compare import compare_frame, compare_summary, history_comparison, x_axis
from rodimpact.present.film_tables import write_provenance_with_files
from rodimpact.present.table_formats import markdown_table, panels
from rodimpact.present.tables import write_table
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.runs import RunRecord, read_run

__all__ = ["SIGNAL_FIGURES", "make_compare_figure", "make_compare_table", "make_signal_figure"]

log = logging.getLogger(__name__)

_CAPTION = (
    "Measured against computed, per case, method and quantity: the measured value and its source, the "
    "computed value, and the error (computed − measured) / |measured| in %. A measured force history adds "
    "the contact time read from both signals at the history's threshold, and the L2 and max-norm errors "
    "of the computed force after the two are aligned where each first rises through that fraction of its "
    "peak. A strain at a gauge, or the far end's velocity, adds its first pulse's arrival (against x/c), "
    "peak and time integral, and the errors after the arrivals are aligned "
    '(config/README.md, "Comparing with your experiment").'
)


def _histories(records) -> dict[str, dict[str, MeasuredHistory]]:
    """Case id -> its records, read, by their key in the ``measured`` block."""
    out: dict[str, dict[str, MeasuredHistory]] = {}
    for record in records:
        measured = record.config.get("measured") or {}
        if record.case_id in out:
            continue
        found = {key: read_history(measured[key]["path"], measured[key], key) for key in RECORDS if measured.get(key)}
        if found:
            out[record.case_id] = found
    return out


def _history_files(records) -> list[str]:
    return sorted(
        {spec["path"] for r in records for key in RECORDS if (spec := (r.config.get("measured") or {}).get(key))}
    )


def make_compare_table(
    runs: Sequence[str | Path],
    set_name: str,
    *,
    csv: str | Path,
    summary: str | Path,
    md: str | Path,
    html: str | Path,
    tex: str | Path,
    provenance: str | Path,
) -> None:
    """The set's comparison table (:func:`~rodimpact.present.compare.compare_frame`) and its
    summary per method and quantity (:func:`~rodimpact.present.compare.compare_summary`)."""
    records = [read_run(p) for p in runs]
    frame = compare_frame(records, _histories(records))
    totals = compare_summary(frame)
    views = panels(
        frame,
        f"Set {set_name} against its measurements",
        ["row", "quantity_words", "unit"],
        # a warning column only where a measurement is flagged (compare.rigid_wall_warnings)
        ["method_label", "measured", "computed", "error_pct", *(["warning"] if frame["warning"].notna().any() else [])],
        by="variant" if frame["variant"].notna().any() else "",
    )
    write_table(frame, csv=csv, html=html, tex=tex, views=views)
    with atomic_output(summary) as tmp:
        totals.to_csv(tmp, index=False, float_format="%.10g")
    with atomic_output(md) as tmp:
        tmp.write_text(
            f"{_CAPTION}\n\n{markdown_table(frame)}\n\nPer method and quantity: the cases compared, the "
            f"mean and the largest |error|, and the mean signed error (%).\n\n"
            f"{markdown_table(totals)}\n",
            encoding="utf-8",
        )
    write_provenance_with_files(
        provenance, records, [csv, summary, md, html, tex], {"measured records": _history_files(records)}
    )
    log.info("set %s: %d comparisons of %d runs", set_name, len(frame), len(records))


def make_compare_figure(
    runs: Sequence[str | Path],
    set_name: str,
    title: str,
    *,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
    descriptions: Mapping[str, str] | None = None,
    x: str | None = None,
) -> None:
    """The set's figure (:func:`~rodimpact.present.compare_figures.plot_compare_set`), against
    ``x`` (the set's ``compare.x``) or what varies along the set
    (:func:`~rodimpact.present.compare.x_axis`)."""
    from rodimpact.present.compare_figures import plot_compare_set
    from rodimpact.present.figures import save_figure
    from rodimpact.storage.sidecar import provenance_record

    records = [read_run(p) for p in runs]
    frame = compare_frame(records, _histories(records))
    column, x_label = x_axis(frame, x)
    save_figure(
        plot_compare_set(frame, title, x=column, x_label=x_label, descriptions=descriptions),
        pdf=pdf,
        png=png,
        provenance=provenance_record(records, [pdf, png]),
        title=f"Set {set_name} against its measurements",
    )
    write_provenance_with_files(provenance, records, [pdf, png], {"measured records": _history_files(records)})


#: A record's figure: its key -> (the signal in words, the y label, the scale to its unit).
SIGNAL_FIGURES = {
    "force_history": ("force", "contact force $P$ (N)", 1.0),
    "strain_history": ("strain", "axial strain at the gauge (µstrain)", 1e6),
    "velocity_history": ("velocity", "velocity (m/s)", 1.0),
}


def make_signal_figure(
    runs: Sequence[str | Path],
    key: str,
    title: str,
    *,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
) -> None:
    """A set's measured force, strain or velocity records against each method's signals, one
    row per case (``key``: a key of :data:`SIGNAL_FIGURES`; every run of ``runs`` is of a case
    with such a record; :func:`~rodimpact.present.compare_figures.plot_signal_overlays`).

    Raises
    ------
    ValueError
        A run's case has no such record.
    """
    from rodimpact.present.compare_figures import plot_signal_overlays
    from rodimpact.present.figures import save_figure
    from rodimpact.storage.sidecar import provenance_record

    order = {name: k for k, name in enumerate(METHODS)}
    records = sorted(
        (read_run(p) for p in runs), key=lambda r: (r.config["impactor"]["mass_kg"], order.get(r.method, 99))
    )
    histories = _histories(records)
    panels = []
    for case_id in dict.fromkeys(r.case_id for r in records):  # a row per case, lightest first
        if key not in histories.get(case_id, {}):
            raise ValueError(f"runs: case {case_id!r} has no measured {key}")
        runs_of_case = [r for r in records if r.case_id == case_id]
        spec, history = runs_of_case[0].config["measured"][key], histories[case_id][key]
        comparisons = [(r, _record_comparison(key, spec, r, history)) for r in runs_of_case]
        description = str(runs_of_case[0].config.get("description") or case_id)
        panels.append((comparisons, spec, description, history.note))
    words, ylabel, scale = SIGNAL_FIGURES[key]
    if key == "velocity_history":
        whose = {p[1]["of"] for p in panels}
        ylabel = (f"the {'impactor' if whose == {'impactor'} else 'far end'}'s " if len(whose) == 1 else "") + ylabel
    save_figure(
        plot_signal_overlays(panels, ylabel, scale, title),
        pdf=pdf,
        png=png,
        provenance=provenance_record(records, [pdf, png]),
        title=title,
    )
    write_provenance_with_files(provenance, records, [pdf, png], {"measured records": _history_files(records)})


def _record_comparison(
    key: str, spec: Mapping[str, Any], record: RunRecord, history: MeasuredHistory
) -> HistoryComparison | SignalComparison:
    """A run's signal against the record ``key`` names: a force aligned at ``threshold`` of each
    peak, as the comparison table aligns it (:func:`~rodimpact.present.compare.history_comparison`);
    a strain or velocity on its first pulse (:func:`~rodimpact.analysis.observations.signal_comparison`).
    """
    if key == "force_history":
        return history_comparison(record, history, float(spec.get("threshold", DEFAULT_THRESHOLD)))
    return signal_comparison(key, spec, record.series, record.summary, history)
