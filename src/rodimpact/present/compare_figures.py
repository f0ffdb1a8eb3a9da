"""The figures of a case set against its measurements: one for the set, one per kind of measured
record (a row per case); each drawn from the set's stored runs and measured files only, and saved
with its provenance."""

from __future__ import annotations

import logging
import math
import textwrap
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")  # headless: the workflow's figures never open a window

import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from numpy.typing import NDArray  # noqa: E402

from rodimpact.analysis.history_compare import DEFAULT_THRESHOLD, HistoryComparison  # noqa: E402
from rodimpact.analysis.measured import MeasuredHistory  # noqa: E402
from rodimpact.analysis.observations import NORMS, gauge_column, signal_comparison  # noqa: E402
from rodimpact.analysis.wave_compare import SignalComparison  # noqa: E402
from rodimpact.present.compare import (  # noqa: E402
    compare_table,
    comparison_markdown,
    history_comparison,
    history_files,
    read_histories,
    summary_table,
    x_axis,
)
from rodimpact.present.figures import save_figure  # noqa: E402
from rodimpact.present.table import write_csv, write_table  # noqa: E402
from rodimpact.present.table2_figures import short_source  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402
from rodimpact.storage.atomic import atomic_output  # noqa: E402
from rodimpact.storage.runs import RunRecord, read_run  # noqa: E402
from rodimpact.storage.sidecar import provenance_record, write_provenance  # noqa: E402

__all__ = [
    "SIGNAL_FIGURES",
    "make_compare",
    "make_signal_figure",
    "plot_compare_set",
    "plot_signal_overlays",
]

#: The measured scalars drawn, in this order, each in its row of panels.
_DRAWN = (
    "contact_time_us",
    "signal_contact_time_us",
    "peak_force_n",
    "rebound_velocity_m_s",
    "restitution",
    "strain_peak_microstrain",
    "strain_integral_microstrain_us",
    "far_end_peak_velocity_m_s",
)
#: The error norms drawn (of a record that gives no value to draw), after the values.
_DRAWN_NORMS = ("impactor_velocity_l2_pct", "impactor_velocity_max_pct")
log = logging.getLogger(__name__)

_MARKERS = ("s", "D", "P", "X", "h")
#: The markers of a method's lines, one per contact law met in the set.
_LAW_MARKERS = ("o", "^", "v", "D", "s")
#: The most panels side by side; more variants wrap to further rows.
_MAX_COLUMNS = 4


def _method_style(method: str) -> dict:
    spec = METHODS.get(method)
    return {"color": spec.color, "ls": spec.style} if spec is not None else {"color": "0.3", "ls": "-"}


