"""The Table 2 figure: contact time against ball mass, one panel per reading of the rod.

The panels form a grid by rod radius (rows) and rod length (columns) where the readings allow
it; a film reading is drawn on the panel of the reading it extends (the same rod). Every panel
has the same axes, fitted to the table's balls. Built from stored runs only; headless (Agg).
Here the figure is assembled (the grid, the common axes, the legend below the panels); what a
panel shows is drawn by :mod:`.table2_drawing`.
"""

from __future__ import annotations

import logging
import math
import textwrap
from collections.abc import Mapping, Sequence
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from rodimpact.present.table2_drawing import (  # noqa: E402
    SECOND_CONTACT_LABEL,
    _film_overlay,
    _panel_title,
    _rows,
    _sensor_overlay,
    _sweep_curves,
    short_source,
    swept_methods,
)

# SECOND_CONTACT_LABEL and short_source live in .table2_drawing; named here too, where they were found before
__all__ = ["SECOND_CONTACT_LABEL", "panel_grid", "plot_table2_contact_time", "short_source"]

log = logging.getLogger(__name__)

#: Margin of the axes round the data, as a factor on the log scales.
_MASS_MARGIN, _TIME_MARGIN = 1.3, 1.15
#: A panel's width and height, in; the legend's font size, pt; a character's mean width, em (DejaVu Sans):
#: the legend wraps to fit.
_PANEL_WIDTH_IN = 5.0
_PANEL_HEIGHT_IN = 3.5
_LEGEND_PT = 7.5
_CHAR_EM = 0.6


def panel_grid(panels: Sequence[str], readings: pd.DataFrame | None) -> list[list[str | None]]:
    """The panels placed in rows and columns.

    A grid with one row per rod radius and one column per rod length (both increasing), when
    each panel's rod is its own and the grid is at most half empty; otherwise the panels in
    rows of two, by radius, then length. Without ``readings`` (the rods), in rows of two in
    the order given.

    Parameters
    ----------
    panels : sequence of str
        The variants that get a panel.
    readings : DataFrame, optional
        :func:`rodimpact.present.film_tables.readings_frame` (``rod_radius_mm``, ``rod_length_mm``).
    """
    panels = list(panels)
    rods: dict[str, tuple[float, float]] = {}
    if readings is not None and set(panels) <= set(readings["variant"]):
        known = readings.set_index("variant")
        rods = {
            v: (round(float(known.at[v, "rod_radius_mm"]), 9), round(float(known.at[v, "rod_length_mm"]), 9))
            for v in panels
        }
        panels.sort(key=lambda v: rods[v])
    radii = sorted({r for r, _ in rods.values()})
    lengths = sorted({length for _, length in rods.values()})
    if rods and len(set(rods.values())) == len(panels) and len(radii) * len(lengths) <= 2 * len(panels):
        grid: list[list[str | None]] = [[None] * len(lengths) for _ in radii]
        for variant, (radius, length) in rods.items():
            grid[radii.index(radius)][lengths.index(length)] = variant
        return grid
    cols = 2 if len(panels) > 1 else 1
    return [panels[i : i + cols] + [None] * (cols - len(panels[i : i + cols])) for i in range(0, len(panels), cols)]


def _limits(
    axes: Sequence[matplotlib.axes.Axes], frames: Sequence[pd.DataFrame], bands: pd.DataFrame | None
) -> tuple[tuple[float, float], tuple[float, float]]:
    """Mass limits fitted to the table's balls; time limits fitted to everything drawn at those
    masses (points, curves, band ends)."""
    masses = np.concatenate([f["mass_g"].to_numpy(float) for f in frames])
    masses = masses[np.isfinite(masses) & (masses > 0)]
    x0, x1 = masses.min() / _MASS_MARGIN, masses.max() * _MASS_MARGIN
    times = [] if bands is None or bands.empty else [bands[c].to_numpy(float) for c in ("band_min_us", "band_max_us")]
    for ax in axes:
        for line in ax.lines:
            x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
            times.append(y[(x >= x0) & (x <= x1)])
    ys = np.concatenate(times) if times else np.empty(0)
    ys = ys[np.isfinite(ys) & (ys > 0)]
    return (x0, x1), ((ys.min() / _TIME_MARGIN, ys.max() * _TIME_MARGIN) if len(ys) else (1.0, 1e3))


