"""Figures of the sensor film, built from stored runs only; headless (Agg)."""

from __future__ import annotations

import logging
from collections.abc import Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rodimpact.present.figures import METHOD_LABELS, METHOD_ORDER  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402
from rodimpact.storage.runs import RunRecord  # noqa: E402

__all__ = ["FILM_STYLES", "film_words", "plot_film_force"]

log = logging.getLogger(__name__)

#: Line style of a run without and with the film (the method gives the colour).
FILM_STYLES = {False: "-", True: "--"}


def film_words(config: dict) -> str:
    """``with film`` or ``no film``, from a run's case."""
    return "with film" if (config.get("contact") or {}).get("film") is not None else "no film"


def _first_contact_s(rec: RunRecord) -> float:
    """When the run's first contact starts, s (0 when the summary does not say)."""
    start = np.atleast_1d(rec.summary.get("contact_start_s", [0.0]))
    return float(start[0]) if len(start) else 0.0


def plot_film_force(records: Sequence[RunRecord], rows: Sequence[str], title: str = "") -> matplotlib.figure.Figure:
    """The contact force P(t) with and without the film, one panel per Table 2 row.

    Parameters
    ----------
    records : sequence of RunRecord
        Runs with the ``contact_force`` series; each is drawn on the panel of its case's ``row``,
        coloured by method (the registry's colour) and dashed when its case has the film.
    rows : sequence of str
        The rows, one panel each, in this order.
    title : str
        The figure's title.

    Raises
    ------
    ValueError
        A row has no run, or a run has no ``contact_force``.
    """
    rank = {m: i for i, m in enumerate(METHOD_ORDER)}
    fig, axes = plt.subplots(1, len(rows), figsize=(5.2 * len(rows), 4.6), squeeze=False, layout="constrained")
    for ax, row in zip(axes[0], rows):
        runs = [r for r in records if r.config.get("row") == row]
        if not runs:
            raise ValueError(f"records: no run of row {row!r}")
        runs.sort(key=lambda r: (rank.get(r.method, len(rank)), film_words(r.config) == "with film"))
        end_us = 0.0
        for rec in runs:
            if "contact_force" not in rec.series:
                raise ValueError(f"{rec.path}: no contact_force series (add it to the case's outputs)")
            start_s = _first_contact_s(rec)
            t_us = 1e6 * (np.asarray(rec.series["time"], float) - start_s)
            film = film_words(rec.config)
            spec = METHODS.get(rec.method)
            # a method that takes the contact from a law takes the film as a thin layer: an approximation
            words = (
                f"{film}, thin-layer law: an approximation"
                if film == "with film" and spec and spec.contact == "law"
                else film
            )
            ax.plot(
                t_us,
                rec.series["contact_force"],
                FILM_STYLES[film == "with film"],
                lw=1.3,
                color=spec.color if spec else None,
                label=f"{METHOD_LABELS.get(rec.method, rec.method)} ({words}): "
                f"{1e6 * float(rec.summary['contact_time_s']):.1f} µs",
            )
            ends = np.atleast_1d(rec.summary.get("contact_end_s", [rec.summary["contact_time_s"]]))
            end_us = max(end_us, 1e6 * (float(ends[-1]) - start_s))
        imp = runs[0].config["impactor"]
        ax.set_title(f"ball {2000.0 * imp['radius_m']:.2f} mm, {1000.0 * imp['mass_kg']:.2f} g", fontsize=10)
        ax.set_xlabel("time from the first contact $t$ (µs)")
        ax.set_ylabel("contact force $P$ (N)")
        ax.set_xlim(0, 1.05 * end_us if end_us > 0 else None)
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=1, frameon=False)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig
