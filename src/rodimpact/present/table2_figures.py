"""The Table 2 figure: contact time against ball mass, one panel per reading of the rod.

The panels form a grid by rod radius (rows) and rod length (columns) where the readings allow
it; a film reading is drawn on the panel of the reading it extends (the same rod). Every panel
has the same axes, fitted to the table's balls. What one panel shows: a reading's rows
(measured, one marker per source; the paper's; ours), its sweeps' curves, a film reading's and a
sensor reading's overlays with their bands, the rings round the runs with more than one contact,
and the panel's title. Built from stored runs only; headless (Agg).
"""

from __future__ import annotations

import logging
import math
import re
import textwrap
from collections.abc import Mapping, Sequence
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from rodimpact.present.figures import METHOD_LABELS, METHOD_ORDER  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402

__all__ = ["SECOND_CONTACT_LABEL", "panel_grid", "plot_table2_contact_time", "short_source", "swept_methods"]

log = logging.getLogger(__name__)

#: The legend entry of the rings round runs with more than one contact.
SECOND_CONTACT_LABEL = "ring: ball struck again by the reflected wave (first contact's time shown)"
#: Markers of the measured points, one per source, in the order the sources are met.
_SOURCE_MARKERS = ("s", "P", "X", "*", "h", "p")
#: Longest source text in the legend.
_SOURCE_CHARS = 48
#: A panel title's line, characters (at 9 pt on a panel's width): titles wrap to fit.
_TITLE_CHARS = 70

#: The colour of the sensor as built (no method's: the methods take C0 to C3).
SENSOR_COLOR = "C9"


def short_source(source: str) -> str:
    """A source of measurements shortened for a legend: without a trailing parenthesis, and cut
    at a word to at most 48 characters (``Table 2, column "Natural experiment" (time of the
    contact interaction, us)`` -> ``Table 2, column "Natural experiment"``)."""
    text = re.sub(r"\s*\([^()]*\)\s*$", "", " ".join(str(source).split())) or str(source).strip()
    if len(text) <= _SOURCE_CHARS:
        return text
    return text[: _SOURCE_CHARS - 1].rsplit(" ", 1)[0].rstrip(",;:") + "…"


def _panel_title(
    variant: str,
    overlays: Sequence[str],
    descriptions: Mapping[str, str],
    readings: pd.DataFrame | None,
    sensors: Mapping[str, bool],
) -> str:
    """The reading in words (its ``description`` in the case file), and what its overlays add:
    the sensor as built (``sensors``), the film alone (the other overlays)."""
    title = descriptions.get(variant, "")
    if not title and readings is not None and variant in set(readings["variant"]):
        reading = readings.set_index("variant").loc[variant]
        title = f"Rod radius {reading['rod_radius_mm']:g} mm, length {reading['rod_length_mm']:g} mm"
    title = title or "Rod of this reading"
    drawn = []
    if any(v in sensors for v in overlays):
        drawn.append("the sensor as built (cyan)")
    if any(v not in sensors for v in overlays):
        drawn.append("the film alone (red)")
    if drawn:
        title += "\n" + textwrap.fill("without the sensor, and with " + " and ".join(drawn), _TITLE_CHARS)
    return title


def _rings(ax: matplotlib.axes.Axes, mass: Sequence[float], time: Sequence[float], many: Sequence[bool]) -> None:
    """Rings round the points whose run had more than one contact."""
    pick = np.asarray(many, bool)
    if pick.any():
        ax.plot(
            np.asarray(mass, float)[pick],
            np.asarray(time, float)[pick],
            "o",
            ms=9,
            mfc="none",
            mew=1.0,
            color="0.15",
            label=SECOND_CONTACT_LABEL,
            zorder=5,
        )


def _many_contacts(frame: pd.DataFrame) -> np.ndarray:
    """Per row of a sweep frame: more than one contact (False where the frame does not say)."""
    if "n_contacts" not in frame:
        return np.zeros(len(frame), bool)
    return frame["n_contacts"].fillna(1).to_numpy(float) > 1


