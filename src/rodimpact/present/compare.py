"""A case set against its measurements: the table ``results/tables/compare_{set}.*`` and its summary.

Any case set whose cases carry ``measured`` values is compared the same way, whatever its
name. For each case (and variant) and each method that ran it, every measured quantity is set
against the computed one: the contact time, the peak force, the rebound velocity (positive away
from the rod) and with it the coefficient of restitution (its ratio to the impact velocity), and what
each record gives (:mod:`rodimpact.analysis.observations`): for a force history, the contact
time read from both signals and the errors of the force after alignment; for a strain at a
gauge, or the far end's velocity, the first pulse's arrival, peak and integral and the errors
after alignment; for the impactor's velocity, its errors. Errors are signed, in % of the
measured value: (computed - measured) / |measured|; a history's norms are errors already. Each
table is declared here once, its columns beside its frame (:mod:`rodimpact.present.table`).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.history_compare import HistoryComparison
from rodimpact.analysis.measured import RECORDS, MeasuredHistory, read_history
from rodimpact.analysis.observations import QUANTITY_ORDER, force_comparison, observed
from rodimpact.contact.laws import law_of
from rodimpact.model.problem import ImpactProblem
from rodimpact.present.columns import shared
from rodimpact.present.table import Column, Table, markdown_table, panels
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.runs import RunRecord

__all__ = [
    "COLUMNS",
    "X_AXES",
    "X_NAMES",
    "compare_frame",
    "compare_summary",
    "compare_table",
    "comparison_markdown",
    "history_comparison",
    "history_files",
    "model_label",
    "read_histories",
    "summary_table",
    "x_axis",
]


def model_label(config: Mapping[str, Any], method: str) -> str:
    """The model in words: the method, and for a method that takes a contact law, the law
    (the thin-layer film law is an approximation, and a reader must see which law drew a line)."""
    spec = METHODS.get(method)
    if spec is None:
        return method
    if spec.contact != "law":
        return spec.label
    return f"{spec.label}; contact law: {law_of(config.get('contact')).label}"


def history_comparison(record: RunRecord, history: MeasuredHistory, threshold: float) -> HistoryComparison:
    """The run's contact force against the measured history (needs the run's ``contact_force``)."""
    try:
        return force_comparison(record.series, history, threshold)
    except KeyError as missing:
        raise ValueError(f"run {record.path}: {missing.args[0]}") from None


log = logging.getLogger(__name__)

#: The comparison table's columns, in order (each row: :func:`_row`).
COLUMNS = (
    "case_id",
    "row",
    "variant",
    "mass_g",
    "velocity_m_s",
    "diameter_mm",
    "rod_length_mm",
    "method",
    "method_label",
    "contact_law",
    "quantity",
    "quantity_words",
    "unit",
    "measured",
    "computed",
    "error_pct",
    "source",
    "warning",
)

#: A measurement past what the same law gives on a rigid wall by more than this fraction is
#: flagged: an elastic rod only lengthens the contact and lowers its peak (noise aside).
RIGID_MARGIN = 0.05


def rigid_wall_warnings(config: Mapping[str, Any]) -> dict[str, str]:
    """Measured values a case's own law cannot give on any elastic rod, quantity -> the warning.

    The same impact on a rigid wall through the case's contact law
    (:attr:`~rodimpact.model.problem.ImpactProblem.rigid_contact`) bounds what an elastic rod
    gives: the contact no shorter, the peak no higher. A measured contact time shorter than that
    bound, or a peak higher, by more than :data:`RIGID_MARGIN`, is legal but implausible: the
    measurement, its unit or the law is off. Empty when the law cannot be built here, and for a
    law that declares itself an approximation (its numbers bound nothing).
    """
    measured = config.get("measured") or {}
    try:
        problem = ImpactProblem.from_case(config)
    except (ArithmeticError, KeyError, TypeError, ValueError):
        return {}
    if problem.law.approximation:
        return {}
    rigid = problem.rigid_contact
    bound_us, warnings = 1e6 * rigid.contact_time_s, {}
    time = measured.get("contact_time_us")
    if time is not None and float(time) < (1.0 - RIGID_MARGIN) * bound_us:
        warnings["contact_time_us"] = (
            f"shorter than the {bound_us:.4g} µs the same law gives on a rigid wall: an elastic rod only "
            "lengthens the contact (the measurement, its unit or the law is off)"
        )
    peak = measured.get("peak_force_n")
    if peak is not None and float(peak) > (1.0 + RIGID_MARGIN) * rigid.peak_force_N:
        warnings["peak_force_n"] = (
            f"above the {rigid.peak_force_N:.4g} N the same law gives on a rigid wall: an elastic rod only "
            "lowers the peak (the measurement, its unit or the law is off)"
        )
    return warnings


def _row(
    config: Mapping[str, Any],
    method: str,
    quantity: str,
    words: str,
    unit: str,
    measured: float,
    computed: float,
    error_pct: float,
    warning: str | None = None,
) -> dict[str, Any]:
    return {
        "case_id": config["id"],
        "row": config.get("row", config["id"]),
        "variant": config.get("variant"),
        "mass_g": 1000.0 * float(config["impactor"]["mass_kg"]),
        "velocity_m_s": float(config["impactor"].get("velocity_m_s", math.nan)),
        "diameter_mm": 2000.0 * float(config["impactor"].get("radius_m", math.nan)),
        "rod_length_mm": 1000.0 * float(config.get("rod", {}).get("length_m", math.nan)),
        "method": method,
        "method_label": model_label(config, method),
        "contact_law": law_of(config.get("contact")).name,
        "quantity": quantity,
        "quantity_words": words,
        "unit": unit,
        "measured": measured,
        "computed": computed,
        "error_pct": error_pct,
        "source": str((config.get("measured") or {}).get("source", "")),
        "warning": warning,
    }


def compare_frame(
    records: Sequence[RunRecord], histories: Mapping[str, Mapping[str, MeasuredHistory]] | None = None
) -> pd.DataFrame:
    """One row per case, method and measured quantity (see the module docstring).

    Parameters
    ----------
    records : sequence of RunRecord
        Full runs (with series where a record is compared) of the set's measured cases.
    histories : mapping, optional
        Case id -> its records, read, by their key in the ``measured`` block.

    Returns
    -------
    DataFrame
        Columns :data:`COLUMNS`, sorted by mass, case, quantity and the registry's method order.
    """
    histories = dict(histories or {})
    rows = []
    for record in records:
        config = record.config
        warnings = rigid_wall_warnings(config)
        for key, text in warnings.items():
            log.warning("case %s: measured %s %s", record.case_id, key, text)
        # the bound is the law's: a method that resolves the contact itself does not take it
        bounded = METHODS[record.method].contact == "law"
        try:
            found = observed(config, record.series, record.summary, histories.get(record.case_id))
        except (KeyError, ValueError) as problem:
            raise ValueError(f"run {record.path}: {problem.args[0] if problem.args else problem}") from None
        for row in found:
            warning = warnings.get(row.quantity) if bounded else None
            rows.append(
                _row(
                    config,
                    record.method,
                    row.quantity,
                    row.words,
                    row.unit,
                    row.measured,
                    row.computed,
                    row.error_pct,
                    warning,
                )
            )
    frame = pd.DataFrame(rows, columns=list(COLUMNS))
    if frame.empty:
        return frame
    order = {m: k for k, m in enumerate(METHODS)}
    quantities = {q: k for k, q in enumerate(QUANTITY_ORDER)}
    frame = frame.assign(_m=frame["method"].map(order).fillna(len(order)), _q=frame["quantity"].map(quantities))
    return (
        frame.sort_values(["mass_g", "case_id", "_q", "_m"], kind="stable")
        .drop(columns=["_m", "_q"])
        .reset_index(drop=True)
    )


#: What a set's figure may draw its values against, in this order: the first that varies along
#: the set (frame column -> axis label).
X_AXES = {
    "mass_g": "impactor mass $m$ (g)",
    "velocity_m_s": "impact velocity $V_0$ (m/s)",
    "diameter_mm": "impactor diameter (mm)",
    "rod_length_mm": "rod length (mm)",
}
#: The names a case file's ``compare: {x: ...}`` gives them (workflow/schemas/cases.schema.yaml).
X_NAMES = {"mass": "mass_g", "velocity": "velocity_m_s", "diameter": "diameter_mm", "rod_length": "rod_length_mm"}


def x_axis(frame: pd.DataFrame, named: str | None = None) -> tuple[str, str]:
    """The column a set's figure is drawn against, and its label: the one ``named`` (a key of
    :data:`X_NAMES`, the set's ``compare.x``), else the first of :data:`X_AXES` that takes more
    than one value (the mass when nothing varies).

    Raises
    ------
    KeyError
        ``named`` is not a key of :data:`X_NAMES`.
    """
    if named is not None:
        column = X_NAMES[named]
        return column, X_AXES[column]
    for column, label in X_AXES.items():
        if column in frame and frame[column].nunique() > 1:
            return column, label
    return "mass_g", X_AXES["mass_g"]


def compare_summary(frame: pd.DataFrame) -> pd.DataFrame:
    """Per variant, model and quantity: the cases compared, the mean and max of |error|, the mean
    signed error, %."""
    keys = ["variant", "method", "method_label", "quantity", "quantity_words"]
    if frame.empty:
        return pd.DataFrame(
            columns=[*keys, "cases", "mean_abs_error_pct", "max_abs_error_pct", "mean_signed_error_pct"]
        )
    grouped = frame.groupby(keys, sort=False, dropna=False)["error_pct"]
    summary = grouped.agg(
        cases="count",
        mean_abs_error_pct=lambda e: float(np.mean(np.abs(e))),
        max_abs_error_pct=lambda e: float(np.max(np.abs(e))),
        mean_signed_error_pct="mean",
    ).reset_index()
    return summary


#: The comparison's own columns (the case's and the method's are shared).
_COMPARE_COLUMNS = (
    Column("quantity", "Quantity", fmt="", in_words="quantity_words"),
    Column("quantity_words", "Quantity", fmt=""),
    Column("unit", "Unit", fmt=""),
    Column("measured", "Measured", fmt=".5g"),
    Column("computed", "Computed", fmt=".5g"),
    Column("error_pct", "Error", "%"),
    Column("source", "Source", fmt=""),
)

_CAPTION = (
    "Measured against computed, per case, method and quantity: the measured value and its source, the "
    "computed value, and the error (computed − measured) / |measured| in %. A measured force history adds "
    "the contact time read from both signals at the history's threshold, and the L2 and max-norm errors "
    "of the computed force after the two are aligned where each first rises through that fraction of its "
    "peak. A strain at a gauge, or the far end's velocity, adds its first pulse's arrival (against x/c), "
    "peak and time integral, and the errors after the arrivals are aligned "
    '(config/README.md, "Comparing with your experiment").'
)


def compare_table(
    records: Sequence[RunRecord], histories: Mapping[str, Mapping[str, MeasuredHistory]], set_name: str
) -> Table:
    """The set's comparison (:func:`compare_frame`): for people, per quantity the models'
    measured, computed and error, a panel per variant; a warning column only where a
    measurement is flagged (:func:`rigid_wall_warnings`)."""
    frame = compare_frame(records, histories)
    table = Table(
        frame,
        (
            *shared(["case_id", "row", "variant", "mass_g", "velocity_m_s", "diameter_mm", "rod_length_mm"]),
            *shared(["method", "method_label", "contact_law", "warning"]),
            *_COMPARE_COLUMNS,
        ),
        _CAPTION,
    )
    values = ["method_label", "measured", "computed", "error_pct"]
    if frame["warning"].notna().any():
        values.append("warning")
    return table.showing(
        panels(
            table,
            f"Set {set_name} against its measurements",
            ["row", "quantity_words", "unit"],
            values,
            by="variant" if frame["variant"].notna().any() else "",
        )
    )


def summary_table(frame: pd.DataFrame) -> Table:
    """Per variant, model and quantity (:func:`compare_summary` of a comparison's frame)."""
    return Table(
        compare_summary(frame),
        (
            *shared(["variant", "method", "method_label"]),
            *_COMPARE_COLUMNS[:2],
            Column("cases", "Cases", fmt=""),
            Column("mean_abs_error_pct", "Mean |error|", "%"),
            Column("max_abs_error_pct", "Largest |error|", "%"),
            Column("mean_signed_error_pct", "Mean signed error", "%"),
        ),
        "Per method and quantity: the cases compared, the mean and the largest |error|, and the mean signed error (%).",
    )


def read_histories(records: Sequence[RunRecord]) -> dict[str, dict[str, MeasuredHistory]]:
    """Case id -> its records, read, by their key in the ``measured`` block."""
    out: dict[str, dict[str, MeasuredHistory]] = {}
    for record in records:
        measured = record.config.get("measured") or {}
        if record.case_id in out:
            continue
        found = {key: read_history(measured[key]["path"], measured[key], key) for key in RECORDS if measured.get(key)}
        if found:
            out[record.case_id] = found
    return out


def history_files(records: Sequence[RunRecord]) -> list[str]:
    """The measured records' files of the runs' cases."""
    return sorted(
        {spec["path"] for r in records for key in RECORDS if (spec := (r.config.get("measured") or {}).get(key))}
    )


def comparison_markdown(table: Table, totals: Table) -> str:
    """The comparison's Markdown: its caption and table, then its summary's caption and table."""
    return f"{table.caption}\n\n{markdown_table(table)}\n\n{totals.caption}\n\n{markdown_table(totals)}\n"
