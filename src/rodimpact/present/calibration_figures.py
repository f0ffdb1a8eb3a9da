"""A calibration's figure: each measurement's error, fitted and held out, and the constants
within their bounds (:func:`plot_calibration`)."""

from __future__ import annotations

import textwrap

import matplotlib

matplotlib.use("Agg")  # headless: the workflow's figures never open a window

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

__all__ = ["plot_calibration"]


def plot_calibration(
    constants: pd.DataFrame, measurements: pd.DataFrame, title: str, verdict: str
) -> matplotlib.figure.Figure:
    """Left: each measurement's error in % of the measured value, by the model at the start
    (crosses), by the fitted model (filled) and by the fit made without its case (open:
    leave-one-out), one row per case and quantity; below a dashed line, the cases predicted at
    the fitted constants without being fitted (triangles, with two standard errors).
    Right: each constant's fitted value with two standard errors, against its bounds (scaled to
    0-1 of the bounds' width; the start marked).

    Parameters
    ----------
    constants, measurements : DataFrame
        :func:`rodimpact.present.calibration_tables.calibration_frames`.
    title : str
        The fit's heading ("A fit, not a prediction: ...").
    verdict : str
        Its status and warnings, printed under the title.
    """
    rows = len(measurements)
    labels = [
        textwrap.fill(f"{case}: {words.split(' (')[0]}", 60)
        for case, words in zip(measurements["case_words"], measurements["quantity_words"], strict=True)
    ]
    fig, (left, right) = plt.subplots(
        1,
        2,
        figsize=(11.5, 2.6 + 0.1 * sum(label.count("\n") + 3 for label in labels) + 0.4 * len(constants)),
        width_ratios=(3, 2),
        layout="constrained",
    )
    y = np.arange(rows)[::-1]
    left.axvline(0.0, color="0.5", lw=0.8)
    fitted = (measurements["role"] == "fitted").to_numpy()
    left.plot(measurements["start_error_pct"], y, "x", color="0.45", label="model at the start")
    left.plot(measurements["residual_pct"][fitted], y[fitted], "o", color="C0", label="fitted model (in sample)")
    left.plot(
        measurements["held_out_error_pct"][fitted],
        y[fitted],
        "o",
        mfc="none",
        color="C3",
        label="fit without this case (held out)",
    )
    if not fitted.all():
        left.errorbar(
            measurements["residual_pct"][~fitted],
            y[~fitted],
            xerr=2.0 * (100.0 * measurements["fitted_standard_error"] / measurements["measured"].abs())[~fitted],
            fmt="^",
            color="C2",
            capsize=3,
            label="not fitted, predicted (± 2 standard errors)",
        )
        left.axhline(y[fitted].min() - 0.5, color="0.7", lw=0.8, ls="--")
    left.set_yticks(y, labels, fontsize=7.5)
    left.set_xlabel("error against the measurement (%)")
    left.grid(alpha=0.3, axis="x")
    left.legend(fontsize=7.5, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, frameon=False)
    yc = np.arange(len(constants))[::-1]
    width = (constants["high"] - constants["low"]).to_numpy(float)
    low = constants["low"].to_numpy(float)
    value = (constants["value"].to_numpy(float) - low) / width
    error = 2.0 * constants["standard_error"].to_numpy(float) / width
    start = (constants["start"].to_numpy(float) - low) / width
    right.errorbar(
        value,
        yc,
        xerr=np.where(np.isfinite(error), error, 0.0),
        fmt="o",
        color="C0",
        capsize=4,
        label="fitted ± 2 standard errors",
    )
    right.plot(start, yc, "|", color="0.3", ms=14, label="start")
    right.set_xlim(-0.05, 1.05)
    right.set_ylim(-0.8, len(constants) - 0.2)
    right.set_yticks(
        yc,
        [
            textwrap.fill(f"{p} = {v:.4g} ± {s:.2g} {u}".rstrip(), 34, break_long_words=False)
            for p, v, s, u in zip(
                constants["parameter"], constants["value"], constants["standard_error"], constants["unit"], strict=True
            )
        ],
        fontsize=7.5,
    )
    right.yaxis.tick_right()
    right.set_xlabel("within the bounds (0 least, 1 largest)")
    right.grid(alpha=0.3, axis="x")
    right.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, frameon=False)
    fig.suptitle(textwrap.fill(title, 90) + "\n" + textwrap.fill(verdict, 120), fontsize=8.5)
    return fig
