"""The fit of one model parameter to measured contact times, and its leave-one-out check.

The model was run on a grid of values of one scalar parameter theta (in our use: the
thickness of the glue bond line under the sensor film, m) for every row (a ball, a case):
``predicted[i, j]`` is the contact time of row i at ``theta_grid[j]``, µs. The fit finds the
theta that brings the model closest to the measured contact times ``measured[i]``, µs.

Method:

* Between grid points each row is interpolated by a monotone cubic (PCHIP,
  :class:`scipy.interpolate.PchipInterpolator`); each row must be strictly monotone in theta.
  Nothing is extrapolated: theta stays in [theta_grid[0], theta_grid[-1]].
* Least squares on relative residuals (the paper reports relative errors):
  r_i(theta) = (t_i(theta) - m_i) / m_i, minimizing S(theta) = sum_i w_i r_i(theta)^2
  (w_i = 1 unless weights are given). The minimum is bracketed on
  :data:`SCAN_POINTS` evenly spaced values over the grid's span, then refined by
  :func:`scipy.optimize.minimize_scalar` (``method="bounded"``) on the bracket. A minimum at
  the edge of the grid is reported as such (``at_bound=True``, ``success=False``).
* Standard error of theta, Gauss-Newton (linearized) approximation:
  se = sqrt(s2 / sum_i w_i (dr_i/dtheta)^2), s2 = S(theta) / (n - 1), with n the rows used
  and one parameter; dr_i/dtheta = t_i'(theta) / m_i from the interpolant. It measures the
  scatter of the residuals only, not the error of the model or of the grid interpolation.
* Leave-one-out: each row in turn is held out, theta is fitted on the others only, and the
  held-out row is predicted at that theta.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "SCAN_POINTS",
    "FitInputError",
    "LeaveOneOut",
    "ThetaFit",
    "fit_theta",
    "inside",
    "leave_one_out",
    "predict_at",
]

log = logging.getLogger(__name__)


def _pchip():
    """:class:`scipy.interpolate.PchipInterpolator`, imported on first use: the table and figure
    jobs that import this module through :mod:`rodimpact.present` without fitting skip
    scipy.interpolate (0.4 s)."""
    from scipy.interpolate import PchipInterpolator

    return PchipInterpolator


#: The number of evenly spaced values of theta on which the minimum is bracketed.
SCAN_POINTS = 2001


_MESSAGES = {
    "converged": "the minimum lies inside the grid",
    "at_lower_bound": "the minimum lies at the grid's lower edge: widen the grid (not extrapolated)",
    "at_upper_bound": "the minimum lies at the grid's upper edge: widen the grid (not extrapolated)",
    "not_converged": "the bounded refinement did not converge",
}


class FitInputError(ValueError):
    """An argument of the fit is wrong; ``field`` names it."""

    def __init__(self, field: str, message: str) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field


@dataclass(frozen=True, eq=False)
class ThetaFit:
    """The least-squares value of theta and how well it fits.

    Attributes
    ----------
    theta : float
        The fitted value, in the unit of ``theta_grid`` (m in our use). The grid's edge
        value when the minimum lies at the edge (``at_bound``).
    standard_error : float
        Gauss-Newton standard error of ``theta`` (module docstring), unit of theta; NaN with
        a single row used.
    residual_rms : float
        sqrt(mean r_i^2) of the relative residuals r_i = (t_i - m_i) / m_i of the rows used,
        dimensionless (unweighted).
    rows_used : tuple of int
        The indices of the rows fitted.
    predicted : ndarray, shape (n_rows,)
        Every row's model contact time at ``theta``, µs (rows not used included).
    at_bound : bool
        True when the minimum lies at the edge of the grid (never extrapolated).
    success : bool
        True when the minimum is inside the grid and the refinement converged.
    status : str
        ``"converged"``, ``"at_lower_bound"``, ``"at_upper_bound"`` or ``"not_converged"``.
    message : str
        A sentence saying the same, for people.
    evaluations : int
        The number of evaluations of the cost S (each over all the rows used).
    inside_range : bool or None
        Whether ``theta`` lies in the ``source_range`` given to the fit; None without one.
    """

    theta: float
    standard_error: float
    residual_rms: float
    rows_used: tuple[int, ...]
    predicted: NDArray[np.float64]
    at_bound: bool
    success: bool
    status: str
    message: str
    evaluations: int
    inside_range: bool | None = None


@dataclass(frozen=True, eq=False)
class LeaveOneOut:
    """Each row held out in turn: fitted on the others, predicted at their theta.

    Attributes
    ----------
    theta : ndarray, shape (n_rows,)
        Element i: theta fitted on every row but i, unit of theta.
    held_out_predicted : ndarray, shape (n_rows,)
        Element i: row i's model contact time at ``theta[i]``, µs.
    signed_error_pct : ndarray, shape (n_rows,)
        100 (predicted - measured) / measured of the held-out row, %.
    abs_error_pct : ndarray, shape (n_rows,)
        Its absolute value, %.
    mean_abs_error_pct : float
        The mean of ``abs_error_pct``, %.
    folds : tuple of ThetaFit
        Element i: the fit on every row but i.
    """

    theta: NDArray[np.float64]
    held_out_predicted: NDArray[np.float64]
    signed_error_pct: NDArray[np.float64]
    abs_error_pct: NDArray[np.float64]
    mean_abs_error_pct: float
    folds: tuple[ThetaFit, ...]

    @property
    def all_success(self) -> bool:
        """True when every fold's fit succeeded (none at the grid's edge)."""
        return all(fold.success for fold in self.folds)


def inside(theta: float, low: float, high: float) -> bool:
    """True when ``low <= theta <= high`` (the closed range)."""
    return bool(low <= theta <= high)


def _frozen(values: ArrayLike) -> NDArray[np.float64]:
    """A read-only float copy (the results are frozen)."""
    out = np.array(values, dtype=float)
    out.setflags(write=False)
    return out


def _grid(theta_grid: ArrayLike, predicted: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The grid and the predictions, checked (module docstring for what they must be)."""
    grid = np.asarray(theta_grid, dtype=float)
    if grid.ndim != 1 or grid.size < 3:
        raise FitInputError("theta_grid", f"must be 1-d with at least 3 values, got shape {grid.shape}")
    if not np.all(np.isfinite(grid)) or not np.all(np.diff(grid) > 0):
        raise FitInputError("theta_grid", "must be finite and strictly increasing")
    table = np.asarray(predicted, dtype=float)
    if table.ndim != 2 or table.shape[1] != grid.size or table.shape[0] < 1:
        raise FitInputError(
            "predicted", f"must have shape (n_rows, {grid.size}) to match theta_grid, got {table.shape}"
        )
    if not np.all(np.isfinite(table)):
        raise FitInputError("predicted", "must be finite")
    steps = np.diff(table, axis=1)
    monotone = np.all(steps > 0, axis=1) | np.all(steps < 0, axis=1)
    if not np.all(monotone):
        bad = [int(i) for i in np.flatnonzero(~monotone)]
        raise FitInputError("predicted", f"every row must be strictly monotone in theta; rows {bad} are not")
    return grid, table


