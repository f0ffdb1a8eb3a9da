"""The sensor's figure: the fit of its bond line, labelled as a fit; headless (Agg)."""

from __future__ import annotations

import logging
import textwrap
from collections.abc import Mapping
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import pandas as pd  # noqa: E402

__all__ = ["plot_sensor_fit"]

log = logging.getLogger(__name__)


def plot_sensor_fit(
    frame: pd.DataFrame, summary: Mapping[str, Any], descriptions: Mapping[str, str] | None = None
) -> matplotlib.figure.Figure:
    """Measured and computed contact time against ball mass: the sourced stack, the fitted one
    and (on the fitted reading) each row held out; one panel per reading.

    Parameters
    ----------
    frame, summary
        :func:`rodimpact.present.sensor_tables.sensor_fit_frame`'s table and summary.
    descriptions : mapping, optional
        Variant -> the reading in words (panel titles).
    """
    descriptions = dict(descriptions or {})
    variants = list(dict.fromkeys(frame["variant"]))
    fig, axes = plt.subplots(
        1, len(variants), figsize=(5.2 * len(variants), 4.6), squeeze=False, sharey=True, layout="constrained"
    )
    thickness = f"{summary['fitted_thickness_um']:.1f} ± {summary['standard_error_um']:.1f} µm"
    for ax, variant in zip(axes[0], variants):
        rows = frame[frame["variant"] == variant].sort_values("mass_g")
        fitted = bool((rows["role"] == "fitted").any())
        ax.plot(rows["mass_g"], rows["measured_us"], "s", color="k", ms=6, label="measured")
        ax.plot(
            rows["mass_g"],
            rows["nominal_us"],
            "-o",
            color="tab:green",
            ms=4,
            label="sensor as built, sourced constants (prediction, no fit)",
        )
        ax.plot(
            rows["mass_g"],
            rows["fitted_us"],
            "--D",
            color="tab:orange",
            ms=4,
            label=f"FIT: {summary['layer']} {thickness} (fitted on the left panel's reading)",
        )
        if fitted:
            ax.plot(
                rows["mass_g"],
                rows["held_out_us"],
                "o",
                mfc="none",
                color="tab:purple",
                ms=8,
                label="fit on the other rows, this row held out",
            )
        title = textwrap.fill(descriptions.get(variant, variant), 60)
        ax.set_title(f"{title}\n({'the fit' if fitted else 'the fitted stack applied'})", fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis in (ax.xaxis, ax.yaxis):  # plain numbers on the log axes (0.5, 1, 2; 40, 60, 100)
            axis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 3.0, 5.0)))
            axis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
            axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("ball mass $m$ (g)")
        ax.grid(alpha=0.3, which="both")
    axes[0][0].set_ylabel("contact time (µs)")
    handles: dict[str, Any] = {}
    for ax in axes[0]:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    fig.legend(list(handles.values()), list(handles), loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    fig.suptitle(
        f"A fit, not a prediction: the {summary['layer']}'s thickness from the measurements "
        f"(sourced range {summary['source_low_um']:.0f}–{summary['source_high_um']:.0f} µm)",
        fontsize=10,
    )
    return fig