def plot_compare_set(
    frame: pd.DataFrame,
    title: str,
    x: str = "mass_g",
    x_label: str = "impactor mass $m$ (g)",
    descriptions: Mapping[str, str] | None = None,
) -> matplotlib.figure.Figure:
    """Measured and computed values against ``x``, a panel per measured quantity (rows) and
    variant (columns); measured points marked by their source, each method a line. The
    impactor's velocity, which gives error norms alone (no value to set against ``x``), adds
    each method's norms of it, in %.

    Parameters
    ----------
    frame : DataFrame
        :func:`rodimpact.present.compare.compare_frame`.
    title : str
        The set in words.
    x : str
        The frame's column along the set (default the impactor's mass, g).
    descriptions : mapping, optional
        Variant -> its description (panel titles).
    """
    descriptions = dict(descriptions or {})
    present = set(frame["quantity"])
    quantities = [q for q in (*_DRAWN, *_DRAWN_NORMS) if q in present]
    if not quantities:
        raise ValueError(f"frame: no quantity to draw; its quantities: {sorted(present)}")
    variants = list(dict.fromkeys(frame["variant"].fillna("")))
    cols = min(len(variants), _MAX_COLUMNS)
    per_quantity = math.ceil(len(variants) / cols)  # rows of panels each quantity takes
    fig, axes = plt.subplots(
        len(quantities) * per_quantity,
        cols,
        figsize=(4.6 * cols, 3.2 * len(quantities) * per_quantity + 1.4),
        squeeze=False,
        layout="constrained",
    )
    for ax in axes.flat[len(quantities) * len(variants) :]:
        ax.set_visible(False)
    sources = list(dict.fromkeys(frame["source"]))
    laws = list(dict.fromkeys(frame["contact_law"]))  # a method's models differ by their marker
    values = frame[x].to_numpy(float)
    logarithmic = values.min() > 0 and values.max() > 3.0 * values.min()  # over a decade or so
    for i, quantity in enumerate(quantities):
        for j, variant in enumerate(variants):
            ax = axes[i * per_quantity + j // cols, j % cols]
            rows = frame[(frame["quantity"] == quantity) & (frame["variant"].fillna("") == variant)]
            norm = quantity in NORMS  # a norm is an error already: no measured point, the error drawn
            measured = rows.drop_duplicates("case_id").sort_values(x).iloc[: 0 if norm else None]
            for source, points in measured.groupby("source", sort=False):
                ax.plot(
                    points[x],
                    points["measured"],
                    _MARKERS[sources.index(source) % len(_MARKERS)],
                    color="k",
                    ms=6,
                    ls="none",
                    zorder=5,
                    label=f"measured ({short_source(source)})" if source else "measured",
                )
            for (method, _, law), computed in rows.groupby(["method", "method_label", "contact_law"], sort=False):
                computed = computed.sort_values(x)
                takes_law = method in METHODS and METHODS[method].contact == "law"  # a continuum resolves the bodies
                marker = _LAW_MARKERS[laws.index(law) % len(_LAW_MARKERS)] if takes_law else "o"
                ax.plot(
                    computed[x],
                    computed["error_pct" if norm else "computed"],
                    marker=marker,
                    ms=4,
                    lw=1.2,
                    label=computed["method_label"].iloc[0],
                    **_method_style(method),
                )
            words, unit = rows["quantity_words"].iloc[0], rows["unit"].iloc[0]
            ax.set_ylabel(textwrap.fill(f"{words} ({unit})", 42))
            ax.set_xlabel(x_label)
            ax.grid(alpha=0.3)
            if logarithmic:
                ax.set_xscale("log")
                ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
                ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda value, _: f"{value:g}"))
                ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            if variant:
                ax.set_title(textwrap.fill(descriptions.get(variant, variant), 55), fontsize=8.5)
    handles: dict[str, object] = {}
    for ax in axes.flat:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    fig.legend(
        list(handles.values()),
        [textwrap.fill(label, 70) for label in handles],
        loc="outside lower center",
        ncol=min(2, cols),
        fontsize=8,
        frameon=False,
    )
    fig.suptitle(textwrap.fill(title, 90), fontsize=10)
    return fig


