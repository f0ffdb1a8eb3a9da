"""The waves, drawn: the axial strain over the whole rod against time (output ``strain_field``).

One panel per run of a case that stored the field (``sem`` through d'Alembert's solution,
``fem1d`` from its bar), side by side on one colour scale: time across, the distance from the
struck end up. Over the map, the paths of the wave fronts that leave the struck end when a
contact starts (solid) and when it ends (dashed), reflected at both ends
(:func:`rodimpact.analysis.waves.characteristic`), and the contact intervals as a bar along
the struck end. Everything drawn is read from the stored runs (the field, the contact
intervals and the wave speed in the summary).
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.colors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from rodimpact.analysis.waves import characteristic  # noqa: E402
from rodimpact.solvers.registry import METHODS  # noqa: E402
from rodimpact.storage.runs import RunRecord, read_run  # noqa: E402
from rodimpact.storage.sidecar import provenance_record, write_provenance  # noqa: E402

__all__ = ["make_wave_map", "plot_wave_map"]

log = logging.getLogger(__name__)

#: The map's colours: compression (negative strain) blue, tension red, zero white.
_CMAP = "RdBu_r"
_FRONT = {"color": "0.1", "linewidth": 0.7}


def _with_field(records: Sequence[RunRecord]) -> list[RunRecord]:
    """The runs that stored the field, in the registry's order of their methods."""
    rank = {name: index for index, name in enumerate(METHODS)}
    return sorted((r for r in records if "strain" in r.field), key=lambda r: rank.get(r.method, len(rank)))


def plot_wave_map(records: Sequence[RunRecord], title: str = "") -> matplotlib.figure.Figure:
    """The strain over the rod against time, one panel per run, on one colour scale.

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of one case; those with a stored field (``strain``, ``time``, ``x``) are drawn,
        each with ``wave_speed_m_s``, ``contact_start_s`` and ``contact_end_s`` in its summary.
    title : str
        The figure's title.

    Raises
    ------
    ValueError
        No run has a field.
    """
    runs = _with_field(records)
    if not runs:
        raise ValueError("runs: none stored the strain field (output strain_field)")
    limit = 100.0 * max(float(np.max(np.abs(r.field["strain"]))) for r in runs)
    norm = matplotlib.colors.Normalize(-limit, limit)
    fig, axes = plt.subplots(
        1, len(runs), figsize=(3.6 * len(runs) + 1.2, 4.3), sharey=True, layout="constrained", squeeze=False
    )
    for ax, run in zip(axes[0], runs):
        mesh = _panel(ax, run, norm)
    axes[0][0].set_ylabel("distance from the struck end $x$ (m)")
    bar = fig.colorbar(mesh, ax=list(axes[0]), shrink=0.9, pad=0.02)
    bar.set_label(r"axial strain $\varepsilon = \partial u / \partial x$ (%)")
    formatter = matplotlib.ticker.ScalarFormatter(useMathText=True)
    formatter.set_powerlimits((-3, 4))  # a small strain's ticks as multiples of a power of ten
    bar.formatter = formatter
    handles = [
        Line2D([], [], linestyle="-", **_FRONT),
        Line2D([], [], linestyle="--", **_FRONT),
        Line2D([], [], color="k", linewidth=4.0, solid_capstyle="butt"),
    ]
    labels = [
        "wave front from the start of a contact, reflected at both ends",
        "wave front from the end of a contact",
        "contact",
    ]
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def _panel(ax: matplotlib.axes.Axes, run: RunRecord, norm: matplotlib.colors.Normalize):
    """One run's map, its fronts and its contacts; returns the map (for the colour bar)."""
    t_us, x = 1e6 * run.field["time"], run.field["x"]
    mesh = ax.pcolormesh(
        t_us, x, 100.0 * run.field["strain"].T, cmap=_CMAP, norm=norm, shading="nearest", rasterized=True
    )
    length, speed, t_end = float(x[-1]), float(run.summary["wave_speed_m_s"]), float(run.field["time"][-1])
    starts = np.atleast_1d(run.summary["contact_start_s"])
    ends = np.atleast_1d(run.summary["contact_end_s"])
    for times, style in ((starts, "-"), (ends, "--")):
        for t0 in times:
            t, path = characteristic(float(t0), length, speed, t_end)
            ax.plot(1e6 * t, path, linestyle=style, **_FRONT)
    for t0, t1 in zip(starts, ends):
        ax.plot([1e6 * t0, 1e6 * t1], [0.0, 0.0], color="k", linewidth=4.0, solid_capstyle="butt", clip_on=False)
    ax.set_xlim(t_us[0], t_us[-1])
    ax.set_ylim(0.0, length)
    ax.set_xlabel("time $t$ (µs)")
    ax.set_title(METHODS[run.method].label if run.method in METHODS else run.method, fontsize=9)
    return mesh


def _title(config: dict) -> str:
    """The figure's title in words: what it shows, then the case's description and its rod."""
    rod = config["rod"]
    words = f"rod {1000 * float(rod['length_m']):.3g} mm long, far end {rod['far_end']}"
    description = str(config.get("description") or "").strip()
    return (
        f"Axial strain along the rod against time\n{description}; {words}"
        if description
        else (f"Axial strain along the rod against time\n{words[0].upper()}{words[1:]}")
    )


def make_wave_map(runs: Sequence[str | Path], *, pdf: str | Path, png: str | Path, provenance: str | Path) -> None:
    """The strain map of one case from its runs that stored the field, with its provenance.

    Parameters
    ----------
    runs : sequence of path
        Run files of one case (those without a field are left out).
    pdf, png, provenance : path
        The figure (PDF, PNG; provenance in their metadata) and its provenance sidecar.
    """
    from rodimpact.present.figures import save_figure

    records = _with_field([read_run(p) for p in runs])
    cases = sorted({r.case_id for r in records})
    if len(cases) != 1:
        raise ValueError(f"runs: the wave map shows one case's stored fields, got cases {cases}")
    fig = plot_wave_map(records, title=_title(records[0].config))
    save_figure(
        fig,
        pdf=pdf,
        png=png,
        provenance=provenance_record(records, [pdf, png]),
        title="The waves in the rod: axial strain against time and position",
    )
    write_provenance(provenance, records, [pdf, png])
    log.info("wave map of %s: %d panels (%s)", cases[0], len(records), ", ".join(r.method for r in records))
