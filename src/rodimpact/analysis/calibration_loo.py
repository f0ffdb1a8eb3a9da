"""Leave-one-out of a calibration: each case held out in turn, refitted without it, predicted.

Observations belong to cases (:class:`~rodimpact.analysis.calibration.Observation` ``case``) and
a case is held out whole: its observations come from one test, so fitting some of them while
predicting the others would judge the model on data it has nearly seen. For each case the
parameters are refitted by :func:`~rodimpact.analysis.calibration.calibrate` on the other cases'
observations, starting at the full fit's values (every fit shares one cache of the model's
evaluations, so a refit's first step reuses the full fit's last ones), and the held-out case is
predicted at the refitted values. The held-out errors, (predicted - measured) / |measured| in %,
estimate how the calibrated model predicts a new test; set beside the full fit's in-sample
errors they show how much the fit adapts to the data it is given.

A held-out fit that would keep fewer observations than parameters is not attempted: its case
gets the status ``"too_few"`` and NaN predictions.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.analysis.calibration import (
    DEFAULT_FAILURES,
    MAX_TRIALS,
    MODEL_TOLERANCE,
    Calibration,
    CalibrationInputError,
    Observation,
    Parameter,
    calibrate,
    check_inputs,
)
from rodimpact.analysis.errors import relative_error_pct

__all__ = ["TOO_FEW", "LeaveOneOut", "leave_one_out"]

log = logging.getLogger(__name__)

#: The status of a held-out case whose removal leaves fewer observations than parameters.
TOO_FEW = "too_few"


@dataclass(frozen=True, eq=False)
class LeaveOneOut:
    """Each case held out in turn: refitted on the others, predicted at their fit.

    Attributes
    ----------
    fit : Calibration
        The fit on every observation, from whose values each refit starts.
    cases : tuple of str, length k
        The cases, in the order they first appear among the observations.
    status : tuple of str, length k
        Each held-out fit's :attr:`Calibration.status`, or ``"too_few"``.
    values : ndarray, shape (k, p)
        Row c: the parameters fitted without case c, in their units (NaN when too few).
    held_out_predicted : ndarray, shape (n,)
        Each observation's prediction by the fit without its case, in its quantity's unit.
    held_out_error_pct : ndarray, shape (n,)
        100 (held-out predicted - measured) / |measured|, % (NaN for a measured 0 or too few).
    in_sample_error_pct : ndarray, shape (n,)
        The same of the full fit's prediction, %.
    row_status : tuple of str, length n
        Each observation's held-out status (its case's).
    possible : int
        The number of held-out fits made (cases not ``"too_few"``).
    evaluations : int
        The model calls made here (the full fit's included when it was made here).
    folds : tuple of (Calibration or None), length k
        The held-out fits (None when too few).
    """

    fit: Calibration
    cases: tuple[str, ...]
    status: tuple[str, ...]
    values: NDArray[np.float64]
    held_out_predicted: NDArray[np.float64]
    held_out_error_pct: NDArray[np.float64]
    in_sample_error_pct: NDArray[np.float64]
    row_status: tuple[str, ...]
    possible: int
    evaluations: int
    folds: tuple[Calibration | None, ...]

    @property
    def mean_abs_error_pct(self) -> float:
        """The mean |held-out error| over the observations whose held-out fit was made, %."""
        return _mean_abs(self.held_out_error_pct)

    @property
    def in_sample_mean_abs_error_pct(self) -> float:
        """The mean |in-sample error| over the same observations, %."""
        return _mean_abs(np.where(np.isnan(self.held_out_predicted), math.nan, self.in_sample_error_pct))

    def table_rows(self) -> list[dict[str, Any]]:
        """A plain dict an observation: measured, in-sample and held-out predictions and errors."""
        return [
            {
                "case": o.case,
                "quantity": o.quantity,
                "measured": o.measured,
                "in_sample_predicted": float(self.fit.predicted[i]),
                "in_sample_error_pct": float(self.in_sample_error_pct[i]),
                "held_out_predicted": float(self.held_out_predicted[i]),
                "held_out_error_pct": float(self.held_out_error_pct[i]),
                "status": self.row_status[i],
            }
            for i, o in enumerate(self.fit.observations)
        ]


def _mean_abs(values: NDArray[np.float64]) -> float:
    finite = values[np.isfinite(values)]
    return float(np.mean(np.abs(finite))) if finite.size else math.nan


def _error_pct(predicted: NDArray[np.float64], measured: NDArray[np.float64]) -> NDArray[np.float64]:
    """:func:`~rodimpact.analysis.errors.relative_error_pct`, read-only (a frozen result's array)."""
    out = np.array(relative_error_pct(predicted, measured), dtype=float, ndmin=1)
    out.setflags(write=False)
    return out


def leave_one_out(
    model: Callable[[NDArray[np.float64]], Any],
    observations: Sequence[Observation],
    parameters: Sequence[Parameter],
    fit: Calibration | None = None,
    *,
    cache: dict | None = None,
    model_tolerance: float = MODEL_TOLERANCE,
    max_trials: int = MAX_TRIALS,
    failures: tuple[type[BaseException], ...] = DEFAULT_FAILURES,
) -> LeaveOneOut:
    """Hold out each case in turn, refit on the others, predict the held-out case.

    Parameters
    ----------
    model, observations, parameters
        As for :func:`~rodimpact.analysis.calibration.calibrate`.
    fit : Calibration, optional
        The full fit of these observations and parameters (default: made here).
    cache : dict, optional
        The model's evaluations, shared by every fit; pass the full fit's to reuse them.
    model_tolerance, max_trials, failures
        As for :func:`~rodimpact.analysis.calibration.calibrate`, for every fit.

    Returns
    -------
    LeaveOneOut

    Raises
    ------
    CalibrationInputError
        As :func:`~rodimpact.analysis.calibration.calibrate`, before any model call; ``"fit"``
        when ``fit`` is not of these parameters to all these observations.
    """
    obs, params, _ = check_inputs(observations, parameters)
    if fit is not None and (fit.observations, fit.parameters, fit.rows_used) != (obs, params, tuple(range(len(obs)))):
        raise CalibrationInputError("fit", "must be the fit of these parameters to all these observations")
    cache = {} if cache is None else cache
    before = len(cache)
    options = {"cache": cache, "model_tolerance": model_tolerance, "max_trials": max_trials, "failures": failures}
    if fit is None:
        fit = calibrate(model, obs, params, **options)
    starts = tuple(replace(p, start=float(np.clip(v, p.low, p.high))) for p, v in zip(params, fit.values))
    cases = tuple(dict.fromkeys(o.case for o in obs))
    predicted = np.full(len(obs), math.nan)
    values = np.full((len(cases), len(params)), math.nan)
    folds: list[Calibration | None] = []
    for c, case in enumerate(cases):
        kept = [i for i, o in enumerate(obs) if o.case != case]
        if len(kept) < len(params):
            log.info("leave-one-out: without %s, %d observations for %d parameters", case, len(kept), len(params))
            folds.append(None)
            continue
        folds.append(fold := calibrate(model, obs, starts, rows=kept, **options))
        held = [i for i, o in enumerate(obs) if o.case == case]
        values[c], predicted[held] = fold.values, fold.predicted[held]
    status = tuple(TOO_FEW if fold is None else fold.status for fold in folds)
    by_case = dict(zip(cases, status))
    predicted.setflags(write=False)
    values.setflags(write=False)
    measured = np.array([o.measured for o in obs], dtype=float)
    return LeaveOneOut(
        fit=fit,
        cases=cases,
        status=status,
        values=values,
        held_out_predicted=predicted,
        held_out_error_pct=_error_pct(predicted, measured),
        in_sample_error_pct=_error_pct(fit.predicted, measured),
        row_status=tuple(by_case[o.case] for o in obs),
        possible=sum(s != TOO_FEW for s in status),
        evaluations=len(cache) - before,
        folds=tuple(folds),
    )
