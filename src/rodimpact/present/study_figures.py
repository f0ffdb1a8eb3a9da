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

__all__ = ["plot_stability_map", "plot_work_precision"]

_COLORS = {name: spec.color for name, spec in METHODS.items()}
_MARKERS = {"contact_time": "o", "history_l2": "s", "history_max": "D"}
_LINES = {"contact_time": "-", "history_l2": ":", "history_max": "-."}


def plot_work_precision(frame: pd.DataFrame, orders: pd.DataFrame, case_id: str) -> matplotlib.figure.Figure:
    """Log-log relative error against wall time of one case: one line per method and quantity.

    The wall time is the best of the repeated solves (the least disturbed by the other job
    on the machine); the legend gives each line's observed order next to the theoretical
    one, or says that no level lies in the asymptotic range.
    """
    data = frame[frame["case_id"] == case_id]
    fitted = orders[orders["case_id"] == case_id].set_index(["method", "quantity"])
    fig, ax = plt.subplots(figsize=(8.0, 5.6))
    for method in dict.fromkeys(data["method"]):
        rows = data[data["method"] == method].sort_values("resolution_value")
        for quantity in quantities(frame):
            err = rows[f"err_{quantity}"].to_numpy(float)
            keep = np.isfinite(err) & (err > 0)
            if not keep.any():
                continue
            order = fitted.loc[(method, quantity)]
            observed = (f"order {order.observed_order:.2f}" if np.isfinite(order.observed_order)
                        else "no asymptotic range")
            label = f"{method}: {quantity.replace('_', ' ')} ({observed}, theory {order.theoretical_order:g})"
            marker = _MARKERS.get(quantity, "^")
            ax.loglog(rows["wall_time_min_s"].to_numpy(float)[keep], err[keep], color=_COLORS.get(method, "k"),
                      linestyle=_LINES.get(quantity, "--"), marker=marker, markersize=4, linewidth=1,
                      label=label)
    ax.set_xlabel("wall time of one solve, s (best of the repeats)")
    ax.set_ylabel("relative error against the reference")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)
    machine = next((m for m in data.get("machine", []) if m), "")
    ax.set_title(f"Error against run time, case {case_id!r}\n{machine}", fontsize=9)
    fig.tight_layout()
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
