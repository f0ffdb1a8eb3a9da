"""The table of a set's parameter sweeps: every point's swept values, its ball, its contact time
and force, from the points' stored runs only. Declared here once, its columns beside its frame."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from rodimpact.analysis.signals import first_contact_maxima
from rodimpact.present.columns import COLUMNS, shared
from rodimpact.present.inputs import load_records
from rodimpact.present.table import Column, Table, TableArtifact, panels
from rodimpact.storage.runs import RunRecord

__all__ = ["make_sweep_table", "sweep_results_frame", "sweep_table"]

#: The columns of every sweep table (a sweep adds one per swept parameter, :data:`SWEPT`).
FIXED = (
    *shared(["row", "variant", "method", "mass_g", "diameter_mm", "velocity_m_s", "rod_length_mm"]),
    *shared(["contact_time_us", "n_contacts"]),
    Column("sweep", "Sweep", fmt=""),
    Column("first_peak_force_N", "First force maximum", "N", ".4g"),
    Column("max_force_N", "Largest force maximum", "N", ".4g"),
)
#: Every parameter a sweep may vary (:data:`rodimpact.analysis.sweeps.SWEEP_PARAMETERS`), as its
#: column in SI units.
SWEPT = {
    c.name: c
    for c in (
        Column("ball_diameter_m", "Ball diameter", "m", ".5f"),
        Column("mass_kg", "Impactor mass", "kg", ".4g"),
        Column("radius_m", "Nose radius", "m", ".4g"),
        COLUMNS["velocity_m_s"],
        Column("rod_length_m", "Rod length", "m", ".4g"),
        COLUMNS["film_modulus_pa"],
        Column("film_poisson_ratio", "Film Poisson's ratio", fmt=".3g"),
        Column("film_thickness_m", "Film thickness", "m", ".3g"),
    )
}


def sweep_results_frame(records: Sequence[RunRecord]) -> pd.DataFrame:
    """One row per sweep point and method: the swept values and the computed contact.

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of sweep points (their config has ``sweep_point``: parameter -> value, and
        ``sweep_of``: the sweep case's id).

    Returns
    -------
    DataFrame
        Columns ``sweep`` (the sweep case's id), ``row`` (its id without the variant),
        ``variant, method``, one column per swept parameter (SI units),
        ``mass_g, diameter_mm, velocity_m_s, rod_length_mm, contact_time_us`` (first
        contact), ``first_peak_force_N``, ``max_force_N`` (largest in the first contact),
        ``n_contacts``, sorted by sweep, method and mass.
    """
    rows = []
    for rec in records:
        config, summary = rec.config, rec.summary
        maxima = first_contact_maxima(
            summary["peak_time_s"], summary["peak_force_N"], summary.get("contact_end_s", np.empty(0))
        )
        rows.append(
            {
                "sweep": config["sweep_of"],
                "row": config.get("row"),
                "variant": config.get("variant"),
                "method": rec.method,
                **{f"{name}": float(value) for name, value in (config.get("sweep_point") or {}).items()},
                "mass_g": 1000.0 * config["impactor"]["mass_kg"],
                "diameter_mm": 2000.0 * config["impactor"]["radius_m"],
                "velocity_m_s": config["impactor"]["velocity_m_s"],
                "rod_length_mm": 1000.0 * config["rod"]["length_m"],
                "contact_time_us": 1e6 * float(summary["contact_time_s"]),
                "first_peak_force_N": float(maxima[0]) if len(maxima) else math.nan,
                "max_force_N": float(np.max(maxima)) if len(maxima) else math.nan,
                "n_contacts": int(summary.get("n_contacts", 1)),
            }
        )
    frame = pd.DataFrame(rows)
    if frame.empty:
        return frame
    return frame.sort_values(["sweep", "method", "mass_g"], kind="stable").reset_index(drop=True)


def sweep_table(records: Sequence[RunRecord]) -> Table:
    """Every sweep point (:func:`sweep_results_frame`): for people, the swept values (other than
    the ball's diameter, shown in mm), the ball, the contact time, the largest force and the
    number of contacts; each row named by its reading (by its sweep when a reading has several)
    and by its method when there are several."""
    frame = sweep_results_frame(records)
    fixed = {c.name for c in FIXED}
    swept = [c for c in frame.columns if c not in fixed]
    table = Table(
        frame,
        (*FIXED, *(SWEPT[c] for c in swept if c != "velocity_m_s")),
        "Parameter sweeps: contact time (first contact, µs) and force maxima (N) at every point.",
    )
    shown = [c for c in swept if c != "ball_diameter_m" and frame[c].notna().any()]
    one_per_reading = frame.empty or frame.groupby("variant")["sweep"].nunique().max() == 1
    key = ["variant" if one_per_reading else "sweep", *(["method"] if frame["method"].nunique() > 1 else [])]
    return table.showing(
        panels(
            table,
            "Every sweep point",
            key,
            [*shown, "diameter_mm", "mass_g", "contact_time_us", "max_force_N", "n_contacts"],
        )
    )


def make_sweep_table(runs: Sequence[str | Path], threads: int = 1) -> TableArtifact:
    """Every sweep point's contact time and force (:func:`sweep_table`), from the points' runs,
    read by up to ``threads`` processes (:func:`~rodimpact.present.inputs.load_records`)."""
    records = load_records(runs, workers=threads)
    return TableArtifact(sweep_table(records), records)
