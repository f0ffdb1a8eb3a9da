"""The studies' artifacts from stored runs: the work-precision table with the observed orders
and its figure, the stability table (raising on a silent wrong answer) and the stability map.

The figure modules (matplotlib) are imported by the functions that draw, so that a table's job
does not load them.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rodimpact.analysis.stability_study import StudyViolation, map_frame, stability_frame, violations
from rodimpact.analysis.work_precision import ORDER_TOLERANCE, observed_orders, work_precision_frame
from rodimpact.present.artifact_common import _one_case, _outputs, _save_figure, case_in_words
from rodimpact.present.table_views import orders_views, stability_views
from rodimpact.present.tables import write_table
from rodimpact.storage.runs import read_run
from rodimpact.storage.sidecar import provenance_record, write_provenance

__all__ = ["make_stability", "make_stability_map", "make_work_precision", "make_work_precision_figure"]

log = logging.getLogger(__name__)

WORK_PRECISION_CAPTION = (
    "Error against run time: relative errors of each method's levels against the reference (the "
    "Richardson extrapolation of the reference method's finest two levels; ref_err_* is its own "
    "error estimate), wall time of one solve (median of the repeats) on the machine named."
)


def make_work_precision(
    runs: Sequence[str | Path],
    methods: Mapping[str, Any],
    fit_levels: int,
    *,
    arrival_window: float,
    csv: str | Path,
    orders_csv: str | Path,
    orders_md: str | Path,
    provenance: str | Path,
    orders_html: str | Path | None = None,
    per_case: Mapping[str, Any] | None = None,
) -> None:
    """The work-precision table, and the orders: expected, observed with the fit's standard
    error, the levels fitted, monotone or not, and the three-level uncertainty of a method that
    is its own reference by its finest level (config.yaml ``work_precision``)."""
    records = [read_run(p) for p in runs]
    frame = work_precision_frame(records, methods)
    orders = observed_orders(frame, methods, fit_levels, arrival_window=arrival_window, per_case=per_case)
    write_table(frame, csv=csv)
    write_table(
        orders,
        csv=orders_csv,
        md=orders_md,
        html=orders_html,
        views=orders_views(orders),
        caption=(
            f"Orders of convergence: expected (from the scheme and the solution's regularity; none "
            f"stated: a dash) and observed (log-log fit of the error against h = 1/resolution on the "
            f"finest {fit_levels} levels whose error exceeds 10x the reference's, with its standard "
            f"error); whether the errors fall at every fitted level and whether their signs change "
            f"there; whether the order is within {ORDER_TOLERANCE:g} of the expected one; and, for a "
            f"method measured against its own finest level, the grid convergence index of its finest "
            f"three levels (safety factor 1.25) or, where they oscillate, half their range."
        ),
    )
    write_provenance(provenance, records, _outputs(csv, orders_csv, orders_md, orders_html))
    log.info("work precision: %d runs, %d cases", len(records), frame["case_id"].nunique())


def make_work_precision_figure(
    runs: Sequence[str | Path],
    methods: Mapping[str, Any],
    fit_levels: int,
    *,
    arrival_window: float,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
    per_case: Mapping[str, Any] | None = None,
) -> None:
    """Error against wall time for one case: every method and quantity, the observed and
    expected orders in the legends, a slope guide of the expected order, the fitted levels filled."""
    from rodimpact.present.study_figures import plot_work_precision

    records = [read_run(p) for p in runs]
    case = _one_case(records, "a work-precision figure")
    frame = work_precision_frame(records, methods)
    orders = observed_orders(frame, methods, fit_levels, arrival_window=arrival_window, per_case=per_case)
    fig = plot_work_precision(frame, orders, case, title=case_in_words(records[0].config))
    _save_figure(fig, records, pdf=pdf, png=png, provenance=provenance, title=f"Error against run time, case {case}")


def make_stability(
    runs: Sequence[str | Path],
    references: Sequence[str | Path],
    tolerances: Mapping[str, Mapping[str, float]],
    *,
    csv: str | Path,
    md: str | Path,
    provenance: str | Path,
    html: str | Path | None = None,
) -> None:
    """The stress runs checked against the stated tolerances; raises when one is a violation
    (a silent wrong answer), after logging the whole table."""
    records = [read_run(p) for p in runs]
    refs = {r.case_id: r for r in (read_run(p) for p in references)}
    frame = stability_frame(records, refs, tolerances)
    bad = violations(frame)
    if bad:
        log.error("stability table:\n%s", frame.to_string())
        raise StudyViolation(
            "stability study: runs that neither met their tolerances nor failed clearly:\n  " + "\n  ".join(bad)
        )
    write_table(
        frame,
        csv=csv,
        md=md,
        html=html,
        views=stability_views(frame),
        caption=(
            "Stress cases: every method's result checked (finite, force >= 0, energy balance and first "
            "contact time within the method's stated tolerances against a sem reference at tolerance "
            "1e-8), or its failure message."
        ),
    )
    write_provenance(provenance, [*records, *refs.values()], _outputs(csv, md, html))
    log.info(
        "stability: %d runs, %d ok, %d failed clearly",
        len(frame),
        (frame["verdict"] == "ok").sum(),
        frame["verdict"].str.startswith("failed").sum(),
    )


def make_stability_map(
    runs: Sequence[str | Path],
    references: Sequence[str | Path],
    spec: Mapping[str, Any],
    *,
    csv: str | Path,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
) -> None:
    """The stability map: the table of its points and the figure."""
    from rodimpact.present.figures import save_figure
    from rodimpact.present.study_figures import plot_stability_map

    records = [read_run(p) for p in runs]
    refs = {r.config["row"]: r for r in (read_run(p) for p in references)}
    frame = map_frame(records, refs, float(spec["accuracy"]))
    write_table(frame, csv=csv)
    fig = plot_stability_map(frame, int(spec["steps_per_contact"]), float(spec["accuracy"]))
    prov = provenance_record([*records, *refs.values()], [csv, pdf, png])
    save_figure(fig, pdf=pdf, png=png, provenance=prov, title="Stability map of the SEM schemes")
    write_provenance(provenance, [*records, *refs.values()], [csv, pdf, png])