def plot_signal_overlays(
    panels: Sequence[tuple[Sequence[tuple[Any, HistoryComparison | SignalComparison]], Mapping[str, Any], str, str]],
    ylabel: str,
    scale: float,
    title: str,
) -> matplotlib.figure.Figure:
    """A set's measured force, strain or velocity records, one row per case: the record and
    each method's signal (left), and their difference, computed minus measured (right), against
    the time since the impact.

    Parameters
    ----------
    panels : sequence of (comparisons, spec, description, note)
        Per case: each run (its ``method``, ``series`` and ``summary``) with its comparison (a
        force's :class:`HistoryComparison`, a strain's or velocity's :class:`SignalComparison`),
        the record's block (``station_m`` and ``gauge_length_m`` of a gauge; ``of`` of a
        velocity), the case in words and how the record was made.
    ylabel : str
        The signal in words, with its unit.
    scale : float
        Multiplies the signal into the unit of ``ylabel``.
    title : str
        The figure's title.
    """
    rows = max(len(panels), 1)
    fig, axes = plt.subplots(
        rows, 2, figsize=(10.0, 0.6 + 2.9 * rows), width_ratios=(3, 2), squeeze=False, layout="constrained"
    )
    unit = ylabel.rsplit("(", 1)[-1].rstrip(")") if ylabel.endswith(")") else ""
    for (signal, difference), (comparisons, spec, description, note) in zip(axes, panels, strict=False):
        _signal_row(signal, difference, comparisons, spec, scale)
        if "station_m" in spec:
            where = f"gauge at {1e3 * float(spec['station_m']):.4g} mm"
            if float(spec.get("gauge_length_m", 0.0)) > 0:
                where += f", {1e3 * float(spec['gauge_length_m']):.3g} mm long"
            description = f"{description} ({where})"
        # the note's opening only, before any parenthesis: how the record was made, not the
        # command that made it
        text = description + (f" — {textwrap.shorten(note.split(' (', 1)[0], 90)}" if note else "")
        signal.set_title(textwrap.fill(text, 95), fontsize=8, loc="left")
        signal.set_ylabel(ylabel, fontsize=8.5)
        difference.set_ylabel(f"computed − measured ({unit})" if unit else "computed − measured", fontsize=8.5)
    for ax in axes.flat:  # every row has its own time range: each axis its own label
        ax.set_xlabel("time since the impact (µs)", fontsize=8.5)
    if not panels:
        axes[0, 0].text(0.5, 0.5, "no record to compare", transform=axes[0, 0].transAxes, ha="center")
    handles: dict[str, object] = {}
    for ax in axes[:, 0]:
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, handle)
    fig.legend(list(handles.values()), list(handles), loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    fig.suptitle(textwrap.fill(title, 100), fontsize=10)
    return fig


def _signal_row(signal, difference, comparisons, spec: Mapping[str, Any], scale: float) -> None:
    """One case's record and each method's signal (``signal``), and their difference."""
    for index, (run, result) in enumerate(comparisons):
        t_us = 1e6 * result.time_s
        measured, model, aligned = _traces(result)
        if index == 0:
            signal.plot(t_us, scale * measured, color="k", lw=1.0, label=f"measured ({aligned})")
        style = _method_style(run.method)
        label = METHODS[run.method].label if run.method in METHODS else run.method
        signal.plot(t_us, scale * model, lw=1.3, label=label, **style)
        difference.plot(
            t_us,
            scale * (model - measured),
            lw=0.9,
            label=f"{label}: L2 error {100 * result.l2_error:.1f} %",
            **style,
        )
        if "gauge_mean_strain" in run.series and "station_m" in spec:
            column = gauge_column(run.summary, float(spec["station_m"]), float(spec.get("gauge_length_m", 0.0)))
            mean = np.asarray(run.series["gauge_mean_strain"]).reshape(len(run.series["time"]), -1)[:, column]
            signal.plot(
                t_us,
                scale * np.interp(result.time_s, run.series["time"], mean),
                lw=1.0,
                color=style["color"],
                ls=":",
                label=f"{label}: the section's mean strain (the surface's drawn solid)",
            )
    difference.axhline(0.0, color="0.5", lw=0.8)
    difference.legend(fontsize=7, loc="best")
    for ax in (signal, difference):
        ax.grid(alpha=0.3)


def _traces(
    result: HistoryComparison | SignalComparison,
) -> tuple[NDArray[np.float64], NDArray[np.float64], str]:
    """A comparison's record and computed signal at its time points, and how the record was
    aligned, in words: a force at its threshold of each peak (as the comparison table aligns
    it), a wave signal on its first pulse's arrival, an impactor's velocity not at all."""
    if isinstance(result, HistoryComparison):
        return result.measured_N, result.model_N, f"aligned at {result.threshold:g} of its peak"
    aligned = "aligned on the first arrival" if result.measured_pulse is not None else "on its own clock"
    return result.measured, result.model, aligned


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
    order = {name: k for k, name in enumerate(METHODS)}
    records = sorted(
        (read_run(p) for p in runs), key=lambda r: (r.config["impactor"]["mass_kg"], order.get(r.method, 99))
    )
    histories = read_histories(records)
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
    write_provenance(provenance, records, [pdf, png], {"measured records": history_files(records)})


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


def make_compare(
    runs: Sequence[str | Path],
    set_name: str,
    title: str,
    *,
    csv: str | Path,
    summary: str | Path,
    md: str | Path,
    html: str | Path,
    tex: str | Path,
    provenance: str | Path,
    pdf: str | Path,
    png: str | Path,
    figure_provenance: str | Path,
    descriptions: Mapping[str, str] | None = None,
    x: str | None = None,
) -> None:
    """A set against its measurements, from one read of its runs and records: the table
    (:func:`~rodimpact.present.compare.compare_table`; ``csv``, ``html``, ``tex``) and its summary per
    method and quantity (``summary``; both in ``md``), and the figure of the measured and computed
    values (:func:`plot_compare_set`) against ``x`` (the set's ``compare.x``) or what varies along
    the set (:func:`~rodimpact.present.compare.x_axis`); each with its sidecar."""
    records = [read_run(p) for p in runs]
    table = compare_table(records, read_histories(records), set_name)
    totals = summary_table(table.frame)
    write_table(table, csv=csv, html=html, tex=tex)
    write_csv(totals.frame, summary)
    with atomic_output(md) as tmp:
        tmp.write_text(comparison_markdown(table, totals), encoding="utf-8")
    files = {"measured records": history_files(records)}
    write_provenance(provenance, records, [csv, summary, md, html, tex], files)
    column, x_label = x_axis(table.frame, x or None)
    save_figure(
        plot_compare_set(table.frame, title, x=column, x_label=x_label, descriptions=descriptions or None),
        pdf=pdf,
        png=png,
        provenance=provenance_record(records, [pdf, png]),
        title=f"Set {set_name} against its measurements",
    )
    write_provenance(figure_provenance, records, [pdf, png], files)
    log.info("set %s: %d comparisons of %d runs", set_name, len(table.frame), len(records))