def _inputs(
    theta_grid: ArrayLike,
    predicted: ArrayLike,
    measured: ArrayLike,
    weights: ArrayLike | None,
    source_range: Sequence[float] | None,
) -> tuple[NDArray[np.float64], ...]:
    grid, table = _grid(theta_grid, predicted)
    n_rows = table.shape[0]
    times = np.asarray(measured, dtype=float)
    if times.shape != (n_rows,):
        raise FitInputError("measured", f"must have shape ({n_rows},) to match predicted, got {times.shape}")
    if not np.all(np.isfinite(times) & (times > 0)):
        raise FitInputError("measured", "must be finite and > 0")
    w = np.ones(n_rows) if weights is None else np.asarray(weights, dtype=float)
    if w.shape != (n_rows,) or not np.all(np.isfinite(w) & (w > 0)):
        raise FitInputError("weights", f"must have shape ({n_rows},), finite and > 0")
    if source_range is not None:
        bounds = np.asarray(source_range, dtype=float)
        if bounds.shape != (2,) or not np.all(np.isfinite(bounds)) or bounds[0] > bounds[1]:
            raise FitInputError("source_range", f"must be (low, high), finite, low <= high; got {source_range!r}")
    return grid, table, times, w


def _rows(rows: Sequence[int] | None, n_rows: int) -> tuple[int, ...]:
    if rows is None:
        return tuple(range(n_rows))
    try:
        chosen = tuple(int(i) for i in rows)
    except (TypeError, ValueError) as error:
        raise FitInputError("rows", f"must be a sequence of row indices, got {rows!r}") from error
    if not chosen or len(set(chosen)) != len(chosen) or not all(0 <= i < n_rows for i in chosen):
        raise FitInputError("rows", f"must be distinct indices in [0, {n_rows}), at least one; got {rows!r}")
    return chosen


