"""The studies' tables, from stored runs: the work-precision table (every level, data) and its
observed orders, and the stability table (raising on a silent wrong answer). Each table for
people is declared here once, its columns beside its frame (:mod:`rodimpact.present.table`).
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from rodimpact.analysis.stability_study import StudyViolation, stability_frame, violations
from rodimpact.analysis.work_precision import ORDER_TOLERANCE, observed_orders, work_precision_frame
from rodimpact.present.columns import shared
from rodimpact.present.table import Column, Table, TableArtifact, panels, write_csv, write_table
from rodimpact.storage.runs import RunRecord, read_run
from rodimpact.storage.sidecar import write_provenance

__all__ = [
    "STUDY_QUANTITY_WORDS",
    "levels_and_orders",
    "make_stability",
    "make_work_precision",
    "orders_table",
    "stability_table",
]

log = logging.getLogger(__name__)

#: The error quantities of the error-against-run-time study, in words (a table's ``quantity``).
STUDY_QUANTITY_WORDS = {
    "contact_time": "contact time",
    "history_l2": "force history, L2 norm",
    "history_max": "force history, max norm",
    **{
        f"max_{k}": f"{ordinal} force maximum"
        for k, ordinal in enumerate(
            ("first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth"), start=1
        )
    },
}

#: The orders table's columns.
_ORDERS = (
    *shared(["case_id", "method", "monotone"]),
    Column("quantity", "Quantity", fmt="", words=STUDY_QUANTITY_WORDS),
    Column("expected_order", "Expected order", fmt=".3g"),
    Column("observed_order", "Observed order"),
    Column("order_stderr", "Standard error", fmt=".2f"),
    Column("fitted_levels", "Fitted levels", fmt=""),
    Column("sign_change", "Sign change", fmt=""),
    Column("within_expected", f"Within {ORDER_TOLERANCE:g} of expected", fmt=""),
    Column("asymptotic", "Asymptotic", fmt=""),
    Column("arrival_offset", "Offset from a wave arrival (of 2L/c)", fmt=".3f"),
    Column("gci_order", "GCI order"),
    Column("gci_pct", "GCI", "%", ".3f"),
    Column("oscillatory", "Oscillatory", fmt=""),
    Column("u_osc_pct", "Oscillatory half range", "%", ".3f"),
)


def orders_table(orders: pd.DataFrame, fit_levels: int) -> Table:
    """The observed orders (:func:`rodimpact.analysis.work_precision.observed_orders`), a panel per case."""
    table = Table(
        orders,
        _ORDERS,
        f"Orders of convergence: expected (from the scheme and the solution's regularity; none "
        f"stated: a dash) and observed (log-log fit of the error against h = 1/resolution on the "
        f"finest {fit_levels} levels whose error exceeds 10x the reference's, with its standard "
        f"error); whether the errors fall at every fitted level and whether their signs change "
        f"there; whether the order is within {ORDER_TOLERANCE:g} of the expected one; and, for a "
        f"method measured against its own finest level, the grid convergence index of its finest "
        f"three levels (safety factor 1.25) or, where they oscillate, half their range.",
    )
    return table.showing(
        panels(
            table,
            "Orders of convergence",
            ["case_id", "method", "quantity"],
            [
                "expected_order",
                "observed_order",
                "order_stderr",
                "fitted_levels",
                "monotone",
                "sign_change",
                "within_expected",
                "asymptotic",
                "gci_order",
                "gci_pct",
                "oscillatory",
                "u_osc_pct",
            ],
            by="case_id",
        )
    )


def levels_and_orders(
    runs: Sequence[str | Path], study: Mapping[str, Any]
) -> tuple[list[RunRecord], pd.DataFrame, pd.DataFrame]:
    """The error-against-run-time study's levels (their runs read), their table
    (:func:`~rodimpact.analysis.work_precision.work_precision_frame`) and the observed orders
    (:func:`~rodimpact.analysis.work_precision.observed_orders`); ``study``: its ``methods``
    (each one's settings), ``fit_levels``, ``arrival_window`` and ``per_case``
    (config.yaml ``work_precision``)."""
    records = [read_run(p) for p in runs]
    frame = work_precision_frame(records, study["methods"])
    orders = observed_orders(
        frame,
        study["methods"],
        study["fit_levels"],
        arrival_window=study["arrival_window"],
        per_case=study.get("per_case"),
    )
    return records, frame, orders


def make_work_precision(
    runs: Sequence[str | Path],
    study: Mapping[str, Any],
    *,
    csv: str | Path,
    orders_csv: str | Path,
    orders_md: str | Path,
    provenance: str | Path,
    orders_html: str | Path | None = None,
) -> None:
    """The work-precision table (every level: data, CSV only), and the orders (:func:`orders_table`):
    expected, observed with the fit's standard error, the levels fitted, monotone or not, and the
    three-level uncertainty of a method that is its own reference by its finest level
    (:func:`levels_and_orders`)."""
    records, frame, orders = levels_and_orders(runs, study)
    write_csv(frame, csv)
    write_table(orders_table(orders, study["fit_levels"]), csv=orders_csv, md=orders_md, html=orders_html)
    write_provenance(provenance, records, [csv, orders_csv, orders_md, orders_html])
    log.info("work precision: %d runs, %d cases", len(records), frame["case_id"].nunique())


#: The stability table's columns.
_STABILITY = (
    *shared(["case_id", "method", "status", "n_contacts", "wall_time_s", "message"]),
    Column("success", "Success", fmt=""),
    Column("finite", "Finite", fmt=""),
    Column("min_force_N", "Smallest force", "N", ".3g"),
    Column("energy_error", "Energy error", fmt=".1e"),
    Column("energy_tolerance", "Energy tolerance", fmt=".0e"),
    Column("contact_time_s", "Contact time", "s", ".4e"),
    Column("reference_contact_time_s", "Reference contact time", "s", ".4e"),
    Column("contact_time_error", "Contact-time error", fmt=".1e"),
    Column("contact_time_tolerance", "Contact-time tolerance", fmt=".0e"),
    Column("contact_intervals_us", "Contact intervals", "µs", ""),
    Column("verdict", "Verdict", fmt=""),
)


def stability_table(frame: pd.DataFrame) -> Table:
    """Every stress run's verdict, its number of contacts, its errors (the tolerances are the
    method's, in the caption) and its wall time."""
    table = Table(
        frame,
        _STABILITY,
        "Stress cases: every method's result checked (finite, force >= 0, energy balance and first "
        "contact time within the method's stated tolerances against a sem reference at tolerance "
        "1e-8), or its failure message.",
    )
    return table.showing(
        panels(
            table,
            "Every stress run, checked",
            ["case_id", "method"],
            ["verdict", "n_contacts", "contact_time_error", "energy_error", "wall_time_s"],
        )
    )


def make_stability(
    runs: Sequence[str | Path], references: Sequence[str | Path], tolerances: Mapping[str, Mapping[str, float]]
) -> TableArtifact:
    """The stress runs checked against the stated tolerances (:func:`stability_table`); raises when
    one is a violation (a silent wrong answer), after logging the whole table.

    Raises
    ------
    StudyViolation
        A run neither met its tolerances nor failed clearly.
    """
    records = [read_run(p) for p in runs]
    refs = {r.case_id: r for r in (read_run(p) for p in references)}
    frame = stability_frame(records, refs, tolerances)
    bad = violations(frame)
    if bad:
        log.error("stability table:\n%s", frame.to_string())
        raise StudyViolation(
            "stability study: runs that neither met their tolerances nor failed clearly:\n  " + "\n  ".join(bad)
        )
    log.info(
        "stability: %d runs, %d ok, %d failed clearly",
        len(frame),
        (frame["verdict"] == "ok").sum(),
        frame["verdict"].str.startswith("failed").sum(),
    )
    return TableArtifact(stability_table(frame), [*records, *refs.values()])
