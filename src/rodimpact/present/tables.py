"""Tables built from stored runs only (never from a solver): Table 2 and its summaries.

Errors follow the paper (docs/paper-notes.md, "Table 2"): |model - measured| / measured, in %.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.signals import first_contact_maxima
from rodimpact.present.table_formats import Panel, html_tables, latex_tables, markdown_table
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.runs import RunRecord, read_summary

__all__ = [
    "METHOD_ORDER",
    "comparison_frame",
    "load_records",
    "sweep_results_frame",
    "table2_frame",
    "variants_summary",
    "write_table",
]

log = logging.getLogger(__name__)

#: Column order of our methods in every table: the registry's.
METHOD_ORDER = tuple(METHODS)


def load_records(paths: Iterable[str | Path]) -> list[RunRecord]:
    """Read the summaries (and verified configs) of stored runs."""
    return [read_summary(p) for p in paths]


def _methods(records: Sequence[RunRecord]) -> list[str]:
    present = {r.method for r in records}
    return [m for m in METHOD_ORDER if m in present] + sorted(present - set(METHOD_ORDER))


def _error_pct(model: float, measured: float | None) -> float:
    if measured is None or not math.isfinite(model):
        return math.nan
    return abs(model - measured) / measured * 100.0


def _published(config: dict[str, Any], family: str, key: str) -> float:
    block = (config.get("published") or {}).get(family) or {}
    value = block.get(key)
    return math.nan if value is None else float(value)


def table2_frame(records: Sequence[RunRecord]) -> pd.DataFrame:
    """One row per case (ball), sorted by mass: measured, published and our contact times.

    Parameters
    ----------
    records : sequence of RunRecord
        Runs of the cases of one geometry variant, any methods (several per case).

    Returns
    -------
    DataFrame
        Columns ``case_id, row, variant, diameter_mm, mass_g, measured_us,
        published_fem_us, published_sem_us, published_fem_error_pct,
        published_sem_error_pct`` (the published columns only when a case declares
        ``published``), then ``{method}_us, {method}_error_pct`` for each method present, and
        ``sem_vs_published_sem_pct`` when ``sem`` is present (and published).
    """
    by_case: dict[str, dict[str, RunRecord]] = {}
    for rec in records:
        by_case.setdefault(rec.case_id, {})[rec.method] = rec
    methods = _methods(records)
    rows = []
    for case_id, runs in by_case.items():
        config = next(iter(runs.values())).config
        measured = (config.get("measured") or {}).get("contact_time_us")
        row: dict[str, Any] = {
            "case_id": case_id,
            "row": config.get("row", case_id),
            "variant": config.get("variant"),
            "diameter_mm": 2000.0 * config["impactor"]["radius_m"],
            "mass_g": 1000.0 * config["impactor"]["mass_kg"],
            "measured_us": math.nan if measured is None else float(measured),
            "published_fem_us": _published(config, "fem", "contact_time_us"),
            "published_sem_us": _published(config, "sem", "contact_time_us"),
            "published_fem_error_pct": _published(config, "fem", "error_pct"),
            "published_sem_error_pct": _published(config, "sem", "error_pct"),
        }
        for method in methods:
            rec = runs.get(method)
            ours = math.nan if rec is None else 1e6 * float(rec.summary["contact_time_s"])
            row[f"{method}_us"] = ours
            row[f"{method}_error_pct"] = _error_pct(ours, measured)
        if "sem" in methods:
            row["sem_vs_published_sem_pct"] = (row["sem_us"] / row["published_sem_us"] - 1.0) * 100.0
        rows.append(row)
    frame = pd.DataFrame(rows)
    if not any(rec.config.get("published") for rec in records):  # no case declares the paper's results
        frame = frame.drop(columns=[c for c in frame.columns if "published" in c])
    return frame.sort_values("mass_g", kind="stable").reset_index(drop=True)


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


def variants_summary(
    frames: dict[str, pd.DataFrame], readings: Mapping[str, Mapping[str, Any]] | None = None
) -> pd.DataFrame:
    """Per variant and method: mean, max and mean signed error against the measurements,
    next to the paper's own errors for the same family of method (SEM or FEM) when a case
    declares them (else no ``paper_*`` columns).

    Parameters
    ----------
    frames : dict
        Variant name -> :func:`table2_frame` of that variant.
    readings : mapping, optional
        Variant -> ``{"film": bool, "contact_law": str}``: given, the columns ``film`` and
        ``contact_law`` follow ``variant``.
    """
    rows = []
    for variant, frame in frames.items():
        reading = (
            {}
            if readings is None
            else {"film": bool(readings[variant]["film"]), "contact_law": str(readings[variant]["contact_law"])}
        )
        measured = frame["measured_us"].to_numpy(float)
        for column in frame.columns:
            if not column.endswith("_us") or column.startswith(("measured", "published")):
                continue
            method = column[: -len("_us")]
            family = METHODS[method].family if method in METHODS else None
            ours = frame[column].to_numpy(float)
            signed = (ours - measured) / measured * 100.0
            published = f"published_{family}_error_pct"
            paper = frame[published].to_numpy(float) if family and published in frame else np.array([np.nan])
            rows.append(
                {
                    "variant": variant,
                    **reading,
                    "method": method,
                    "n_cases": int(np.sum(np.isfinite(signed))),
                    "mean_error_pct": float(np.nanmean(np.abs(signed))),
                    "max_error_pct": float(np.nanmax(np.abs(signed))),
                    "mean_signed_error_pct": float(np.nanmean(signed)),
                    "paper_method": family or "",
                    "paper_mean_error_pct": float(np.nanmean(paper)),
                    "paper_max_error_pct": float(np.nanmax(paper)),
                }
            )
    summary = pd.DataFrame(rows)
    if not any("published_fem_us" in frame for frame in frames.values()):
        summary = summary.drop(columns=[c for c in summary.columns if c.startswith("paper_")])
    return summary


def _first_contact_maxima(rec: RunRecord) -> np.ndarray:
    summary = rec.summary
    return first_contact_maxima(summary["peak_time_s"], summary["peak_force_N"], summary["contact_end_s"])


def comparison_frame(records: Sequence[RunRecord], reference: str = "sem") -> pd.DataFrame:
    """Contact time and every force maximum of one case, per method, with each method's
    relative difference from ``reference`` and the paper's published FEM-SEM differences.

    Returns
    -------
    DataFrame
        Columns ``method, contact_time_us, n_maxima, max_1_kN, ..., contact_time_vs_{ref}_pct,
        maxima_vs_{ref}_pct`` (largest |difference| over the maxima, NaN when the numbers of
        maxima differ), ``paper_fem_vs_sem_contact_time_pct, paper_fem_vs_sem_extrema_pct``.
    """
    by_method = {r.method: r for r in records}
    if reference not in by_method:
        raise ValueError(f"records: no run of the reference method {reference!r}")
    ref = by_method[reference]
    ref_tc, ref_max = float(ref.summary["contact_time_s"]), _first_contact_maxima(ref)
    published = (ref.config.get("published") or {}).get("fem_vs_sem") or {}
    rows = []
    for method in _methods(records):
        rec = by_method[method]
        tc, maxima = float(rec.summary["contact_time_s"]), _first_contact_maxima(rec)
        row: dict[str, Any] = {
            "case_id": rec.case_id,
            "method": method,
            "contact_time_us": 1e6 * tc,
            "n_maxima": len(maxima),
        }
        for i, value in enumerate(maxima, start=1):
            row[f"max_{i}_kN"] = 1e-3 * value
        row[f"contact_time_vs_{reference}_pct"] = (tc / ref_tc - 1.0) * 100.0
        row[f"maxima_vs_{reference}_pct"] = (
            float(np.max(np.abs(maxima / ref_max - 1.0))) * 100.0 if len(maxima) == len(ref_max) else math.nan
        )
        row["paper_fem_vs_sem_contact_time_pct"] = published.get("contact_time_difference_pct", math.nan)
        row["paper_fem_vs_sem_extrema_pct"] = published.get("extrema_difference_pct", math.nan)
        rows.append(row)
    frame = pd.DataFrame(rows)
    maxima_columns = sorted((c for c in frame.columns if c.startswith("max_")), key=lambda c: int(c.split("_")[1]))
    head = ["case_id", "method", "contact_time_us", "n_maxima", *maxima_columns]
    return frame[head + [c for c in frame.columns if c not in head]]


def write_table(
    frame: pd.DataFrame,
    *,
    csv: str | Path,
    md: str | Path | None = None,
    html: str | Path | None = None,
    tex: str | Path | None = None,
    caption: str = "",
    views: Sequence[Panel] | None = None,
) -> None:
    """Write a table: the CSV with every column at full precision (machine names), and for
    people, each optional: Markdown (every column, rounded, headers in words with units, after
    ``caption``), and the panels ``views`` as HTML tables (for the report) and as LaTeX tables
    (each with its caption and label). Headers, units and rounding: :mod:`.columns`. A table
    with no rows (no panels) says so in each format.

    Raises
    ------
    ValueError
        ``html`` or ``tex`` is asked for without ``views``.
    """
    if (html is not None or tex is not None) and views is None:
        raise ValueError("write_table: HTML and LaTeX show panels: give views")
    with atomic_output(csv) as tmp:
        frame.to_csv(tmp, index=False, float_format="%.10g")
    if md is not None:
        _write_text(md, (f"{caption}\n\n" if caption else "") + markdown_table(frame) + "\n")
    if html is not None:
        _write_text(html, html_tables(frame, views))
    if tex is not None:
        _write_text(tex, latex_tables(frame, views))


def _write_text(path: str | Path, text: str) -> None:
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