def predict_at(theta_grid: ArrayLike, predicted: ArrayLike, theta: ArrayLike) -> NDArray[np.float64]:
    """Every row's prediction at ``theta``, by PCHIP between grid points (no extrapolation).

    Parameters
    ----------
    theta_grid : array_like, shape (k,)
        Strictly increasing values of theta, k >= 3.
    predicted : array_like, shape (n_rows, k)
        The model's value (contact time, µs) of each row at each grid value; rows strictly monotone.
    theta : float or array_like, shape (m,)
        Where to predict; inside [theta_grid[0], theta_grid[-1]].

    Returns
    -------
    ndarray, shape (n_rows,) for a scalar theta, (n_rows, m) for an array
        The interpolated predictions, unit of ``predicted``.
    """
    grid, table = _grid(theta_grid, predicted)
    at = np.asarray(theta, dtype=float)
    if not np.all(np.isfinite(at)) or np.any(at < grid[0]) or np.any(at > grid[-1]):
        raise FitInputError("theta", f"must lie in the grid's span [{grid[0]:g}, {grid[-1]:g}] (no extrapolation)")
    return _pchip()(grid, table, axis=1, extrapolate=False)(at)


def fit_theta(
    theta_grid: ArrayLike,
    predicted: ArrayLike,
    measured: ArrayLike,
    *,
    rows: Sequence[int] | None = None,
    weights: ArrayLike | None = None,
    source_range: Sequence[float] | None = None,
) -> ThetaFit:
    """The least-squares theta of the measured contact times (module docstring for the method).

    Parameters
    ----------
    theta_grid : array_like, shape (k,)
        Strictly increasing values of theta at which the model was run, k >= 3 (m in our use).
    predicted : array_like, shape (n_rows, k)
        The model's contact time of each row at each grid value, µs; each row strictly monotone.
    measured : array_like, shape (n_rows,)
        The measured contact times, µs; finite, > 0.
    rows : sequence of int, optional
        The rows to fit (default: all). The others take no part in the fit (their
        measurements are still checked) but are predicted at the fitted theta.
    weights : array_like, shape (n_rows,), optional
        w_i of the relative residuals' squares, > 0 (default: all 1, plain relative errors).
    source_range : (float, float), optional
        (low, high) of theta from a source; the result says whether theta lies inside.

    Returns
    -------
    ThetaFit

    Raises
    ------
    FitInputError
        An argument is wrong; its ``field`` names which.
    """
    grid, table, times, w = _inputs(theta_grid, predicted, measured, weights, source_range)
    used = _rows(rows, table.shape[0])
    index = np.asarray(used)
    curve = _pchip()(grid, table[index], axis=1, extrapolate=False)
    slope = curve.derivative()
    m, wu = times[index], w[index]
    evaluations = 0

    def cost(theta: float) -> float:
        nonlocal evaluations
        evaluations += 1
        r = (curve(theta) - m) / m
        return float(np.sum(wu * r * r))

    scan = np.linspace(grid[0], grid[-1], SCAN_POINTS)
    residuals = (curve(scan) - m[:, None]) / m[:, None]
    costs = np.sum(wu[:, None] * residuals**2, axis=0)
    evaluations += SCAN_POINTS
    j = int(np.argmin(costs))

    def gradient(theta: float) -> float:  # dS/dtheta = 2 sum w r r'
        return float(2.0 * np.sum(wu * (curve(theta) - m) / m * slope(theta) / m))

    converged = False
    if j == 0 and gradient(grid[0]) >= 0.0:  # S rises from the lower edge into the grid
        theta, status = float(grid[0]), "at_lower_bound"
    elif j == SCAN_POINTS - 1 and gradient(grid[-1]) <= 0.0:  # S still falls at the upper edge
        theta, status = float(grid[-1]), "at_upper_bound"
    else:
        low, high = scan[max(j - 1, 0)], scan[min(j + 1, SCAN_POINTS - 1)]
        from scipy.optimize import minimize_scalar

        result = minimize_scalar(
            cost, bounds=(low, high), method="bounded", options={"xatol": 1e-12 * (grid[-1] - grid[0])}
        )
        converged = bool(result.success)
        theta = float(result.x) if result.fun <= costs[j] else float(scan[j])
        status = "converged" if converged else "not_converged"
    at_bound = status.startswith("at_")

    r = (curve(theta) - m) / m
    ssr = float(np.sum(wu * r * r))
    sensitivity = float(np.sum(wu * (slope(theta) / m) ** 2))
    n = len(used)
    se = math.sqrt(ssr / (n - 1) / sensitivity) if n > 1 and sensitivity > 0 else math.nan
    fit = ThetaFit(
        theta=theta,
        standard_error=se,
        residual_rms=float(np.sqrt(np.mean(r * r))),
        rows_used=used,
        predicted=_frozen(_pchip()(grid, table, axis=1, extrapolate=False)(theta)),
        at_bound=at_bound,
        success=converged and not at_bound,
        status=status,
        message=_MESSAGES[status],
        evaluations=evaluations,
        inside_range=None if source_range is None else inside(theta, *(float(x) for x in source_range)),
    )
    if fit.success:
        log.debug("theta fit on rows %s: %g +/- %g, rms %.3g", used, theta, se, fit.residual_rms)
    else:
        log.warning("theta fit on rows %s: %s (theta %g)", used, fit.message, theta)
    return fit


