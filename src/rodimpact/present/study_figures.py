"""Figures of the numerical studies: error against wall time, and the stability map."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from rodimpact.analysis.stability_study import MAP_CLASSES, enforced_limit_line  # noqa: E402
from rodimpact.analysis.work_precision import quantities  # noqa: E402
from rodimpact.present.figures import METHOD_LABELS  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402

__all__ = ["plot_stability_map", "plot_work_precision", "quantity_words"]

_COLORS = {name: spec.color for name, spec in METHODS.items()}
#: Markers of the methods, in the registry's order.
_MARKERS = ("o", "s", "^", "D", "v", "P")
_ORDINALS = {1: "first", 2: "second", 3: "third", 4: "fourth", 5: "fifth", 6: "sixth", 7: "seventh",
             8: "eighth", 9: "ninth"}


def quantity_words(quantity: str) -> str:
    """An error quantity of the work-precision table in words (``max_2`` -> ``second force maximum``)."""
    if quantity.startswith("max_") and quantity[4:].isdigit():
        k = int(quantity[4:])
        return f"{_ORDINALS.get(k, f'{k}th')} force maximum"
    return {"contact_time": "contact time", "history_l2": "force history, $L_2$ norm",
            "history_max": r"force history, max norm"}.get(quantity, quantity.replace("_", " "))


def _quantity_rank(quantity: str) -> tuple[int, int]:
    """Contact time, the maxima in order, then the histories."""
    if quantity == "contact_time":
        return (0, 0)
    if quantity.startswith("max_") and quantity[4:].isdigit():
        return (1, int(quantity[4:]))
    return (2, ("history_l2", "history_max").index(quantity) if quantity in ("history_l2", "history_max") else 9)


def plot_work_precision(frame: pd.DataFrame, orders: pd.DataFrame, case_id: str,
                        title: str = "") -> matplotlib.figure.Figure:
    """Log-log relative error against wall time of one case: one panel per error quantity, one
    line per method.

    All panels share their axes. The wall time is the best of the repeated solves (the least
    disturbed by the other jobs on the machine). Each panel's small legend gives each method's
    observed order next to the theoretical one (a dash: no level lies in the asymptotic range);
    the figure's legend names the methods once.

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
    fitted = orders[orders["case_id"] == case_id].set_index(["method", "quantity"])
    rank = {m: i for i, m in enumerate(METHODS)}
    methods = sorted(dict.fromkeys(data["method"]), key=lambda m: rank.get(m, len(rank)))
    drawn = sorted((q for q in quantities(frame) if np.any(data[f"err_{q}"].to_numpy(float) > 0)), key=_quantity_rank)
    cols = min(len(drawn), 3 if len(drawn) <= 9 else 4)
    rows = -(-len(drawn) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.1 * cols + 0.3, 2.6 * rows + 1.0), sharex=True, sharey=True,
                             squeeze=False, layout="constrained")
    handles = {}
    for ax, quantity in zip(axes.flat, drawn):
        for index, method in enumerate(methods):
            rows_of = data[data["method"] == method].sort_values("resolution_value")
            err = rows_of[f"err_{quantity}"].to_numpy(float)
            keep = np.isfinite(err) & (err > 0)
            if not keep.any():
                continue
            order = fitted.loc[(method, quantity)] if (method, quantity) in fitted.index else None
            observed = (f"{order.observed_order:.2f}" if order is not None and np.isfinite(order.observed_order)
                        else "–")
            theory = f" ({order.theoretical_order:g})" if order is not None else ""
            (line,) = ax.loglog(rows_of["wall_time_min_s"].to_numpy(float)[keep], err[keep],
                                color=_COLORS.get(method, "k"), marker=_MARKERS[index % len(_MARKERS)],
                                markersize=3.5, linewidth=1.0, label=f"{observed}{theory}")
            handles.setdefault(METHOD_LABELS.get(method, method), line)
        ax.set_title(quantity_words(quantity), fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(title="order (theory)", fontsize=6.5, title_fontsize=6.5, loc="best", framealpha=0.85,
                  handlelength=1.6, borderpad=0.3, labelspacing=0.25)
    for ax in list(axes.flat)[len(drawn):]:
        ax.set_visible(False)
    for j in range(cols):  # the lowest panel of each column carries the time axis
        lowest = [axes[i, j] for i in range(rows) if i * cols + j < len(drawn)][-1]
        lowest.set_xlabel("wall time of one solve (s)")
        lowest.xaxis.set_tick_params(labelbottom=True)
    for i in range(rows):
        axes[i, 0].set_ylabel("relative error")
    fig.legend(list(handles.values()), list(handles), loc="outside lower center", ncol=min(len(handles), 4),
               fontsize=8, frameon=False)
    fig.suptitle(f"Error against run time: {title}" if title else "Error against run time", fontsize=10)
    return fig


def plot_stability_map(frame: pd.DataFrame, steps_per_contact: int, accuracy: float) -> matplotlib.figure.Figure:
    """Where each SEM scheme is stable and accurate at one step, over mass and rod impedance.

    One panel per method; on the paper scheme's panel the line is its enforced limit (h = 2 Z / k_c
    at the rigid-rod Hertz approach): below the line (small Z) its step is beyond the limit and
    the scheme is refused unless asked. The implicit scheme has no such limit.
    """
    methods = list(dict.fromkeys(frame["method"]))
    fig, axes = plt.subplots(1, len(methods), figsize=(5.2 * len(methods), 5.2), sharey=True, squeeze=False,
                             layout="constrained")
    line = enforced_limit_line(frame)
    masses, limit = line["mass_kg"].to_numpy(float), line["z_crit"].to_numpy(float)
    styles = {MAP_CLASSES[0]: ("o", "C2"), MAP_CLASSES[1]: ("s", "C1"), MAP_CLASSES[2]: ("X", "C3"),
              MAP_CLASSES[3]: ("d", "0.6")}
    for ax, method in zip(axes[0], methods):
        rows = frame[frame["method"] == method]
        for cls, (marker, color) in styles.items():
            pick = rows[rows["class"] == cls]
            ax.scatter(pick["mass_kg"], pick["impedance_kg_s"], marker=marker, color=color, s=40,
                       label=f"{cls} ({len(pick)})")
        if getattr(METHODS[method].options(), "scheme", None) == "paper":
            floor = 0.5 * float(frame["impedance_kg_s"].min())
            ax.loglog(masses, limit, "k--", linewidth=1,
                      label=r"stability limit $h = 2Z/k_c(\alpha_H)$; shaded: unstable")
            ax.fill_between(masses, np.maximum(limit, floor), floor, color="0.85", alpha=0.6, lw=0, zorder=0)
            ax.set_ylim(bottom=floor)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("impactor mass $m$ (kg)")
        ax.set_title(f"{METHOD_LABELS.get(method, method)}\n{steps_per_contact} steps per Hertz time", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False)
    axes[0][0].set_ylabel(r"rod impedance $Z = S\sqrt{E\rho}$ (kg/s)")
    fig.suptitle(f"Stability map: accurate = contact time (against the reference) and energy balance "
                 f"within {accuracy:g}", fontsize=10)
    return fig
