"""One set's calibration job: its declared constants fitted to its measurements, with
leave-one-out, written to one HDF5 file (:mod:`rodimpact.storage.calibrations`).

The model (:mod:`rodimpact.jobs.calibration_model`) runs every fitted case with the block's
method at a vector of the constants, in memory, storing nothing, or reads it between runs made
once on a constant's ``grid``. A value's residual is relative to the measured value; an error
norm (a quantity ending in ``_pct``) is a relative error already, its measured value 0 and its
scale 100 %. The fit and its leave-one-out are :func:`rodimpact.analysis.calibration.calibrate`
and :func:`rodimpact.analysis.calibration_loo.leave_one_out`, sharing one cache of runs. The
cases of the block's ``apply_to`` are then predicted at the fitted constants, with the standard
error their covariance gives (:class:`Applied`).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.analysis.calibration import STEP, Calibration, Observation, Parameter, calibrate
from rodimpact.analysis.calibration_loo import LeaveOneOut, leave_one_out
from rodimpact.analysis.errors import relative_error_pct
from rodimpact.analysis.measured import RECORDS, read_history
from rodimpact.analysis.observations import NORMS, Observed
from rodimpact.config.calibration import applied_cases, calibration_cases
from rodimpact.jobs.calibration_model import GridModel, SetModel, predicted_values
from rodimpact.storage.calibrations import StoredCalibration, write_calibration
from rodimpact.storage.provenance import file_sha256

__all__ = [
    "Applied",
    "calibration_parameters",
    "mixed_scales_warning",
    "observations_of",
    "propagated_standard_errors",
    "run_calibration",
]

#: What a calibration fits: a set's model, run at every trial or read between runs on a grid.
Model = SetModel | GridModel

log = logging.getLogger(__name__)


def _scale(row: Observed) -> float:
    """A measurement's residual scale: the standard uncertainty its record's noise gives it,
    where the record has a quiet start to measure that noise on; else its own size (a relative
    residual)."""
    return row.measured_sd if math.isfinite(row.measured_sd) and row.measured_sd > 0.0 else abs(row.measured)


def mixed_scales_warning(rows: Sequence[Observed]) -> str | None:
    """A sentence when some measurements are weighted by their records' noise and others, with
    no noise estimate, by their own size: the fit then weighs the two kinds against each other
    by that choice alone, and its standard errors are no better than the choice. None otherwise."""
    values = [row for row in rows if row.quantity not in NORMS]
    relative = [row.quantity for row in values if not (math.isfinite(row.measured_sd) and row.measured_sd > 0.0)]
    if not relative or len(relative) == len(values):
        return None
    named = ", ".join(sorted(set(relative)))
    return (
        f"{len(relative)} of {len(values)} measurements ({named}) have no noise estimate (a value with no "
        "record, or a record without 8 quiet samples before its pulse) and count by their relative error, the "
        "others in their records' standard uncertainties: the weights of the two kinds, and so the standard "
        "errors, rest on that choice"
    )


def _start(parameter: Parameter) -> float:
    """Where the fit starts: the declared start, else the middle of the bounds."""
    return 0.5 * (parameter.low + parameter.high) if parameter.start is None else parameter.start


def calibration_parameters(block: Mapping[str, Any]) -> list[Parameter]:
    return [
        Parameter(
            name=str(p["path"]),
            low=float(p["bounds"][0]),
            high=float(p["bounds"][1]),
            start=None if p.get("start") is None else float(p["start"]),
            unit=str(p.get("unit", "")),
            source=str(p["source"]),
        )
        for p in block["parameters"]
    ]


def _measurements(rows: Sequence[Observed], model: Model) -> list[dict[str, Any]]:
    """Each measurement's case id, quantity and unit, and whether it is a norm (ids and units
    only: the presentation says them in words, from the cases the file's configuration holds)."""
    return [
        {"case": cid, "quantity": quantity, "unit": row.unit, "norm": quantity in NORMS}
        for (cid, quantity), row in zip(model.rows, rows, strict=True)
    ]


def observations_of(ids: Sequence[tuple[str, str]], rows: Sequence[Observed]) -> list[Observation]:
    """The measurements a fit compares, from the rows a model observed (the records read as the
    model reads them): a value against its scale (:func:`_scale`), a norm against 0 at 100 %."""
    return [
        Observation(cid, row.quantity, 0.0, 100.0)
        if row.quantity in NORMS
        else Observation(cid, row.quantity, row.measured, _scale(row))
        for (cid, _), row in zip(ids, rows, strict=True)
    ]