def leave_one_out(
    theta_grid: ArrayLike,
    predicted: ArrayLike,
    measured: ArrayLike,
    *,
    weights: ArrayLike | None = None,
    source_range: Sequence[float] | None = None,
) -> LeaveOneOut:
    """Hold out each row in turn, fit theta on the others, predict the held-out row.

    Parameters
    ----------
    theta_grid, predicted, measured, weights, source_range
        As for :func:`fit_theta`; at least 2 rows.

    Returns
    -------
    LeaveOneOut
        Fold i is fitted with ``rows`` = every row but i, so the held-out measurement takes
        no part in its own fold.

    Raises
    ------
    FitInputError
        An argument is wrong, or fewer than 2 rows (``field="predicted"``).
    """
    grid, table, times, w = _inputs(theta_grid, predicted, measured, weights, source_range)
    n_rows = table.shape[0]
    if n_rows < 2:
        raise FitInputError("predicted", "leave-one-out needs at least 2 rows")
    folds = tuple(
        fit_theta(
            grid, table, times, rows=[i for i in range(n_rows) if i != held], weights=w, source_range=source_range
        )
        for held in range(n_rows)
    )
    held_out = np.array([fold.predicted[held] for held, fold in enumerate(folds)])
    signed = 100.0 * (held_out - times) / times
    return LeaveOneOut(
        theta=_frozen(np.array([fold.theta for fold in folds])),
        held_out_predicted=_frozen(held_out),
        signed_error_pct=_frozen(signed),
        abs_error_pct=_frozen(np.abs(signed)),
        mean_abs_error_pct=float(np.mean(np.abs(signed))),
        folds=folds,
    )
