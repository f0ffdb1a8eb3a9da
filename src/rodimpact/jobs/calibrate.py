"""One set's calibration job: its declared constants fitted to its measurements, with
leave-one-out, written to one HDF5 file (:mod:`rodimpact.storage.calibrations`).

The model (:class:`SetModel`) runs every fitted case with the block's method at a vector of the
constants (each set by its path, :mod:`rodimpact.config.paths`), in memory, storing nothing,
and reads each case's fitted quantities from the run as the comparison tables read them
(:func:`rodimpact.analysis.observations.observed`): one place says what "the computed arrival
at the gauge" is, for a table and for a fit alike. A value's residual is relative to the
measured value; an error norm (a quantity ending in ``_pct``) is a relative error already, its
measured value 0 and its scale 100 %. The fit and its leave-one-out are
:func:`rodimpact.analysis.calibration.calibrate` and
:func:`rodimpact.analysis.calibration_loo.leave_one_out`, sharing one cache of runs.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.analysis.calibration import Calibration, ModelFailure, Observation, Parameter, calibrate
from rodimpact.analysis.calibration_loo import LeaveOneOut, leave_one_out
from rodimpact.analysis.measured import RECORDS, MeasuredHistory, read_history
from rodimpact.analysis.observations import NORMS, Observed, gives, observed
from rodimpact.config.calibration import calibration_cases, with_method
from rodimpact.config.measured import record_outputs
from rodimpact.config.paths import with_setting
from rodimpact.jobs.runner import SolverFailed, run_case
from rodimpact.storage.calibrations import StoredCalibration, write_calibration

__all__ = ["SetModel", "calibration_parameters", "mixed_scales_warning", "run_calibration"]

log = logging.getLogger(__name__)


class SetModel:
    """The fitted quantities of a set's cases at a vector of its constants (module docstring).

    Parameters
    ----------
    cases : sequence of mapping
        The fitted cases, resolved.
    block : mapping
        The set's ``calibrate`` block.
    numerics : mapping
        The global numerics per method.
    records : mapping
        Case id -> its records, read, by their key in the ``measured`` block.
    """

    def __init__(
        self,
        cases: Sequence[Mapping[str, Any]],
        block: Mapping[str, Any],
        numerics: Mapping[str, Any],
        records: Mapping[str, Mapping[str, MeasuredHistory]],
    ) -> None:
        self.block, self.records = block, records
        self.method = str(block["method"])
        self.paths = [str(p["path"]) for p in block["parameters"]]
        self.cases = [self._as_run(case, numerics) for case in cases]
        self.rows = [(case["id"], q) for case in self.cases for q in block["quantities"] if gives(case, q)]

    def _as_run(self, case: Mapping[str, Any], numerics: Mapping[str, Any]) -> dict[str, Any]:
        """The case as the method runs it here: its outputs only those the records need."""
        run = with_method(case, self.method, numerics)
        run["outputs"] = list(dict.fromkeys(["contact_force", *record_outputs(case)]))
        return run

    def observe(self, theta: NDArray[np.float64]) -> list[Observed]:
        """Every fitted measurement against the runs at ``theta``, in the order of :attr:`rows`.

        Raises
        ------
        ModelFailure
            A run failed (its solver's status and message), or a signal could not be read.
        """
        found: list[Observed] = []
        for case in self.cases:
            changed = case
            for path, value in zip(self.paths, np.asarray(theta, float), strict=True):
                changed = with_setting(changed, path, float(value))
            try:
                result = run_case(changed, self.method)
                series = {name: array for name, (array, _, _) in result.series(changed["outputs"]).items()}
                rows = observed(changed, series, result.summary(), self.records.get(case["id"]))
            except (SolverFailed, KeyError, ValueError) as problem:
                raise ModelFailure(
                    f"case {case['id']!r} at {dict(zip(self.paths, theta, strict=True))}: {problem}"
                ) from None
            by_quantity = {row.quantity: row for row in rows}
            found += [by_quantity[q] for cid, q in self.rows if cid == case["id"]]
        return found

    def __call__(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """The predicted value of every fitted measurement (a norm's value in %)."""
        return np.asarray([row.error_pct if row.is_norm else row.computed for row in self.observe(theta)], float)

    def observations(self, rows: Sequence[Observed]) -> list[Observation]:
        """The measurements, from the rows :meth:`observe` gave (the records read as the model reads them)."""
        return [
            Observation(cid, row.quantity, 0.0, 100.0)
            if row.quantity in NORMS
            else Observation(cid, row.quantity, row.measured, _scale(row))
            for (cid, _), row in zip(self.rows, rows, strict=True)
        ]


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


def _stored(
    set_name: str, model: SetModel, words: list[Observed], fit: Calibration, loo: LeaveOneOut, warnings: list[str]
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
        "parameters": [{"path": p.name, "unit": p.unit, "source": p.source} for p in params],
        "observations": [
            # the words without what depends on the constants (x/c at the start's modulus)
            {
                "case": o.case,
                "quantity": o.quantity,
                "words": w.words.split(" (x/c")[0],
                "unit": w.unit,
                "norm": o.quantity in NORMS,
            }
            for o, w in zip(fit.observations, words, strict=True)
        ],
        "loo": {"cases": list(loo.cases), "status": list(loo.status), "row_status": list(loo.row_status)},
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
        "predicted": fit.predicted,
        "residuals": fit.residuals,
        "held_out_predicted": loo.held_out_predicted,
        "held_out_error_pct": loo.held_out_error_pct,
        "in_sample_error_pct": loo.in_sample_error_pct,
        "loo_values": loo.values,
    }
    return StoredCalibration(scalars, described, {k: np.asarray(v, float) for k, v in arrays.items()})


def run_calibration(
    set_name: str,
    cases: Sequence[Mapping[str, Any]],
    block: Mapping[str, Any],
    numerics: Mapping[str, Any],
    out: str | Path,
) -> Calibration:
    """Fit the set's constants, hold out each case in turn, and write the file ``out``.

    A fit that does not converge, or that the data cannot identify, is still written: its
    status, message and warnings are the result (failure is data); the table and the report
    show them.

    Raises
    ------
    ModelFailure
        The model failed at the start, where nothing can be fitted.
    """
    fitted = calibration_cases(cases, block)
    records = {
        case["id"]: {
            key: read_history(case["measured"][key]["path"], case["measured"][key], key)
            for key in RECORDS
            if case["measured"].get(key)
        }
        for case in fitted
    }
    model = SetModel(fitted, block, numerics, records)
    parameters = calibration_parameters(block)
    start = np.asarray([_start(p) for p in parameters], float)
    words = model.observe(start)
    observations = model.observations(words)
    warnings = [w for w in (mixed_scales_warning(words),) if w]
    for warning in warnings:
        log.warning("calibration of %s: %s", set_name, warning)
    cache: dict = {}
    fit = calibrate(model, observations, parameters, cache=cache)
    log.info("calibration of %s: %s (%s); values %s", set_name, fit.status, fit.message, fit.values)
    loo = leave_one_out(model, observations, parameters, fit, cache=cache)
    config = {"calibrate": dict(block), "cases": [dict(c) for c in fitted]}
    write_calibration(out, _stored(set_name, model, words, fit, loo, warnings), config=config)
    return fit