def _stored(
    set_name: str,
    model: Model,
    words: list[Observed],
    fit: Calibration,
    loo: LeaveOneOut,
    warnings: list[str],
    applied: Applied | None,
    grids: Mapping[str, Sequence[float]],
) -> StoredCalibration:
    """What the calibration file holds (:mod:`rodimpact.storage.calibrations`)."""
    params = fit.parameters
    scalars = {
        "set": set_name,
        "method": model.method,
        "status": fit.status,
        "message": fit.message,
        "success": bool(fit.success),
        "identifiable": bool(fit.identifiable),
        "evaluations": int(fit.evaluations + loo.evaluations),
        "dof": int(fit.dof),
        "s2": float(fit.s2),
        "condition_number": float(fit.condition_number),
    }
    described = {
        "warnings": [*fit.warnings, *warnings],
        "parameters": [
            {"path": p.name, "unit": p.unit, "source": p.source, "grid": list(map(float, grids.get(p.name, [])))}
            for p in params
        ],
        "observations": _measurements(words, model),
        "loo": {"cases": list(loo.cases), "status": list(loo.status), "row_status": list(loo.row_status)},
        "applied": [] if applied is None else _measurements(applied.rows, applied.model),
    }
    arrays = {
        "low": [p.low for p in params],
        "high": [p.high for p in params],
        "start": [_start(p) for p in params],
        "values": fit.values,
        "standard_errors": fit.standard_errors,
        "at_bound": fit.at_bound.astype(float),
        "covariance": fit.covariance,
        "correlation": fit.correlation,
        "measured": [o.measured for o in fit.observations],
        "scale": [o.scale for o in fit.observations],
        "start_predicted": model(np.asarray([_start(p) for p in params], float)),
        "predicted": fit.predicted,
        "residuals": fit.residuals,
        "held_out_predicted": loo.held_out_predicted,
        "held_out_error_pct": loo.held_out_error_pct,
        "in_sample_error_pct": loo.in_sample_error_pct,
        "loo_values": loo.values,
        **(applied.arrays() if applied is not None else Applied.empty()),
    }
    return StoredCalibration(scalars, described, {k: np.asarray(v, float) for k, v in arrays.items()})


@dataclass(frozen=True, eq=False)
class Applied:
    """The cases a calibration predicts at its fitted constants without fitting them
    (``apply_to``): each measurement's value by the model at the start and at the fit, with
    the standard error the constants' covariance gives it, and the error against the measurement.

    Attributes
    ----------
    model : SetModel or GridModel
        The model of those cases.
    rows : list of Observed
        Their measurements as the model reads them, shape (a,).
    measured, start_predicted, predicted, standard_errors, error_pct : ndarray, shape (a,)
        The measured value (0 for a norm), the model's at the start and at the fitted constants,
        the latter's standard error, and its error (% of the measured value; a norm's own value).
    """

    model: Model
    rows: list[Observed]
    measured: NDArray[np.float64]
    start_predicted: NDArray[np.float64]
    predicted: NDArray[np.float64]
    standard_errors: NDArray[np.float64]
    error_pct: NDArray[np.float64]

    @classmethod
    def of(cls, model: Model, fit: Calibration) -> Applied:
        """The model's predictions at ``fit``'s start and fitted constants."""
        start = np.asarray([_start(p) for p in fit.parameters], float)
        rows = model.observe(start)
        # a run's rows are its prediction; a grid model's rows are its first grid value's
        start_predicted = predicted_values(rows) if isinstance(model, SetModel) else model(start)
        norm = np.asarray([row.is_norm for row in rows], bool)
        measured = np.asarray([0.0 if row.is_norm else row.measured for row in rows], float)
        predicted = model(fit.values)
        relative = relative_error_pct(predicted, measured)
        return cls(
            model,
            rows,
            measured,
            start_predicted,
            predicted,
            propagated_standard_errors(model, fit),
            np.where(norm, predicted, relative),
        )

    def arrays(self) -> dict[str, NDArray[np.float64]]:
        """The datasets of the calibration file (:mod:`rodimpact.storage.calibrations`)."""
        return {
            "applied_measured": self.measured,
            "applied_start_predicted": self.start_predicted,
            "applied_predicted": self.predicted,
            "applied_standard_errors": self.standard_errors,
            "applied_error_pct": self.error_pct,
        }

    @staticmethod
    def empty() -> dict[str, NDArray[np.float64]]:
        """:meth:`arrays` of a calibration that applies its constants to no case."""
        names = ("measured", "start_predicted", "predicted", "standard_errors", "error_pct")
        return {f"applied_{name}": np.zeros(0) for name in names}


