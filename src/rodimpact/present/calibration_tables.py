"""A set's calibration, presented: its tables and its figure, from its HDF5 file only
(:mod:`rodimpact.storage.calibrations`, which holds numbers, ids and units: the cases and the
quantities are put in words here). Labelled throughout as what it is: a fit, not a
prediction. The fitted model's errors are in-sample; the held-out predictions (each case's
measurements predicted by the fit without that case) are the estimate of how the calibrated
model would predict a new test. A fit the data cannot identify, or one held at a bound, says
so in the tables' ``warning`` column, in their captions and in the figure's title. Each table
is declared here once, its columns beside its frame (:mod:`rodimpact.present.table`).
"""

from __future__ import annotations

import logging
import math
import textwrap
from collections.abc import Mapping
from html import escape
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.errors import relative_error_pct
from rodimpact.analysis.observations import quantity_words
from rodimpact.present.columns import shared
from rodimpact.present.table import Column, Table, html_tables, markdown_table, panels, write_csv
from rodimpact.present.words import case_in_words
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.calibrations import StoredCalibration, read_calibration
from rodimpact.storage.sidecar import write_provenance

__all__ = ["FIT_LABEL", "calibration_frames", "calibration_tables", "make_calibration_artifacts"]

log = logging.getLogger(__name__)

#: What every artifact of a calibration says it is.
FIT_LABEL = "A fit, not a prediction"


def _verdict(stored: StoredCalibration) -> str:
    """The fit's status and warnings in one paragraph."""
    scalars, warnings = stored.scalars, list(stored.described["warnings"])
    verdict = f"Status: {scalars['status']} ({scalars['message']})."
    if not scalars["identifiable"]:
        verdict += " The data do not identify these constants: do not use the values."
    if warnings:
        verdict += " " + " ".join(warnings)
    return verdict


def _mean_abs(values: pd.Series) -> str:
    """The mean of |values| (%, finite ones) in words, "not available" without any."""
    finite = np.abs(values.to_numpy(float))
    finite = finite[np.isfinite(finite)]
    return f"{finite.mean():.3g} %" if finite.size else "not available"


def _measurements(
    role: str,
    rows: list[dict],
    cases: Mapping[str, Mapping[str, Any]],
    measured: np.ndarray,
    start: np.ndarray,
    fitted: np.ndarray,
    standard_error: np.ndarray | float,
    error_pct: np.ndarray,
    held_out: dict | None = None,
) -> pd.DataFrame:
    """The measurements of one role (:func:`calibration_frames`): a norm's row shows its value as
    its error, and has no measured value; each case and quantity in words (``cases``: case id ->
    the resolved case; a quantity's words without the wave's transit, which the fit varies)."""
    norm = np.asarray([r["norm"] for r in rows], bool)
    held = held_out or {"held_out_predicted": math.nan, "held_out_error_pct": math.nan, "held_out_status": None}
    if held_out:
        held = {**held, "held_out_error_pct": np.where(norm, held["held_out_predicted"], held["held_out_error_pct"])}
    return pd.DataFrame(
        {
            "role": role,
            "case_id": [r["case"] for r in rows],
            "case_words": [case_in_words(cases[r["case"]]) for r in rows],
            "quantity": [r["quantity"] for r in rows],
            "quantity_words": [quantity_words(r["quantity"], cases[r["case"]], transit=False) for r in rows],
            "unit": [r["unit"] for r in rows],
            "measured": np.where(norm, math.nan, measured),
            "start_predicted": start,
            "start_error_pct": np.where(norm, start, relative_error_pct(start, measured)),
            "fitted": fitted,
            "fitted_standard_error": standard_error,
            "residual_pct": np.where(norm, fitted, error_pct),
            **held,
        }
    )