def _film_sweep(ax: matplotlib.axes.Axes, curves: pd.DataFrame, nominal_pa: float) -> None:
    """The film sweep of one method: the curve at the nominal film modulus, and the band between
    the curves of the smallest and the largest modulus swept."""
    method = str(curves["method"].iloc[0])
    moduli = np.sort(curves["film_modulus_pa"].dropna().unique())
    nominal = moduli[np.argmin(np.abs(moduli - nominal_pa))] if np.isfinite(nominal_pa) else np.median(moduli)
    by_modulus = {m: c.sort_values("diameter_mm") for m, c in curves.groupby("film_modulus_pa")}
    line = by_modulus[nominal]
    ax.plot(
        line["mass_g"],
        line["contact_time_us"],
        "-",
        lw=1.2,
        color="tab:red",
        # the film rows' model: one legend entry for the rows and the line (:func:`_film_overlay`)
        label=f"{METHOD_LABELS.get(method, method)}, film as a thin layer (approximation, too soft)",
    )
    _rings(ax, line["mass_g"], line["contact_time_us"], _many_contacts(line))
    if len(moduli) > 1:
        low, high = by_modulus[moduli[0]], by_modulus[moduli[-1]]
        edges = low[["diameter_mm", "mass_g", "contact_time_us"]].merge(
            high[["diameter_mm", "contact_time_us"]], on="diameter_mm", suffixes=("_low", "_high")
        )
        ax.fill_between(
            edges["mass_g"],
            np.minimum(edges["contact_time_us_low"], edges["contact_time_us_high"]),
            np.maximum(edges["contact_time_us_low"], edges["contact_time_us_high"]),
            color="tab:red",
            alpha=0.15,
            lw=0,
            label=FILM_RANGES_LABEL,
        )


#: The film's ranges, as one legend entry: each row's band over the film constants' ranges (bars)
#: and the sweep's band over the film's modulus (shade).
FILM_RANGES_LABEL = "film as a thin layer: band over its constants' ranges (approximation; bars: all, shade: modulus)"


def _film_overlay(
    ax: matplotlib.axes.Axes,
    variant: str,
    frame: pd.DataFrame | None,
    sweeps: pd.DataFrame | None,
    bands: pd.DataFrame | None,
    nominal_pa: float,
    method: str,
    contacts: Mapping[tuple[str, str], int],
) -> None:
    """A film reading on the panel of its rod: its runs, its sweep with the modulus band, and
    each row's prediction band over the film constants' ranges."""
    if frame is not None and f"{method}_us" in frame:
        ax.plot(
            frame["mass_g"],
            frame[f"{method}_us"],
            "D",
            ms=4.5,
            color="tab:red",
            label=f"{METHOD_LABELS.get(method, method)}, film as a thin layer (approximation, too soft)",
        )
        _rings(ax, frame["mass_g"], frame[f"{method}_us"], [contacts.get((c, method), 1) > 1 for c in frame["case_id"]])
    if sweeps is not None and not sweeps.empty and "film_modulus_pa" in sweeps:
        for _, curves in sweeps[(sweeps["variant"] == variant) & sweeps["film_modulus_pa"].notna()].groupby("method"):
            _film_sweep(ax, curves, nominal_pa)
    if bands is not None and not bands.empty:
        _band_bars(ax, bands[bands["variant"] == variant], FILM_RANGES_LABEL, "darkred", 1.2, 3)


def _band_bars(
    ax: matplotlib.axes.Axes, band: pd.DataFrame, label: str, colour: str, width: float, caps: float, zorder: float = 2
) -> None:
    """Each row's band as an error bar about its nominal time (``nominal_us``, ``band_min_us``,
    ``band_max_us``, µs, at ``mass_g``); nothing for no row."""
    if band.empty:
        return
    nominal = band["nominal_us"].to_numpy(float)
    ax.errorbar(
        band["mass_g"],
        nominal,
        yerr=[nominal - band["band_min_us"].to_numpy(float), band["band_max_us"].to_numpy(float) - nominal],
        fmt="none",
        ecolor=colour,
        elinewidth=width,
        capsize=caps,
        zorder=zorder,
        label=label,
    )


def _sensor_overlay(
    ax: matplotlib.axes.Axes,
    variant: str,
    frame: pd.DataFrame | None,
    calibrated: bool,
    bands: pd.DataFrame | None,
    sweeps: pd.DataFrame | None,
) -> None:
    """A reading with the sensor as built, on the panel of its rod: the continuum's dynamic runs
    (``fem_axi``), or the 1-D methods with the law the continuum calibrates on the stack (the
    SEM: its sweep over the ball sizes as a line, each indented by the continuum, or a line
    through the rows without one; its rows as points) with each row's band over the stack's
    sourced ranges."""
    if frame is None:
        return
    if not calibrated and "fem_axi_us" in frame:
        ax.plot(
            frame["mass_g"],
            frame["fem_axi_us"],
            "D",
            ms=6,
            color=SENSOR_COLOR,
            zorder=6,
            label=f"{METHOD_LABELS['fem_axi']}, sensor as built (electrodes, film, bond line)",
        )
    if calibrated and "sem_us" in frame:
        label = f"{METHOD_LABELS['sem']}, sensor as built, contact law calibrated by the continuum"
        sweep = (
            None
            if sweeps is None or sweeps.empty
            else sweeps[(sweeps["variant"] == variant) & (sweeps["method"] == "sem")].sort_values("mass_g")
        )
        if sweep is not None and not sweep.empty:
            # the sweep as a line and the rows as dots on it, under one label: one legend entry
            both = f"{label} (line: {len(sweep)} ball sizes; dots: the rows)"
            ax.plot(sweep["mass_g"], sweep["contact_time_us"], "-", lw=1.6, color=SENSOR_COLOR, zorder=5, label=both)
            ax.plot(frame["mass_g"], frame["sem_us"], "o", ms=4, color=SENSOR_COLOR, zorder=6, label=both)
        else:
            ordered = frame.sort_values("mass_g")
            ax.plot(ordered["mass_g"], ordered["sem_us"], "-", lw=1.6, color=SENSOR_COLOR, zorder=5, label=label)
        if bands is not None and not bands.empty:
            _band_bars(
                ax,
                bands[bands["case_id"].isin(frame["case_id"])],
                "sensor as built: band over its sourced ranges (continuum's law)",
                "teal",
                1.6,
                4,
                zorder=5,
            )


