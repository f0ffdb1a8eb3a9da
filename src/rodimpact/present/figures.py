"""Figures built from stored runs only; headless (Agg), provenance in the file metadata."""

from __future__ import annotations

import json
import logging
from pathlib import Path
from typing import Any, Mapping, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from rodimpact.io.atomic import atomic_output  # noqa: E402
from rodimpact.io.store import RunRecord  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402

__all__ = ["METHOD_LABELS", "plot_contact_force", "plot_force_fits", "plot_station_displacement", "plot_table2_contact_time",
           "save_figure"]

log = logging.getLogger(__name__)

#: Method -> its name in words (the registry's labels).
METHOD_LABELS = {name: spec.label for name, spec in METHODS.items()}
_STYLE = {name: spec.style for name, spec in METHODS.items()}
METHOD_ORDER = tuple(METHODS)
#: Open markers that tell apart curves lying on each other, in the methods' order.
_MARKERS = ("s", "^", "D", "v", "o", "x")


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
    ordered = _ordered(records)
    for index, rec in enumerate(ordered):
        t_us = 1e6 * rec.series["time"]
        # curves that lie on each other are told apart by their own markers, placed at
        # staggered times so that each stays visible
        marker = _MARKERS[index % len(_MARKERS)]
        every = (index * max(1, len(t_us) // 40) // max(1, len(ordered)), max(1, len(t_us) // 40))
        ax.plot(t_us, 1e-3 * rec.series["contact_force"], _STYLE.get(rec.method, "-"), lw=1.4,
                color=METHODS[rec.method].color if rec.method in METHODS else None,
                marker=marker, markevery=every, ms=4, mfc="none",
                label=f"{METHOD_LABELS.get(rec.method, rec.method)}: "
                      f"contact {1e6 * rec.summary['contact_time_s']:.1f} µs")
        last_end = max(last_end, float(np.atleast_1d(rec.summary["contact_end_s"])[-1]))
        peaks_t = 1e6 * np.asarray(rec.summary["peak_time_s"])
        ax.plot(peaks_t, 1e-3 * np.asarray(rec.summary["peak_force_N"]), "o", ms=4.5,
                color=ax.lines[-1].get_color(), label="_nolegend_")
    ax.plot([], [], "o", color="0.3", ms=4.5, label="force maxima (filled dots)")
    ax.set_xlabel("time $t$ (µs)")
    ax.set_ylabel("contact force $P$ (kN)")
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


def _panel_title(variant: str, overlays: Sequence[str], readings: pd.DataFrame | None) -> str:
    if readings is None or variant not in set(readings["variant"]):
        return f"rod geometry variant {variant}"
    reading = readings.set_index("variant").loc[variant]
    title = f"{variant}: rod radius {reading['rod_radius_mm']:g} mm, length {reading['rod_length_mm']:g} mm"
    return title + (f"\nwith the sensor film: {', '.join(overlays)}" if overlays else "")


def _film_sweep(ax: matplotlib.axes.Axes, curves: pd.DataFrame, nominal_pa: float) -> None:
    """The film sweep of one method: the curve at the nominal film modulus, and the band between
    the curves of the smallest and the largest modulus swept."""
    method = str(curves["method"].iloc[0])
    moduli = np.sort(curves["film_modulus_pa"].dropna().unique())
    nominal = moduli[np.argmin(np.abs(moduli - nominal_pa))] if np.isfinite(nominal_pa) else np.median(moduli)
    by_modulus = {m: c.sort_values("diameter_mm") for m, c in curves.groupby("film_modulus_pa")}
    line = by_modulus[nominal]
    ax.plot(line["mass_g"], line["contact_time_us"], "-", lw=1.2, color="tab:red",
            label=f"{METHOD_LABELS.get(method, method)}, with film: sweep at film modulus {nominal / 1e9:g} GPa")
    if len(moduli) > 1:
        low, high = by_modulus[moduli[0]], by_modulus[moduli[-1]]
        edges = low[["diameter_mm", "mass_g", "contact_time_us"]].merge(
            high[["diameter_mm", "contact_time_us"]], on="diameter_mm", suffixes=("_low", "_high"))
        ax.fill_between(edges["mass_g"], np.minimum(edges["contact_time_us_low"], edges["contact_time_us_high"]),
                        np.maximum(edges["contact_time_us_low"], edges["contact_time_us_high"]), color="tab:red",
                        alpha=0.15, lw=0, label=f"film modulus {moduli[0] / 1e9:g} to {moduli[-1] / 1e9:g} GPa")


def _film_overlay(ax: matplotlib.axes.Axes, variant: str, frame: pd.DataFrame | None, sweeps: pd.DataFrame | None,
                  bands: pd.DataFrame | None, nominal_pa: float, method: str) -> None:
    """A film reading on the panel of its rod: its runs, its sweep with the modulus band, and
    each row's prediction band over the film constants' ranges."""
    if frame is not None and f"{method}_us" in frame:
        ax.plot(frame["mass_g"], frame[f"{method}_us"], "D", ms=4.5, color="tab:red",
                label=f"{METHOD_LABELS.get(method, method)}, with film")
    if sweeps is not None and not sweeps.empty and "film_modulus_pa" in sweeps:
        for _, curves in sweeps[(sweeps["variant"] == variant) & sweeps["film_modulus_pa"].notna()].groupby("method"):
            _film_sweep(ax, curves, nominal_pa)
    if bands is not None and not bands.empty:
        band = bands[bands["variant"] == variant]
        if not band.empty:
            nominal = band["nominal_us"].to_numpy(float)
            ax.errorbar(band["mass_g"], nominal, yerr=[nominal - band["band_min_us"].to_numpy(float),
                                                       band["band_max_us"].to_numpy(float) - nominal],
                        fmt="none", ecolor="darkred", elinewidth=1.2, capsize=3,
                        label="with film: band over the film constants' ranges (SEM)")


def plot_table2_contact_time(frames: Mapping[str, pd.DataFrame], sweeps: pd.DataFrame | None = None, *,
                             panels: Mapping[str, Sequence[str]] | None = None,
                             readings: pd.DataFrame | None = None, bands: pd.DataFrame | None = None,
                             film_method: str = "sem") -> matplotlib.figure.Figure:
    """Contact time against ball mass per rod: measured, published and ours, with the film.

    Parameters
    ----------
    frames : mapping
        Variant -> :func:`rodimpact.present.tables.table2_frame`.
    sweeps : DataFrame, optional
        :func:`rodimpact.present.tables.sweep_results_frame` of sweep runs: each sweep and method of
        a variant is drawn as a curve in that variant's panel; a sweep over ``film_modulus_pa``
        of a film reading as its nominal curve and the band between its extreme moduli.
    panels : mapping, optional
        Panel variant -> the film readings drawn on it (default: one panel per variant of
        ``frames``, nothing drawn on it).
    readings : DataFrame, optional
        :func:`rodimpact.present.film_tables.readings_frame`: the rods of the titles, the film's
        nominal modulus.
    bands : DataFrame, optional
        :func:`rodimpact.present.film_tables.film_band_frame`: each row's prediction band, as an
        error bar on the panel of its film reading.
    film_method : str
        The method whose film runs are drawn.
    """
    panels = {v: () for v in frames} if panels is None else dict(panels)
    nominal = ({} if readings is None else
               dict(zip(readings["variant"], readings["film_modulus_pa"].astype(float))))
    n = len(panels)
    cols = 2 if n > 1 else 1
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.6 * rows + 1.4), squeeze=False,
                             sharex=True, sharey=True, layout="constrained")
    for ax, (variant, overlays) in zip(axes.flat, panels.items()):
        frame = frames[variant]
        mass = frame["mass_g"]
        ax.plot(mass, frame["measured_us"], "ks", ms=6, label="measured (paper, Table 2)")
        ax.plot(mass, frame["published_fem_us"], "^", mfc="none", color="tab:gray", label="FEM (paper)")
        ax.plot(mass, frame["published_sem_us"], "v", mfc="none", color="tab:brown", label="SEM (paper)")
        for method in METHOD_ORDER:
            if f"{method}_us" in frame:
                ax.plot(mass, frame[f"{method}_us"], "o" + _STYLE[method], ms=4, color=METHODS[method].color,
                        label=f"{METHOD_LABELS[method]}, no film")
        if sweeps is not None and not sweeps.empty:
            plain = sweeps[sweeps["variant"] == variant]
            if "film_modulus_pa" in plain:
                plain = plain[plain["film_modulus_pa"].isna()]
            for (_, method), curve in plain.groupby(["row", "method"]):
                ax.plot(curve["mass_g"], curve["contact_time_us"], _STYLE.get(method, "-"), lw=1.0,
                        color="tab:purple", label=(f"{METHOD_LABELS.get(method, method)}, no film: sweep of "
                                                   f"{len(curve)} ball sizes"))
        for film in overlays:
            _film_overlay(ax, film, frames.get(film), sweeps, bands, nominal.get(film, np.nan), film_method)
        ax.set_title(_panel_title(variant, overlays, readings), fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")  # one scale for all panels: the readings' times differ tenfold
        ax.grid(alpha=0.3, which="both")
    # the limits of the rows' points (sweeps beyond them are cut): the same for every panel
    points = [np.asarray(v, float) for ax in axes.flat[:n] for line in ax.lines if line.get_marker() not in (None, "", "None")
              for v in (line.get_xdata(), line.get_ydata())]
    xs = np.concatenate(points[0::2]) if points else np.empty(0)
    ys = np.concatenate([*points[1::2], *([] if bands is None or bands.empty else
                                           [bands["band_min_us"].to_numpy(float), bands["band_max_us"].to_numpy(float)])])
    xs, ys = xs[np.isfinite(xs) & (xs > 0)], ys[np.isfinite(ys) & (ys > 0)]
    if len(xs) and len(ys):
        axes.flat[0].set_xlim(xs.min() / 2.0, xs.max() * 2.0)
        axes.flat[0].set_ylim(ys.min() / 1.25, ys.max() * 1.25)
    plain = matplotlib.ticker.FuncFormatter(lambda value, _: f"{value:g}")
    for ax in axes.flat[:n]:  # numbers at 1, 2, 5 x 10^k on both log axes
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_locator(matplotlib.ticker.LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(plain)
            axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    for ax in axes[:, 0]:
        ax.set_ylabel("contact time, µs")
    for ax in axes[-1]:
        ax.set_xlabel("ball mass, g")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    handles: dict[str, Any] = {}
    for ax in axes.flat[:n]:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    fig.legend(list(handles.values()), list(handles), loc="outside lower center", ncol=2 if cols > 1 else 1,
               fontsize=7.5, frameon=False)
    return fig


def plot_force_fits(records: Sequence[RunRecord], fits: Sequence[Any], title: str = "") -> matplotlib.figure.Figure:
    """Each method's computed force (line) with its closed form (markers every few samples)
    above, and the closed form's error in per cent of the largest force below."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.4, 6.6), sharex=True, height_ratios=[2.0, 1.0],
                                      layout="constrained")
    pairs = sorted(zip(records, fits), key=lambda pair: METHOD_ORDER.index(pair[0].method))
    for record, fit in pairs:
        t, force = record.series["time"], record.series["contact_force"]
        spec = METHODS[record.method]
        top.plot(1e6 * t, 1e-3 * force, spec.style, color=spec.color, lw=1.2, label=f"{spec.label}, computed")
        step = max(1, len(t) // 60)
        top.plot(1e6 * t[::step], 1e-3 * fit.evaluate(t[::step]), "o", color=spec.color, ms=3, mfc="none",
                 label=f"closed form ({sum(len(p.coefficients) for p in fit.pieces)} coefficients)")
        bottom.plot(1e6 * t, 100.0 * (fit.evaluate(t) - force) / fit.peak_force_N, spec.style, color=spec.color,
                    lw=1.0, label=f"{spec.label}: largest {100.0 * fit.max_rel_error:.2g} %")
    top.set_ylabel("contact force $P$ (kN)")
    bottom.set_ylabel("closed form − computed\n(% of the largest force)")
    bottom.set_xlabel("time $t$ (µs)")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    top.legend(fontsize=7, loc="upper right", ncol=1, frameon=False)
    bottom.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.32), ncol=2, frameon=False)
    if title:
        top.set_title(title, fontsize=10)
    return fig