def _look(handle: Any) -> tuple:
    """What tells two legend handles of one label apart: their kind, marker and line style."""
    marker = handle.get_marker() if hasattr(handle, "get_marker") else None
    style = handle.get_linestyle() if hasattr(handle, "get_linestyle") else None
    return (type(handle).__name__, repr(marker), repr(style))  # a collection's styles are a list


def _log_ticks(ax: matplotlib.axes.Axes) -> None:
    """Numbers at 1, 2, 5 x 10^k (mass) and 1, 2, 3, 5 x 10^k (time), written plainly."""
    plain = matplotlib.ticker.FuncFormatter(lambda value, _: f"{value:g}")
    for axis, subs in ((ax.xaxis, (1.0, 2.0, 5.0)), (ax.yaxis, (1.0, 2.0, 3.0, 5.0))):
        axis.set_major_locator(matplotlib.ticker.LogLocator(base=10.0, subs=subs))
        axis.set_major_formatter(plain)
        axis.set_minor_formatter(matplotlib.ticker.NullFormatter())


def plot_table2_contact_time(
    frames: Mapping[str, pd.DataFrame],
    sweeps: pd.DataFrame | None = None,
    *,
    panels: Mapping[str, Sequence[str]] | None = None,
    readings: pd.DataFrame | None = None,
    bands: pd.DataFrame | None = None,
    descriptions: Mapping[str, str] | None = None,
    sources: Mapping[str, str] | None = None,
    contacts: Mapping[tuple[str, str], int] | None = None,
    film_method: str = "sem",
    sensors: Mapping[str, bool] | None = None,
    sensor_bands: pd.DataFrame | None = None,
    set_title: str,
    published: bool = True,
) -> matplotlib.figure.Figure:
    """Contact time against ball mass per rod: measured, published and ours, with the film.

    Parameters
    ----------
    frames : mapping
        Variant -> :func:`rodimpact.present.tables.table2_frame` (times in µs, masses in g).
    sweeps : DataFrame, optional
        :func:`rodimpact.present.tables.sweep_results_frame` of sweep runs: each sweep and method of
        a variant is drawn as a curve in that variant's panel, ringed at the points with more than
        one contact (``n_contacts``); a sweep over ``film_modulus_pa`` of a film reading as its
        nominal curve and the band between its extreme moduli.
    panels : mapping, optional
        Panel variant -> the film readings drawn on it (default: one panel per variant of
        ``frames``, nothing drawn on it); placed by :func:`panel_grid`.
    readings : DataFrame, optional
        :func:`rodimpact.present.film_tables.readings_frame`: the rods (the grid, titles without a
        description), the film's nominal modulus.
    bands : DataFrame, optional
        :func:`rodimpact.present.film_tables.film_band_frame`: each row's prediction band, as an
        error bar on the panel of its film reading.
    descriptions : mapping, optional
        Variant -> the reading in words (the case file's ``description``): the panel titles.
    sources : mapping, optional
        Case id -> the source of its measured value: measured points are grouped by source.
    contacts : mapping, optional
        (case id, method) -> the run's number of contacts: rows with more than one are ringed.
    set_title : str
        The set in words (its ``compare.title``, e.g. ``Table 2``): the published points' labels.
    film_method : str
        The method whose film runs are drawn.
    sensors : mapping, optional
        Variant -> whether its law is calibrated by the continuum, for the readings with the
        sensor as built drawn on their rod's panel (listed in ``panels`` too): the continuum's
        runs, or the calibrated SEM's line (its sweep in ``sweeps`` under the reading's variant,
        else a line through its rows) with the bands of ``sensor_bands``
        (:func:`rodimpact.present.sensor_tables.sensor_band_frame`).
    published : bool
        Whether the published results the cases declare are drawn (the paper's FEM and SEM).
    """
    panels = {v: () for v in frames} if panels is None else dict(panels)
    descriptions, sources, contacts = dict(descriptions or {}), dict(sources or {}), dict(contacts or {})
    sensors = dict(sensors or {})
    nominal = {} if readings is None else dict(zip(readings["variant"], readings["film_modulus_pa"].astype(float)))
    grid = panel_grid(list(panels), readings)
    rows, cols = len(grid), len(grid[0])
    fig, axes = plt.subplots(
        rows,
        cols,
        figsize=(_PANEL_WIDTH_IN * cols, _PANEL_HEIGHT_IN * rows + 1.6),
        squeeze=False,
        sharex=True,
        sharey=True,
        layout="constrained",
    )
    drawn = []
    for (i, j), variant in np.ndenumerate(np.array(grid, dtype=object)):
        ax = axes[i, j]
        if variant is None:
            ax.set_visible(False)
            continue
        drawn.append(ax)
        _rows(ax, frames[variant], sources, contacts, set_title, published, swept_methods(variant, sweeps))
        _sweep_curves(ax, variant, sweeps)
        for film in panels[variant]:
            if film in sensors:
                _sensor_overlay(ax, film, frames.get(film), sensors[film], sensor_bands, sweeps)
            else:
                _film_overlay(
                    ax, film, frames.get(film), sweeps, bands, nominal.get(film, math.nan), film_method, contacts
                )
        ax.set_title(_panel_title(variant, panels[variant], descriptions, readings, sensors), fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")  # one scale for all panels: the readings' times differ tenfold
        ax.grid(alpha=0.3, which="both")
    (x0, x1), (y0, y1) = _limits(drawn, [frames[v] for v in panels], bands)
    drawn[0].set_xlim(x0, x1)
    drawn[0].set_ylim(y0, y1)
    for ax in drawn:
        _log_ticks(ax)
    for j in range(cols):  # the lowest panel of each column carries the mass axis
        column = [axes[i, j] for i in range(rows) if grid[i][j] is not None]
        if column:
            column[-1].set_xlabel("ball mass $m$ (g)")
            column[-1].xaxis.set_tick_params(labelbottom=True)
    for i in range(rows):
        row = [axes[i, j] for j in range(cols) if grid[i][j] is not None]
        if row:
            row[0].set_ylabel("contact time (µs)")
            row[0].yaxis.set_tick_params(labelleft=True)
    # one entry per label; the artists of one label that look different (a model's rows and its
    # line, a band's bars and its shade) drawn on top of each other in it
    looks: dict[str, dict[tuple, Any]] = {}
    for ax in drawn:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            looks.setdefault(label, {}).setdefault(_look(handle), handle)
    handles = {
        label: tuple(kinds.values()) if len(kinds) > 1 else next(iter(kinds.values())) for label, kinds in looks.items()
    }
    ncol = 2 if cols > 1 else 1
    # each legend column holds its share of the figure's width, less the marker: wrap to it
    width = int((_PANEL_WIDTH_IN * cols / ncol - 0.6) / (_CHAR_EM * _LEGEND_PT / 72.0))
    labels = [textwrap.fill(label, width) for label in handles]
    fig.legend(
        list(handles.values()), labels, loc="outside lower center", ncol=ncol, fontsize=_LEGEND_PT, frameon=False
    )
    # the legend below the panels takes its own height: the panels keep theirs
    lines = math.ceil(sum(label.count("\n") + 1 for label in labels) / ncol)
    fig.set_size_inches(_PANEL_WIDTH_IN * cols, _PANEL_HEIGHT_IN * rows + 0.8 + lines * _LEGEND_PT * 1.5 / 72.0)
    return fig