def propagated_standard_errors(model: Model, fit: Calibration) -> NDArray[np.float64]:
    """The standard error of each of ``model``'s predictions that the fitted constants'
    covariance gives (linearised: sqrt of diag(G Cov G^T), G the predictions' derivatives in the
    constants by a central difference of :data:`~rodimpact.analysis.calibration.STEP` of each
    constant's bounds, one-sided at a bound); NaN where the covariance is."""
    values = np.asarray(fit.values, float)
    columns = []
    for k, p in enumerate(fit.parameters):
        h = STEP * (p.high - p.low)
        low, high = values.copy(), values.copy()
        low[k], high[k] = max(p.low, values[k] - h), min(p.high, values[k] + h)
        columns.append((model(high) - model(low)) / (high[k] - low[k]))
    g = np.column_stack(columns)
    return np.sqrt(np.einsum("ij,jk,ik->i", g, np.asarray(fit.covariance, float), g))


def _model(
    cases: Sequence[Mapping[str, Any]],
    block: Mapping[str, Any],
    numerics: Mapping[str, Any],
    curves: Mapping[str, str] | None = None,
) -> tuple[Model, dict[str, list[float]]]:
    """The model of ``cases``: a :class:`GridModel` on the constant that declares a grid, else a
    :class:`SetModel` (``curves``: as :class:`SetModel` takes them); and the grid by the
    constant's path."""
    records = {
        case["id"]: {
            key: read_history(case["measured"][key]["path"], case["measured"][key], key)
            for key in RECORDS
            if case["measured"].get(key)
        }
        for case in cases
    }
    model = SetModel(cases, block, numerics, records, curves)
    grids = {str(p["path"]): [float(v) for v in p["grid"]] for p in block["parameters"] if p.get("grid")}
    if grids:
        (grid,) = grids.values()
        return GridModel(model, grid), grids
    return model, grids


def run_calibration(
    set_name: str,
    cases: Sequence[Mapping[str, Any]],
    block: Mapping[str, Any],
    numerics: Mapping[str, Any],
    out: str | Path,
    curves: Mapping[str, str] | None = None,
) -> Calibration:
    """Fit the set's constants, hold out each case in turn, predict the cases of ``apply_to`` at
    the fitted constants, and write the file ``out``. ``curves``: case id -> the file of the
    curve its law's rule computed at its own constants, read where the model runs the case at
    them (:class:`~rodimpact.jobs.calibration_model.SetModel`); each is named with its hash in
    the file's configuration.

    A fit that does not converge, or that the data cannot identify, is still written: its
    status, message and warnings are the result (failure is data); the table and the report
    show them.

    Raises
    ------
    ModelFailure
        The model failed at the start (or at a grid value), where nothing can be fitted.
    """
    model, grids = _model(calibration_cases(cases, block), block, numerics, curves)
    parameters = calibration_parameters(block)
    start = np.asarray([_start(p) for p in parameters], float)
    words = model.observe(start)
    observations = observations_of(model.rows, words)
    warnings = [w for w in (mixed_scales_warning(words),) if w]
    for warning in warnings:
        log.warning("calibration of %s: %s", set_name, warning)
    cache: dict = {}
    fit = calibrate(model, observations, parameters, cache=cache)
    log.info("calibration of %s: %s (%s); values %s", set_name, fit.status, fit.message, fit.values)
    loo = leave_one_out(model, observations, parameters, fit, cache=cache)
    others = applied_cases(cases, block)
    applied = Applied.of(_model(others, block, numerics, curves)[0], fit) if others else None
    config = {
        "calibrate": dict(block),
        "cases": [dict(c) for c in calibration_cases(cases, block)],
        "applied": [dict(c) for c in others],
    }
    if curves:
        config["curves"] = {
            cid: {"path": str(path), "sha256": file_sha256(path)} for cid, path in sorted(curves.items())
        }
    write_calibration(out, _stored(set_name, model, words, fit, loo, warnings, applied, grids), config=config)
    return fit
