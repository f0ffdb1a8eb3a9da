"""Figures built from stored runs only; headless (Agg), provenance in the file metadata."""

from __future__ import annotations

import json
import logging
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rodimpact.solvers.registry import METHODS  # noqa: E402
from rodimpact.storage.atomic import atomic_output  # noqa: E402
from rodimpact.storage.runs import RunRecord  # noqa: E402
from rodimpact.storage.sidecar import provenance_record, write_provenance  # noqa: E402

__all__ = [
    "METHOD_LABELS",
    "METHOD_ORDER",
    "plot_contact_force",
    "plot_force_fits",
    "plot_station_displacement",
    "save_figure",
    "save_figure_of_runs",
]

log = logging.getLogger(__name__)

#: Method -> its name in words (the registry's labels).
METHOD_LABELS = {name: spec.label for name, spec in METHODS.items()}
_STYLE = {name: spec.style for name, spec in METHODS.items()}
METHOD_ORDER = tuple(METHODS)
#: Open markers that tell apart curves lying on each other, in the methods' order.
_MARKERS = ("s", "^", "D", "v", "o", "x")


def save_figure(
    fig: matplotlib.figure.Figure, *, pdf: str | Path, png: str | Path, provenance: Mapping[str, Any], title: str
) -> None:
    """Save ``fig`` as PDF and PNG atomically, with ``provenance`` (JSON) in the metadata.

    PNG: text chunks ``Title``, ``Description`` (the provenance JSON), ``Software``.
    PDF: info entries ``Title``, ``Subject`` (the provenance JSON), ``Creator``.
    """
    text = json.dumps(provenance, sort_keys=True)
    software = f"rodimpact {provenance.get('code_version', '')}".strip()
    with atomic_output(png) as tmp:
        fig.savefig(tmp, format="png", dpi=150, metadata={"Title": title, "Description": text, "Software": software})
    # the layout the PNG was drawn with, kept for the PDF: a layout engine would lay the same
    # figure out once more (half the time of a figure with many axes)
    if fig.get_layout_engine() is not None:
        fig.set_layout_engine("none")
    with atomic_output(pdf) as tmp:
        fig.savefig(tmp, format="pdf", metadata={"Title": title, "Subject": text, "Creator": software})
    plt.close(fig)


def save_figure_of_runs(
    fig: matplotlib.figure.Figure,
    records: Sequence[RunRecord],
    *,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
    title: str,
) -> None:
    """Save a figure made from ``records`` (:func:`save_figure`, their provenance in its metadata)
    and its provenance sidecar ``provenance``."""
    save_figure(fig, pdf=pdf, png=png, provenance=provenance_record(records, [pdf, png]), title=title)
    write_provenance(provenance, records, [pdf, png])


def _finish(fig: matplotlib.figure.Figure, ax: matplotlib.axes.Axes, title: str) -> matplotlib.figure.Figure:
    """Grid, a legend below the axes (each label once), and the title: the look every time plot shares."""
    ax.grid(alpha=0.3)
    first: dict[str, Any] = {}
    for handle, label in zip(*ax.get_legend_handles_labels()):
        first.setdefault(label, handle)
    ax.legend(
        list(first.values()),
        list(first),
        fontsize=8,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.14),
        ncol=1,
        frameon=False,
    )
    if title:
        ax.set_title(title, fontsize=10)
    return fig


def _ordered(records: Sequence[RunRecord]) -> list[RunRecord]:
    rank = {m: i for i, m in enumerate(METHOD_ORDER)}
    return sorted(records, key=lambda r: rank.get(r.method, len(rank)))


