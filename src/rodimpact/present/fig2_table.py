"""Fig. 2's numbers: the contact time and every force maximum of the model case per method, their
differences from a reference method, and the paper's own FEM-SEM differences beside them.
Declared here once, its columns beside its frame."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.errors import relative_error_pct
from rodimpact.analysis.signals import first_contact_maxima
from rodimpact.present.columns import method_header, shared
from rodimpact.present.inputs import load_records
from rodimpact.present.readings import methods_of
from rodimpact.present.table import Column, Table, TableArtifact, panels
from rodimpact.storage.runs import RunRecord

__all__ = ["comparison_frame", "comparison_table", "make_comparison"]

_ORDINALS = ("1st", "2nd", "3rd")


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
    for method in methods_of(records):
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
        row[f"contact_time_vs_{reference}_pct"] = relative_error_pct(tc, ref_tc)
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


def _maximum(i: int) -> Column:
    """The ``i``-th force maximum of the first contact, kN: ``max_{i}_kN``."""
    return Column(f"max_{i}_kN", f"{_ORDINALS[i - 1] if i <= len(_ORDINALS) else f'{i}th'} maximum", "kN", ".3f")


def comparison_table(records: Sequence[RunRecord], reference: str = "sem") -> Table:
    """Fig. 2's numbers (:func:`comparison_frame`) against ``reference``."""
    frame = comparison_frame(records, reference)
    maxima = sorted((c for c in frame.columns if c.startswith("max_")), key=lambda c: int(c.split("_")[1]))
    versus = [f"contact_time_vs_{reference}_pct", f"maxima_vs_{reference}_pct"]
    header = method_header(reference)
    table = Table(
        frame,
        (
            *shared(["case_id", "method", "contact_time_us"]),
            Column("n_maxima", "Maxima", fmt=""),
            *(_maximum(int(c.split("_")[1])) for c in maxima),
            Column(versus[0], f"Contact time vs {header}", "%", ".3f"),
            Column(versus[1], f"Maxima vs {header}", "%", ".3f"),
            Column("paper_fem_vs_sem_contact_time_pct", "Paper FEM vs SEM, contact time", "%", ".0f"),
            Column("paper_fem_vs_sem_extrema_pct", "Paper FEM vs SEM, extrema", "%", ".0f"),
        ),
        "Fig. 2, case 'model': contact time (µs) and force maxima (kN) of the first contact "
        "per method; differences from our SEM (%), next to the paper's FEM-SEM differences (%).",
    )
    return table.showing(
        panels(
            table, "Fig. 2 in numbers: the first contact per method", ["method"], ["contact_time_us", *maxima, *versus]
        )
    )


def make_comparison(runs: Sequence[str | Path]) -> TableArtifact:
    """Fig. 2's numbers (:func:`comparison_table`) from the model case's runs: contact time and
    each maximum per method, differences from the SEM, and the paper's 11 % and 9 % beside them."""
    records = load_records(runs)
    return TableArtifact(comparison_table(records), records)