def calibration_frames(stored: StoredCalibration) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The constants' table and the measurements' table of a stored calibration.

    Returns
    -------
    (DataFrame, DataFrame)
        Per constant: ``parameter, unit, low, high, source, start, value, standard_error,
        relative_standard_error_pct, correlation, at_bound, warning``. Per measurement, the
        fitted ones, then those predicted at the fitted constants (``apply_to``): ``role``
        (``fitted`` or ``applied``), ``case_id, case_words, quantity, quantity_words, unit, measured,
        start_predicted`` (the model at the start), ``start_error_pct, fitted`` (at the fitted
        constants), ``fitted_standard_error`` (of an applied prediction, from the constants'
        covariance), ``residual_pct`` (the error at the fitted constants: in sample for a
        fitted row), ``held_out_predicted, held_out_error_pct, held_out_status`` (fitted rows).
    """
    a, params = stored.arrays, stored.described["parameters"]
    cases = {case["id"]: case for case in [*stored.config.get("cases", []), *stored.config.get("applied", [])]}
    names = [p["path"] for p in params]
    warning = "; ".join(stored.described["warnings"]) or None
    constants = pd.DataFrame(
        {
            "parameter": names,
            "unit": [p["unit"] for p in params],
            "low": a["low"],
            "high": a["high"],
            "source": [p["source"] for p in params],
            "start": a["start"],
            "value": a["values"],
            "standard_error": a["standard_errors"],
            "relative_standard_error_pct": 100.0 * a["standard_errors"] / np.abs(a["values"]),
            "correlation": [
                ", ".join(f"{other}: {a['correlation'][j, k]:+.2f}" for k, other in enumerate(names) if k != j) or "–"
                for j in range(len(names))
            ],
            "at_bound": a["at_bound"].astype(bool),
            "warning": warning,
        }
    )
    loo = stored.described["loo"]
    measurements = _measurements(
        "fitted",
        stored.described["observations"],
        cases,
        a["measured"],
        a["start_predicted"],
        a["predicted"],
        math.nan,
        a["in_sample_error_pct"],
        held_out={
            "held_out_predicted": a["held_out_predicted"],
            "held_out_error_pct": a["held_out_error_pct"],
            "held_out_status": loo["row_status"],
        },
    )
    applied = stored.described["applied"]
    if applied:
        others = _measurements(
            "applied",
            applied,
            cases,
            a["applied_measured"],
            a["applied_start_predicted"],
            a["applied_predicted"],
            a["applied_standard_errors"],
            a["applied_error_pct"],
        )
        measurements = pd.concat([measurements, others], ignore_index=True)
    return constants, measurements


#: The constants' table's columns.
_CONSTANTS = (
    Column("parameter", "Constant", fmt=""),
    Column("unit", "Unit", fmt=""),
    Column("low", "Least", fmt=".4g"),
    Column("high", "Largest", fmt=".4g"),
    Column("source", "Source", fmt=""),
    Column("start", "Start", fmt=".4g"),
    Column("value", "Fitted", fmt=".5g"),
    Column("standard_error", "Standard error", fmt=".2g"),
    Column("relative_standard_error_pct", "Standard error", "%", ".2g"),
    Column("correlation", "Correlation with the others", fmt=""),
    Column("at_bound", "At a bound", fmt=""),
)
#: The measurements' table's columns.
_MEASUREMENTS = (
    Column("role", "Role", fmt=""),
    Column("unit", "Unit", fmt=""),
    Column("quantity", "Quantity", fmt="", in_words="quantity_words"),
    Column("quantity_words", "Quantity", fmt=""),
    Column("measured", "Measured", fmt=".5g"),
    Column("start_predicted", "Model at the start", fmt=".5g"),
    Column("start_error_pct", "Model at the start, error", "%", ".3g"),
    Column("fitted", "Fitted model", fmt=".5g"),
    Column("fitted_standard_error", "Fitted model's standard error", fmt=".2g"),
    Column("residual_pct", "Fitted model's error", "%", ".3g"),
    Column("held_out_predicted", "Predicted held out", fmt=".5g"),
    Column("held_out_error_pct", "Held-out error", "%"),
    Column("held_out_status", "Held-out fit", fmt=""),
)


def _caption(stored: StoredCalibration, measurements: pd.DataFrame, heading: str) -> str:
    """What the calibration's tables are, their mean errors, and the fit's verdict."""
    caption = (
        f"{heading}. The constants fitted by {stored.scalars['method']} to the measurements "
        f"(docs/calibration.md): fitted values with their standard errors and correlations, each "
        f"measurement's fitted value and error, and its prediction by the fit made without its case "
        f"(leave-one-out)."
    )
    fitted_rows = measurements[measurements["role"] == "fitted"]
    caption += (
        f" Mean |error| over the {len(fitted_rows)} fitted measurement(s): {_mean_abs(fitted_rows['residual_pct'])} "
        f"in sample, {_mean_abs(fitted_rows['held_out_error_pct'])} held out."
    )
    applied = sorted({row["case"] for row in stored.described["applied"]})
    if applied:
        caption += (
            f" Below the fitted cases, {len(applied)} case(s) not fitted, predicted at the fitted constants "
            "with the standard error the constants' uncertainty gives: a transfer to another set-up, not a "
            "check of the fit."
        )
    return f"{caption} {_verdict(stored)}"


def calibration_tables(stored: StoredCalibration, title: str) -> tuple[Table, Table]:
    """The constants' table and the measurements' table of a calibration (:func:`calibration_frames`),
    each headed a fit, not a prediction; the measurements a panel per role (fitted, applied)."""
    constants, measurements = calibration_frames(stored)
    heading = f"{FIT_LABEL}: {title}"
    caption = _caption(stored, measurements, heading)
    constants_table = Table(constants, (*_CONSTANTS, *shared(["warning"])), caption)
    measurements_table = Table(measurements, (*shared(["case_id", "case_words"]), *_MEASUREMENTS), caption)
    return (
        constants_table.showing(
            panels(
                constants_table,
                f"{heading}: the constants",
                ["parameter", "unit"],
                ["low", "high", "value", "standard_error", "relative_standard_error_pct", "correlation", "at_bound"],
            )
        ),
        measurements_table.showing(
            panels(
                measurements_table,
                f"{heading}: the measurements",
                ["case_words", "quantity_words", "unit"],
                [
                    "measured",
                    "start_predicted",
                    "start_error_pct",
                    "fitted",
                    "fitted_standard_error",
                    "residual_pct",
                    "held_out_predicted",
                    "held_out_error_pct",
                    "held_out_status",
                ],
                by="role",
            )
        ),
    )


def make_calibration_artifacts(
    calibration: str | Path,
    title: str,
    *,
    csv: str | Path,
    parameters_csv: str | Path,
    md: str | Path,
    html: str | Path,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
) -> None:
    """The calibration's tables (per measurement: ``csv``; per constant: ``parameters_csv``;
    both in ``md`` and ``html``: :func:`calibration_tables`) and its figure (``pdf``, ``png``),
    from its file only."""
    from rodimpact.present.calibration_figures import plot_calibration
    from rodimpact.present.figures import save_figure
    from rodimpact.storage.sidecar import provenance_record

    stored = read_calibration(calibration)
    constants, measurements = calibration_tables(stored, title)
    heading = f"{FIT_LABEL}: {title}"
    caption = constants.caption
    write_csv(measurements.frame, csv)
    write_csv(constants.frame, parameters_csv)
    with atomic_output(html) as tmp:
        tmp.write_text(
            f"<p>{escape(caption)}</p>\n"
            + html_tables(constants, f"{Path(html).stem}-constants")
            + html_tables(measurements, f"{Path(html).stem}-measurements"),
            encoding="utf-8",
        )
    # one role (no case predicted at the fitted constants): the column says nothing
    shown = measurements if len(set(measurements.frame["role"])) > 1 else _without_role(measurements)
    with atomic_output(md) as tmp:
        tmp.write_text(
            f"{textwrap.fill(caption, 100)}\n\n{markdown_table(constants)}\n\n{markdown_table(shown)}\n",
            encoding="utf-8",
        )
    record = {**provenance_record([], [pdf, png]), "input_files": [{"path": str(calibration), "kind": "calibration"}]}
    save_figure(
        plot_calibration(constants.frame, measurements.frame, heading, _verdict(stored)),
        pdf=pdf,
        png=png,
        provenance=record,
        title=heading,
    )
    write_provenance(provenance, [], [csv, parameters_csv, md, html, pdf, png], {"calibration": [str(calibration)]})
    log.info("%s: %s, %d measurements", heading, stored.scalars["status"], len(measurements.frame))


def _without_role(table: Table) -> Table:
    return Table(table.frame.drop(columns="role"), table.columns, table.caption)