def _method_curve(
    ax: matplotlib.axes.Axes, method: str, index: int, count: int, x: np.ndarray, y: np.ndarray, label: str
) -> None:
    """One method's curve in its colour and line style; curves that lie on each other are told
    apart by their own open markers, placed at staggered points so that each stays visible."""
    step = max(1, len(x) // 40)
    ax.plot(
        x,
        y,
        _STYLE.get(method, "-"),
        lw=1.4,
        color=METHODS[method].color if method in METHODS else None,
        marker=_MARKERS[index % len(_MARKERS)],
        markevery=(index * step // max(1, count), step),
        ms=4,
        mfc="none",
        label=label,
    )


def plot_contact_force(records: Sequence[RunRecord], title: str = "") -> matplotlib.figure.Figure:
    """Fig. 2: contact force against time, one curve per method (first contact marked).

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of one case with the ``contact_force`` series.
    """
    fig, ax = plt.subplots(figsize=(7.0, 5.0), layout="constrained")
    last_end = 0.0
    ordered = _ordered(records)
    for index, rec in enumerate(ordered):
        _method_curve(
            ax,
            rec.method,
            index,
            len(ordered),
            1e6 * rec.series["time"],
            1e-3 * rec.series["contact_force"],
            f"{METHOD_LABELS.get(rec.method, rec.method)}: contact {1e6 * rec.summary['contact_time_s']:.1f} µs",
        )
        last_end = max(last_end, float(np.atleast_1d(rec.summary["contact_end_s"])[-1]))
        peaks_t = 1e6 * np.asarray(rec.summary["peak_time_s"])
        ax.plot(
            peaks_t,
            1e-3 * np.asarray(rec.summary["peak_force_N"]),
            "o",
            ms=4.5,
            color=ax.lines[-1].get_color(),
            label="_nolegend_",
        )
    ax.plot([], [], "o", color="0.3", ms=4.5, label="force maxima (filled dots)")
    ax.set_xlabel("time $t$ (µs)")
    ax.set_ylabel("contact force $P$ (kN)")
    ax.set_xlim(0, 1.05e6 * last_end)
    ax.set_ylim(bottom=0)
    return _finish(fig, ax, title)


def plot_station_displacement(
    records: Sequence[RunRecord], fraction: float, title: str = ""
) -> matplotlib.figure.Figure:
    """Fig. 4: axial displacement of the cross-section at ``fraction`` of the rod length.

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of one case with ``station_displacement`` and the summary's ``station_x_m``;
        each contributes the station closest to ``fraction`` of its rod's length.
    fraction : float
        Station position as a fraction of the rod length from the struck end.
    """
    fig, ax = plt.subplots(figsize=(7.0, 5.0), layout="constrained")
    ordered = _ordered(records)
    for index, rec in enumerate(ordered):
        xs = np.atleast_1d(rec.summary["station_x_m"])
        length = rec.config["rod"]["length_m"]
        column = int(np.argmin(np.abs(xs / length - fraction)))
        history = np.asarray(rec.series["station_displacement"]).reshape(len(rec.series["time"]), -1)
        _method_curve(
            ax,
            rec.method,
            index,
            len(ordered),
            1e6 * rec.series["time"],
            1e6 * history[:, column],
            f"{METHOD_LABELS.get(rec.method, rec.method)}"
            + (" (d'Alembert, from its contact force)" if rec.method.startswith("sem") else "")
            + (" (cross-section mean)" if rec.method == "fem_axi" else ""),
        )
    for rec in ordered:
        ax.axvline(
            1e6 * rec.summary["contact_end_s"][0],
            color="0.6",
            lw=0.8,
            ls=":",
            label="end of the first contact (dotted)",
        )
    ax.axhline(0.0, color="0.3", lw=0.6)
    ax.set_xlabel("time $t$ (µs)")
    ax.set_ylabel(f"axial displacement $u$ at $x$ = {xs[column]:.4g} m (µm)")
    ax.set_xlim(left=0)
    return _finish(fig, ax, title)


def plot_force_fits(records: Sequence[RunRecord], fits: Sequence[Any], title: str = "") -> matplotlib.figure.Figure:
    """Each method's computed force (line) with its closed form (open circles every few samples)
    above, and the closed form's error in per cent of the largest force below; one legend below
    both names each method with its closed form's size and largest error."""
    fig, (top, bottom) = plt.subplots(
        2, 1, figsize=(6.4, 6.6), sharex=True, height_ratios=[2.0, 1.0], layout="constrained"
    )
    pairs = sorted(zip(records, fits), key=lambda pair: METHOD_ORDER.index(pair[0].method))
    for index, (record, fit) in enumerate(pairs):
        t, force = record.series["time"], record.series["contact_force"]
        spec = METHODS[record.method]
        top.plot(1e6 * t, 1e-3 * force, spec.style, color=spec.color, lw=1.2)
        step = max(1, len(t) // 60)
        # staggered, so that the circles of closed forms lying on each other stay visible
        every = slice(index * step // max(1, len(pairs)), None, step)
        top.plot(1e6 * t[every], 1e-3 * fit.evaluate(t[every]), "o", color=spec.color, ms=3, mfc="none")
        bottom.plot(
            1e6 * t,
            100.0 * (fit.evaluate(t) - force) / fit.peak_force_N,
            spec.style,
            color=spec.color,
            lw=1.0,
            label=f"{spec.label}: closed form of {sum(len(p.coefficients) for p in fit.pieces)} "
            f"coefficients, largest error {100.0 * fit.max_rel_error:.2g} %",
        )
    top.plot([], [], "o", color="0.3", ms=3, mfc="none", label="closed form (open circles); lines: computed")
    top.set_ylabel("contact force $P$ (kN)")
    bottom.set_ylabel("closed form − computed\n(% of the largest force)")
    bottom.set_xlabel("time $t$ (µs)")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    top.legend(fontsize=7.5, loc="upper right", frameon=False)
    bottom.legend(fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.32), ncol=1, frameon=False)
    if title:
        top.set_title(title, fontsize=10)
    return fig
