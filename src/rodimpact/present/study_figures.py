"""Figures of the numerical studies: error against run time, and the stability map (with the data
of its points); each drawn from stored runs and saved with its provenance."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from rodimpact.analysis.stability_study import MAP_CLASSES, enforced_limit_line, map_frame  # noqa: E402
from rodimpact.analysis.work_precision import levels_in, quantities  # noqa: E402
from rodimpact.present.figures import METHOD_LABELS, save_figure, save_figure_of_runs  # noqa: E402
from rodimpact.present.inputs import one_case  # noqa: E402
from rodimpact.present.study_tables import STUDY_QUANTITY_WORDS, levels_and_orders  # noqa: E402
from rodimpact.present.table import write_csv  # noqa: E402
from rodimpact.present.words import case_in_words  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402
from rodimpact.storage.runs import read_run  # noqa: E402
from rodimpact.storage.sidecar import provenance_record, write_provenance  # noqa: E402

__all__ = [
    "make_stability_map",
    "make_work_precision_figure",
    "order_text",
    "plot_stability_map",
    "plot_work_precision",
    "quantity_words",
]

_COLORS = {name: spec.color for name, spec in METHODS.items()}
#: Markers of the methods, in the registry's order.
_MARKERS = ("o", "s", "^", "D", "v", "P")
#: The slope guide lies this factor below the first fitted level's error.
_GUIDE_OFFSET = 0.35
#: The error axis reaches this factor below the smallest error: room for each panel's box of orders.
_LEGEND_ROOM = 10.0**3


def quantity_words(quantity: str) -> str:
    """An error quantity of the work-precision table in words, as a figure sets them (the table's
    words, :data:`~rodimpact.present.study_tables.STUDY_QUANTITY_WORDS`, with L2 as mathtext)."""
    return STUDY_QUANTITY_WORDS.get(quantity, quantity.replace("_", " ")).replace("L2", "$L_2$")


def order_text(order: float) -> str:
    """An order as printed: a fraction where it is one with a denominator up to 4 (1.5 -> 3/2,
    1.667 -> 5/3, 2 -> 2), else two significant digits; an en dash for none."""
    if not np.isfinite(order):
        return "–"
    fraction = Fraction(float(order)).limit_denominator(4)
    if abs(float(fraction) - order) < 5e-3:
        return f"{fraction.numerator}" if fraction.denominator == 1 else f"{fraction.numerator}/{fraction.denominator}"
    return f"{order:.2g}"


def _legend_text(order: pd.Series | None) -> str:
    """``observed ± standard error (expected)`` of one method and quantity; for a method with no
    order stated and a three-level uncertainty, that uncertainty (GCI, or half the range)."""
    if order is None:
        return "–"
    if not np.isfinite(order.expected_order) and np.isfinite(order.get("gci_pct", np.nan)):
        return f"GCI {order.gci_pct:.2g} %"
    if not np.isfinite(order.expected_order) and np.isfinite(order.get("u_osc_pct", np.nan)):
        return f"half range {order.u_osc_pct:.2g} %"
    observed = f"{order.observed_order:.2f} ± {order.order_stderr:.2f}" if np.isfinite(order.observed_order) else "–"
    expected = order_text(order.expected_order) if np.isfinite(order.expected_order) else "none"
    return f"{observed} ({expected})"


def _slope_guide(
    ax: matplotlib.axes.Axes,
    time: np.ndarray,
    err: np.ndarray,
    h: np.ndarray,
    fitted: np.ndarray,
    order: float,
    color: str,
) -> None:
    """A dashed segment under the fitted levels: over their wall times it falls as h^order would
    over their refinement, labelled with the order."""
    first, last = np.flatnonzero(fitted)[[0, -1]]
    x = np.array([time[first], time[last]])
    y = _GUIDE_OFFSET * err[first] * np.array([1.0, (h[last] / h[first]) ** order])
    ax.loglog(x, y, color=color, linestyle=(0, (4, 2)), linewidth=0.9, alpha=0.9)
    ax.annotate(
        f"$h^{{{order_text(order)}}}$",
        (np.sqrt(x[0] * x[1]), np.sqrt(y[0] * y[1])),
        xytext=(-2, -3),
        textcoords="offset points",
        ha="right",
        va="top",
        fontsize=6.5,
        color=color,
    )


def plot_work_precision(
    frame: pd.DataFrame, orders: pd.DataFrame, case_id: str, title: str = ""
) -> matplotlib.figure.Figure:
    """Log-log relative error against wall time of one case: one panel per error quantity, one
    line per method.

    All panels share their axes. The wall time is the best of the repeated solves (the least
    disturbed by the other jobs on the machine). Levels in the fit of the observed order are
    filled, the others open. Under each method's fitted levels a dashed slope guide falls as
    h^p would over their refinement, p the method's expected order. Each panel's small legend
    gives each method's observed order with its standard error and the expected order (a dash:
    none stated, or fewer than three levels in the asymptotic range); the figure's legend names
    the methods once and the markers.

    Parameters
    ----------
    frame : DataFrame
        :func:`rodimpact.analysis.work_precision.work_precision_frame`.
    orders : DataFrame
        :func:`rodimpact.analysis.work_precision.observed_orders` of ``frame``.
    case_id : str
        The case drawn.
    title : str
        The case in words (the figure's title).
    """
    data = frame[frame["case_id"] == case_id]
    fitted_of = orders[orders["case_id"] == case_id].set_index(["method", "quantity"])
    rank = {m: i for i, m in enumerate(METHODS)}
    methods = sorted(dict.fromkeys(data["method"]), key=lambda m: rank.get(m, len(rank)))
    drawn = [q for q in quantities(frame) if np.any(data[f"err_{q}"].to_numpy(float) > 0)]
    cols = min(len(drawn), 3 if len(drawn) <= 9 else 4)
    rows = -(-len(drawn) // cols)
    fig, axes = plt.subplots(
        rows,
        cols,
        figsize=(3.1 * cols + 0.3, 2.6 * rows + 1.1),
        sharex=True,
        sharey=True,
        squeeze=False,
        layout="constrained",
    )
    handles = {}
    for ax, quantity in zip(axes.flat, drawn):
        for index, method in enumerate(methods):
            rows_of = data[data["method"] == method].sort_values("resolution_value")
            err = rows_of[f"err_{quantity}"].to_numpy(float)
            keep = np.isfinite(err) & (err > 0)
            if not keep.any():
                continue
            order = fitted_of.loc[(method, quantity)] if (method, quantity) in fitted_of.index else None
            in_fit = rows_of["level"].isin(levels_in(order.fitted_levels) if order is not None else ()).to_numpy()
            time, color = rows_of["wall_time_min_s"].to_numpy(float), _COLORS.get(method, "k")
            marker = _MARKERS[index % len(_MARKERS)]
            ax.loglog(time[keep], err[keep], color=color, linewidth=1.0)
            for filled in (True, False):
                pick = keep & (in_fit == filled)
                ax.loglog(
                    time[pick],
                    err[pick],
                    linestyle="none",
                    marker=marker,
                    markersize=3.8,
                    color=color,
                    markerfacecolor=color if filled else "white",
                    markeredgewidth=0.9,
                )
            ax.plot([], [], color=color, marker=marker, markersize=3.8, linewidth=1.0, label=_legend_text(order))
            handles.setdefault(
                METHOD_LABELS.get(method, method),
                Line2D([], [], color=color, marker=marker, markersize=3.8, linewidth=1.0),
            )
            if order is not None and in_fit.sum() >= 3 and np.isfinite(order.expected_order):
                _slope_guide(
                    ax,
                    time,
                    err,
                    1.0 / rows_of["resolution_value"].to_numpy(float),
                    in_fit & keep,
                    float(order.expected_order),
                    color,
                )
        ax.set_title(quantity_words(quantity), fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(
            title="order: observed ± s.e. (expected)",
            fontsize=6.5,
            title_fontsize=6.5,
            loc="best",
            framealpha=0.85,
            handlelength=1.0,
            handletextpad=0.4,
            borderpad=0.3,
            labelspacing=0.2,
        )
    for ax in list(axes.flat)[len(drawn) :]:
        ax.set_visible(False)
    errors = data[[f"err_{q}" for q in drawn]].to_numpy(float)
    low, high = np.min(errors[errors > 0]), np.max(errors[np.isfinite(errors)])
    axes[0, 0].set_ylim(low / _LEGEND_ROOM, 3.0 * high)  # room below the lines for each panel's box
    for j in range(cols):  # the lowest panel of each column carries the time axis
        lowest = [axes[i, j] for i in range(rows) if i * cols + j < len(drawn)][-1]
        lowest.set_xlabel("wall time of one solve (s)")
        lowest.xaxis.set_tick_params(labelbottom=True)
    for i in range(rows):
        axes[i, 0].set_ylabel("relative error")
    handles["level in the fit"] = Line2D([], [], color="0.3", marker="o", markersize=3.8, linestyle="none")
    handles["level not in the fit"] = Line2D(
        [], [], color="0.3", marker="o", markersize=3.8, linestyle="none", markerfacecolor="white"
    )
    handles["expected order (slope guide)"] = Line2D([], [], color="0.3", linestyle=(0, (4, 2)), linewidth=0.9)
    fig.legend(
        list(handles.values()),
        list(handles),
        loc="outside lower center",
        ncol=min(len(handles), 4),
        fontsize=8,
        frameon=False,
    )
    fig.suptitle(f"Error against run time: {title}" if title else "Error against run time", fontsize=10)
    return fig


def plot_stability_map(frame: pd.DataFrame, steps_per_contact: int, accuracy: float) -> matplotlib.figure.Figure:
    """Where each SEM scheme is stable and accurate at one step, over mass and rod impedance.

    One panel per method; on the paper scheme's panel the line is its enforced limit (h = 2 Z / k_c
    at the rigid-rod Hertz approach): below the line (small Z) its step is beyond the limit and
    the scheme is refused unless asked. The implicit scheme has no such limit.
    """
    methods = list(dict.fromkeys(frame["method"]))
    fig, axes = plt.subplots(
        1, len(methods), figsize=(5.2 * len(methods), 5.2), sharey=True, squeeze=False, layout="constrained"
    )
    line = enforced_limit_line(frame)
    masses, limit = line["mass_kg"].to_numpy(float), line["z_crit"].to_numpy(float)
    styles = {
        MAP_CLASSES[0]: ("o", "C2"),
        MAP_CLASSES[1]: ("s", "C1"),
        MAP_CLASSES[2]: ("X", "C3"),
        MAP_CLASSES[3]: ("d", "0.6"),
    }
    for ax, method in zip(axes[0], methods):
        rows = frame[frame["method"] == method]
        for cls, (marker, color) in styles.items():
            pick = rows[rows["class"] == cls]
            ax.scatter(
                pick["mass_kg"], pick["impedance_kg_s"], marker=marker, color=color, s=40, label=f"{cls} ({len(pick)})"
            )
        if getattr(METHODS[method].options(), "scheme", None) == "paper":
            floor = 0.5 * float(frame["impedance_kg_s"].min())
            ax.loglog(
                masses, limit, "k--", linewidth=1, label=r"stability limit $h = 2Z/k_c(\alpha_H)$; shaded: unstable"
            )
            ax.fill_between(masses, np.maximum(limit, floor), floor, color="0.85", alpha=0.6, lw=0, zorder=0)
            ax.set_ylim(bottom=floor)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("impactor mass $m$ (kg)")
        ax.set_title(f"{METHOD_LABELS.get(method, method)}\n{steps_per_contact} steps per Hertz time", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False)
    axes[0][0].set_ylabel(r"rod impedance $Z = S\sqrt{E\rho}$ (kg/s)")
    fig.suptitle(
        f"Stability map: accurate = contact time (against the reference) and energy balance within {accuracy:g}",
        fontsize=10,
    )
    return fig


def make_work_precision_figure(
    runs: Sequence[str | Path], study: Mapping[str, Any], *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """Error against wall time for one case (:func:`plot_work_precision`; the study's levels and
    orders: :func:`~rodimpact.present.study_tables.levels_and_orders`): every method and quantity,
    the observed and expected orders in the legends, a slope guide of the expected order, the
    fitted levels filled; with its sidecar."""
    records, frame, orders = levels_and_orders(runs, study)
    case = one_case(records, "a work-precision figure")
    fig = plot_work_precision(frame, orders, case, title=case_in_words(records[0].config))
    save_figure_of_runs(
        fig, records, pdf=pdf, png=png, provenance=provenance, title=f"Error against run time, case {case}"
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
    """The stability map: the data of its points (CSV) and the figure (:func:`plot_stability_map`)."""
    records = [read_run(p) for p in runs]
    refs = {r.config["row"]: r for r in (read_run(p) for p in references)}
    frame = map_frame(records, refs, float(spec["accuracy"]))
    write_csv(frame, csv)
    fig = plot_stability_map(frame, int(spec["steps_per_contact"]), float(spec["accuracy"]))
    prov = provenance_record([*records, *refs.values()], [csv, pdf, png])
    save_figure(fig, pdf=pdf, png=png, provenance=prov, title="Stability map of the SEM schemes")
    write_provenance(provenance, [*records, *refs.values()], [csv, pdf, png])
