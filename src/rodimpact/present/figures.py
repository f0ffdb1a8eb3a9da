"""Figures built from stored runs only; headless (Agg), provenance in the file metadata."""

from __future__ import annotations

import json
import logging
from pathlib import Path
from typing import Any, Mapping, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from rodimpact.io.atomic import atomic_output  # noqa: E402
from rodimpact.io.store import RunRecord  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402

__all__ = ["METHOD_LABELS", "plot_contact_force", "plot_station_displacement", "plot_table2_contact_time",
           "save_figure"]

log = logging.getLogger(__name__)

#: Method -> its name in words (the registry's labels).
METHOD_LABELS = {name: spec.label for name, spec in METHODS.items()}
_STYLE = {name: spec.style for name, spec in METHODS.items()}
METHOD_ORDER = tuple(METHODS)


def save_figure(fig: matplotlib.figure.Figure, *, pdf: str | Path, png: str | Path,
                provenance: Mapping[str, Any], title: str) -> None:
    """Save ``fig`` as PDF and PNG atomically, with ``provenance`` (JSON) in the metadata.

    PNG: text chunks ``Title``, ``Description`` (the provenance JSON), ``Software``.
    PDF: info entries ``Title``, ``Subject`` (the provenance JSON), ``Creator``.
    """
    text = json.dumps(provenance, sort_keys=True)
    software = f"rodimpact {provenance.get('code_version', '')}".strip()
    with atomic_output(pdf) as tmp:
        fig.savefig(tmp, format="pdf", metadata={"Title": title, "Subject": text, "Creator": software})
    with atomic_output(png) as tmp:
        fig.savefig(tmp, format="png", dpi=150,
                    metadata={"Title": title, "Description": text, "Software": software})
    plt.close(fig)


def _finish(fig: matplotlib.figure.Figure, ax: matplotlib.axes.Axes, title: str) -> matplotlib.figure.Figure:
    """Grid, a legend below the axes, and the title: the look every time plot shares."""
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1, frameon=False)
    if title:
        ax.set_title(title, fontsize=10)
    return fig


def _ordered(records: Sequence[RunRecord]) -> list[RunRecord]:
    rank = {m: i for i, m in enumerate(METHOD_ORDER)}
    return sorted(records, key=lambda r: rank.get(r.method, len(rank)))


def plot_contact_force(records: Sequence[RunRecord], title: str = "") -> matplotlib.figure.Figure:
    """Fig. 2: contact force against time, one curve per method (first contact marked).

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of one case with the ``contact_force`` series.
    """
    fig, ax = plt.subplots(figsize=(7.0, 5.0), layout="constrained")
    last_end = 0.0
    for rec in _ordered(records):
        t_us = 1e6 * rec.series["time"]
        ax.plot(t_us, 1e-3 * rec.series["contact_force"], _STYLE.get(rec.method, "-"), lw=1.4,
                label=f"{METHOD_LABELS.get(rec.method, rec.method)}: "
                      f"contact {1e6 * rec.summary['contact_time_s']:.1f} µs")
        last_end = max(last_end, float(np.atleast_1d(rec.summary["contact_end_s"])[-1]))
        peaks_t = 1e6 * np.asarray(rec.summary["peak_time_s"])
        ax.plot(peaks_t, 1e-3 * np.asarray(rec.summary["peak_force_N"]), "o", ms=3.5,
                color=ax.lines[-1].get_color())
    ax.set_xlabel("time t, µs")
    ax.set_ylabel("contact force P, kN")
    ax.set_xlim(0, 1.05e6 * last_end)
    ax.set_ylim(bottom=0)
    return _finish(fig, ax, title)


def plot_station_displacement(records: Sequence[RunRecord], fraction: float,
                              title: str = "") -> matplotlib.figure.Figure:
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
    for rec in _ordered(records):
        xs = np.atleast_1d(rec.summary["station_x_m"])
        length = rec.config["rod"]["length_m"]
        column = int(np.argmin(np.abs(xs / length - fraction)))
        history = np.asarray(rec.series["station_displacement"]).reshape(len(rec.series["time"]), -1)
        ax.plot(1e6 * rec.series["time"], 1e6 * history[:, column], _STYLE.get(rec.method, "-"), lw=1.4,
                label=f"{METHOD_LABELS.get(rec.method, rec.method)}"
                      + (" (d'Alembert, from its contact force)" if rec.method.startswith("sem") else "")
                      + (" (cross-section mean)" if rec.method == "fem_axi" else ""))
        ax.axvline(1e6 * rec.summary["contact_end_s"][0], color="0.6", lw=0.8, ls=":")
    ax.axhline(0.0, color="0.3", lw=0.6)
    ax.set_xlabel("time t, µs")
    ax.set_ylabel(f"axial displacement u at x = {xs[column]:.4g} m, µm")
    ax.set_xlim(left=0)
    return _finish(fig, ax, title)


def plot_table2_contact_time(frames: Mapping[str, pd.DataFrame],
                             sweeps: pd.DataFrame | None = None) -> matplotlib.figure.Figure:
    """Contact time against ball mass per geometry variant: measured, published and ours.

    Parameters
    ----------
    frames : mapping
        Variant -> :func:`rodimpact.present.tables.table2_frame`.
    sweeps : DataFrame, optional
        :func:`rodimpact.present.tables.sweep_results_frame` of sweep runs: each sweep and method of
        a variant is drawn as a curve in that variant's panel.
    """
    n = len(frames)
    cols = 2 if n > 1 else 1
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(5.0 * cols, 3.8 * rows), squeeze=False,
                             sharex=True, layout="constrained")
    for ax, (variant, frame) in zip(axes.flat, frames.items()):
        mass = frame["mass_g"]
        ax.plot(mass, frame["measured_us"], "ks", ms=6, label="measured (paper, Table 2)")
        ax.plot(mass, frame["published_fem_us"], "^", mfc="none", color="tab:gray", label="FEM (paper)")
        ax.plot(mass, frame["published_sem_us"], "v", mfc="none", color="tab:brown", label="SEM (paper)")
        for method in METHOD_ORDER:
            if f"{method}_us" in frame:
                ax.plot(mass, frame[f"{method}_us"], "o" + _STYLE[method], ms=4,
                        label=METHOD_LABELS[method])
        if sweeps is not None and not sweeps.empty:
            for (row, method), curve in sweeps[sweeps["variant"] == variant].groupby(["row", "method"]):
                ax.plot(curve["mass_g"], curve["contact_time_us"], _STYLE.get(method, "-"), lw=1.0,
                        color="tab:purple", label=(f"{METHOD_LABELS.get(method, method)}: sweep "
                                                   f"'{row}', {len(curve)} points"))
        ax.set_title(f"rod geometry variant {variant}", fontsize=10)
        ax.set_xscale("log")
        ax.grid(alpha=0.3, which="both")
        ax.set_ylabel("contact time, µs")
    for ax in axes[-1]:
        ax.set_xlabel("ball mass, g")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=7, loc="upper left")
    return fig