def _rows(
    ax: matplotlib.axes.Axes,
    frame: pd.DataFrame,
    sources: Mapping[str, str],
    contacts: Mapping[tuple[str, str], int],
    set_title: str,
    published: bool = True,
    swept: frozenset[str] = frozenset(),
) -> None:
    """A reading's rows: measured (one marker per source), the paper's FEM and SEM where the
    cases declare them (and ``published``), ours; a method in ``swept`` as dots only (its line
    is its sweep's, :func:`_sweep_curves`)."""
    mass = frame["mass_g"]
    measured = frame.assign(_source=[sources.get(c, "") for c in frame["case_id"]])
    measured = measured[np.isfinite(measured["measured_us"].to_numpy(float))]
    every = list(dict.fromkeys(sources.values())) or [""]
    for source, rows in measured.groupby("_source", sort=False):
        marker = _SOURCE_MARKERS[every.index(source) % len(_SOURCE_MARKERS)] if source in every else "s"
        ax.plot(
            rows["mass_g"],
            rows["measured_us"],
            marker,
            color="k",
            ms=6,
            ls="none",
            zorder=7,  # above every model: what was measured is never hidden
            label=f"measured ({short_source(source)})" if source else "measured",
        )
    for family, marker, colour in (("fem", "^", "tab:gray"), ("sem", "v", "tab:brown")):
        column = f"published_{family}_us"
        if published and column in frame and frame[column].notna().any():
            ax.plot(
                mass,
                frame[column],
                marker,
                mfc="none",
                color=colour,
                ls="none",
                label=f"the paper's FEM (up) and SEM (down), its {set_title}",
            )
    for method in METHOD_ORDER:
        if f"{method}_us" in frame:
            ax.plot(
                mass,
                frame[f"{method}_us"],
                "o" if method in swept else "o" + METHODS[method].style,
                ms=4,
                color=METHODS[method].color,
                label=f"{METHOD_LABELS[method]}, no film",
            )
            _rings(ax, mass, frame[f"{method}_us"], [contacts.get((c, method), 1) > 1 for c in frame["case_id"]])


def swept_methods(variant: str, sweeps: pd.DataFrame | None) -> frozenset[str]:
    """The methods with a sweep of ``variant`` without the film (their line is the sweep's)."""
    if sweeps is None or sweeps.empty:
        return frozenset()
    plain = sweeps[sweeps["variant"] == variant]
    if "film_modulus_pa" in plain:
        plain = plain[plain["film_modulus_pa"].isna()]
    return frozenset(plain["method"])


def _sweep_curves(ax: matplotlib.axes.Axes, variant: str, sweeps: pd.DataFrame | None) -> None:
    """The sweeps of a reading without the film: one curve per sweep and method, in the
    method's colour and under its rows' label (the rows are dots on it: one legend entry),
    ringed where its run had more than one contact."""
    if sweeps is None or sweeps.empty:
        return
    plain = sweeps[sweeps["variant"] == variant]
    if "film_modulus_pa" in plain:
        plain = plain[plain["film_modulus_pa"].isna()]
    for (_, method), curve in plain.groupby(["row", "method"]):
        ax.plot(
            curve["mass_g"],
            curve["contact_time_us"],
            METHODS[method].style if method in METHODS else "-",
            lw=1.2,
            color=METHODS[method].color if method in METHODS else None,
            label=f"{METHOD_LABELS.get(method, method)}, no film",
        )
        _rings(ax, curve["mass_g"], curve["contact_time_us"], _many_contacts(curve))


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
        Variant -> :func:`rodimpact.present.readings.table2_frame` (times in µs, masses in g).
    sweeps : DataFrame, optional
        :func:`rodimpact.present.sweep_table.sweep_results_frame` of sweep runs: each sweep and method of
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
