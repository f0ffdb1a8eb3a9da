"""The calibration of declared constants: bounded nonlinear least squares with its uncertainty.

A model maps p declared constants theta (each named by its path, e.g. ``rod.youngs_modulus_pa``,
bounded by a stated source) to the predictions of n observations. It is expensive (a solver run
per case): each theta is evaluated once (a cache fits may share), and the calls are counted.

* Residuals r_i = (f_i(theta) - m_i) / s_i (f predicted, m measured, s the stated scale: |m| for
  relative residuals, or a standard uncertainty). S = sum r_i^2 over the rows used is minimised
  in u = (theta - low) / (high - low) in [0, 1] by :func:`scipy.optimize.least_squares`
  (``method="trf"``, trust region reflective, inside the bounds) to a step of :data:`XTOL` in u.
* The Jacobian: finite differences in u at :data:`STEP`, central, or one-sided of second order
  within a step of a bound (the model is never called outside them).
* A trial where the model fails (raises one of ``failures``, or returns a non-finite value in a
  row used) is unusable: the trust region shrinks, the result counts it, a derivative falls back
  to a one-sided difference.
* Standard errors by the Gauss-Newton (linearised) covariance Cov = s2 (J^T J)^-1, J the
  residuals' Jacobian in theta, s2 = S / (n - p), n the rows used (NaN when n = p).
* Not identifiable: two parameters correlated beyond :data:`MAX_CORRELATION` (a near-dependence
  of several columns of J shows as such pairs), the scaled Jacobian's condition number beyond
  :data:`MAX_CONDITION`, or a parameter moving the residuals across its whole bounds by no more
  than :data:`NOISE_MARGIN` times the finite-difference noise (the data do not see it).

Leave-one-out is :func:`rodimpact.analysis.calibration_loo.leave_one_out`; docs/calibration.md
gives the method in words.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "DEFAULT_FAILURES",
    "MAX_CONDITION",
    "MAX_CORRELATION",
    "MAX_TRIALS",
    "MODEL_TOLERANCE",
    "NOISE_MARGIN",
    "SHORT_OF_MINIMUM",
    "STEP",
    "XTOL",
    "Calibration",
    "CalibrationInputError",
    "ModelFailure",
    "Observation",
    "Parameter",
    "calibrate",
    "check_inputs",
]

log = logging.getLogger(__name__)

#: Beyond this correlation of two fitted parameters the data cannot tell them apart: the variance
#: of their best-determined combination is below (1 - 0.95) / (1 + 0.95) = 2.6 % of the worst's.
MAX_CORRELATION = 0.95
#: Beyond this condition number of the scaled Jacobian J, J^T J (inverted for the covariance) has
#: one of 1e16 = 1 / machine epsilon: its inverse has no correct digit. A model with solver noise
#: meets :data:`NOISE_MARGIN` first.
MAX_CONDITION = 1e8
#: The finite-difference step in u: the derivative's error is about eps / (STEP c) for a model
#: accurate to eps whose predictions change by a fraction c across the bounds (1e-3 / c at
#: eps = 1e-6; 1e-2 / c at a step of 1e-4); the truncation error, STEP^2 / 6 relative, is 2e-7.
STEP = 1e-3
#: The relative accuracy assumed of the model's predictions (a solver's relative tolerance).
MODEL_TOLERANCE = 1e-6
#: A parameter's scaled column must exceed this many times its finite-difference noise (its
#: derivative then known to 10 %) for the data to count as seeing it.
NOISE_MARGIN = 10.0
#: The optimiser's step tolerance in u: below any standard error worth stating, above the
#: jitter of the minimum of S for a model accurate to 1e-6.
XTOL = 1e-6
#: A fit ends short of the minimum when the linearised minimum lies beyond this many standard
#: errors (Mahalanobis): the model failing across the way, or an optimiser stopped early.
SHORT_OF_MINIMUM = 0.1
#: The optimiser's trial points at most (the Jacobian's evaluations not counted).
MAX_TRIALS = 50


class ModelFailure(RuntimeError):
    """The model could not predict at a theta (its solver failed): the trial is unusable."""


#: The exceptions of a model that make a trial unusable rather than end the fit.
DEFAULT_FAILURES: tuple[type[BaseException], ...] = (ModelFailure, ArithmeticError)


class CalibrationInputError(ValueError):
    """An argument of the calibration is wrong; ``field`` names it (``"parameters.<name>.low"``)."""

    def __init__(self, field: str, message: str) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field


@dataclass(frozen=True)
class Parameter:
    """A declared constant to fit: ``name`` its path (``"rod.youngs_modulus_pa"``), ``low`` <
    ``high`` its finite bounds and ``start`` (None: the mid-point) in ``unit``, ``source`` where
    the bounds come from."""

    name: str
    low: float
    high: float
    start: float | None = None
    unit: str = ""
    source: str = ""


@dataclass(frozen=True)
class Observation:
    """A measurement of ``quantity`` in ``case`` (leave-one-out holds out whole cases):
    ``measured`` finite and ``scale`` > 0 in the quantity's unit, r = (predicted - measured) /
    scale (``abs(measured)`` for relative residuals, or a stated standard uncertainty)."""

    case: str
    quantity: str
    measured: float
    scale: float


@dataclass(frozen=True, eq=False)
class Calibration:
    """The fitted constants, their uncertainty and how far to trust them (module docstring).

    Attributes
    ----------
    parameters, observations, rows_used : tuple
        As given (p and n of them), and the observations fitted (the others predicted only).
    values, standard_errors, at_bound : ndarray, shape (p,)
        The fit and its standard errors in the parameters' units (NaN when n = p, inf for a
        parameter unseen), and True where a bound holds the fit (the data pull it beyond).
    covariance, correlation : ndarray, shape (p, p)
        s2 (J^T J)^-1 (products of the parameters' units), and normalised by its diagonal (1).
    residuals, predicted, jacobian : ndarray, shape (n,), (n,), (n, p)
        r_i (1), f_i (quantity's unit) and d f_i / d theta_j of every observation at ``values``.
    dof, s2, condition_number : int, float, float
        n - p, S / (n - p) (NaN when n = p), the condition number of the scaled Jacobian.
    identifiable, warnings : bool, tuple of str
        False when a parameter is unseen or parameters cannot be told apart; a sentence each.
    success, status, message : bool, str, str
        ``status`` ``"converged"`` (``success``), ``"at_bound"``, ``"not_identifiable"`` or
        ``"failed"``, and in words.
    evaluations, failed_trials : int
        The model calls this fit made (a shared cache's earlier ones not counted), and the
        distinct thetas where the model failed for the rows used.
    """

    parameters: tuple[Parameter, ...]
    observations: tuple[Observation, ...]
    rows_used: tuple[int, ...]
    values: NDArray[np.float64]
    standard_errors: NDArray[np.float64]
    covariance: NDArray[np.float64]
    correlation: NDArray[np.float64]
    residuals: NDArray[np.float64]
    predicted: NDArray[np.float64]
    jacobian: NDArray[np.float64]
    dof: int
    s2: float
    condition_number: float
    at_bound: NDArray[np.bool_]
    identifiable: bool
    warnings: tuple[str, ...]
    success: bool
    status: str
    message: str
    evaluations: int
    failed_trials: int

    def table_rows(self) -> list[dict[str, Any]]:
        """A plain dict a parameter: declaration, value, standard error, correlations, bound flag."""
        names = [q.name for q in self.parameters]
        return [
            {"name": p.name, "unit": p.unit, "source": p.source, "low": p.low, "high": p.high, "start": p.start}
            | {"value": float(self.values[j]), "standard_error": float(self.standard_errors[j])}
            | {"correlation": dict(zip(names, self.correlation[j].tolist())), "at_bound": bool(self.at_bound[j])}
            for j, p in enumerate(self.parameters)
        ]


def _finite(x: object) -> bool:
    return isinstance(x, int | float | np.integer | np.floating) and math.isfinite(float(x))


def check_inputs(
    observations: Sequence[Observation], parameters: Sequence[Parameter], rows: Sequence[int] | None = None
) -> tuple[tuple[Observation, ...], tuple[Parameter, ...], tuple[int, ...]]:
    """The observations, parameters and rows used (default all), checked before any model call;
    else :class:`CalibrationInputError` with ``field`` ``"parameters"`` (none, duplicate names,
    more than the rows used), ``"parameters.<name>.low"`` (``.high``, ``.start``),
    ``"observations"``, ``"observations[i]"`` or ``"rows"``."""
    params, obs = tuple(parameters), tuple(observations)
    if not params or not all(isinstance(p, Parameter) for p in params):
        raise CalibrationInputError("parameters", "must be a non-empty sequence of Parameter")
    if len({p.name for p in params}) != len(params):
        raise CalibrationInputError("parameters", f"duplicate names in {[p.name for p in params]}")
    for p in params:
        for bound in ("low", "high"):
            if not _finite(getattr(p, bound)):
                raise CalibrationInputError(f"parameters.{p.name}.{bound}", f"must be finite, got {p!r}")
        if not p.low < p.high:
            raise CalibrationInputError(f"parameters.{p.name}.low", f"must be below high, got {p!r}")
        if p.start is not None and not (_finite(p.start) and p.low <= p.start <= p.high):
            raise CalibrationInputError(f"parameters.{p.name}.start", f"must lie in the bounds, got {p!r}")
    if not obs:
        raise CalibrationInputError("observations", "must be a non-empty sequence of Observation")
    for i, o in enumerate(obs):
        if not isinstance(o, Observation) or not (isinstance(o.case, str) and o.case and _finite(o.measured)):
            raise CalibrationInputError(f"observations[{i}]", f"needs a case and a finite measured value: {o!r}")
        if not (_finite(o.scale) and o.scale > 0):
            raise CalibrationInputError(f"observations[{i}]", f"needs a finite scale > 0: {o!r}")
    try:
        used = tuple(range(len(obs))) if rows is None else tuple(int(i) for i in rows)
    except (TypeError, ValueError) as error:
        raise CalibrationInputError("rows", f"must be observation indices, got {rows!r}") from error
    if not used or len(set(used)) != len(used) or not all(0 <= i < len(obs) for i in used):
        raise CalibrationInputError("rows", f"must be distinct indices in [0, {len(obs)}), got {rows!r}")
    if len(used) < len(params):
        field = "parameters" if rows is None else "rows"
        raise CalibrationInputError(field, f"{len(params)} parameters but {len(used)} observations to fit")
    return obs, params, used


#: (offsets in steps, weights) of the differences tried: central, one-sided of order 2, then 1.
_STENCILS = (
    ((-1, 1), (-0.5, 0.5)),
    ((0, 1, 2), (-1.5, 2.0, -0.5)),
    ((-2, -1, 0), (0.5, -2.0, 1.5)),
    ((0, 1), (-1.0, 1.0)),
    ((-1, 0), (-1.0, 1.0)),
)


class _StencilFailed(Exception):
    """No stencil of a derivative works: ``args`` (the parameter's index, u)."""


class _Problem:
    """The residuals in u and their Jacobian, through the model's cache: a key is theta to 13
    significant digits (so its round trip through u is one evaluation); a failed one holds None."""

    def __init__(self, model, failures, cache: dict, obs, params, used) -> None:
        self.model, self.failures, self.cache, self.n, self.used = model, failures, cache, len(obs), np.asarray(used)
        self.low = np.array([p.low for p in params], dtype=float)
        self.width = np.array([p.high for p in params], dtype=float) - self.low
        self.measured = np.array([o.measured for o in obs], dtype=float)
        self.scale = np.array([o.scale for o in obs], dtype=float)
        self.unusable: set[tuple[float, ...]] = set()

    def theta(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        return self.low + u * self.width

    def predict(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        theta = self.theta(u)
        key = tuple(float(f"{x:.13g}") for x in theta)
        if key not in self.cache:
            log.debug("model evaluation at %s", theta)
            try:
                self.cache[key] = np.array(self.model(theta.copy()), dtype=float)
            except self.failures as error:
                log.info("the model failed at %s: %s: %s", theta, type(error).__name__, error)
                self.cache[key] = None
        f = np.full(self.n, math.nan) if self.cache[key] is None else self.cache[key]
        if f.shape != (self.n,):
            raise CalibrationInputError("model", f"must return shape ({self.n},), got {f.shape}")
        if not self.usable(f):
            self.unusable.add(key)
        return f

    def usable(self, f: NDArray[np.float64]) -> bool:
        return bool(np.all(np.isfinite(f[self.used])))

    def residuals(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        return ((self.predict(u) - self.measured) / self.scale)[self.used]

    def jacobian(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        """d r / d u, shape (n, p), by the first stencil inside [0, 1] at which the model works."""
        out = np.empty((self.n, u.size))
        for j in range(u.size):
            for offsets, weights in _STENCILS:
                points = [u + k * STEP * np.eye(u.size)[j] if k else u for k in offsets]
                if all(0.0 <= x[j] <= 1.0 for x in points):
                    values = []
                    for x in points:
                        if not self.usable(f := self.predict(x)):
                            break
                        values.append(f)
                    else:
                        out[:, j] = sum(w * f for w, f in zip(weights, values)) / (STEP * self.scale)
                        break
            else:
                raise _StencilFailed(j, u)
        return out


def _diagnose(names, jr, noise: float) -> tuple[NDArray[np.float64], NDArray[np.float64], float, list[str]]:
    """(J^T J)^-1, its correlation and cond(J) of J, shape (m, p), and the identifiability
    warnings (``noise``: a column's). A zero column, and every column of a singular J, gets an
    infinite variance and NaN covariances."""
    p, norms, found = jr.shape[1], np.linalg.norm(jr, axis=0), []
    inv = np.where(np.eye(p) > 0, math.inf, math.nan)
    if (seen := np.flatnonzero(norms > 0)).size:
        _, s, vt = np.linalg.svd(jr[:, seen], full_matrices=False)
        if s[-1] > s[0] * max(jr.shape) * np.finfo(float).eps:
            inv[np.ix_(seen, seen)] = (vt.T / s**2) @ vt
    sv, d = np.linalg.svd(jr, compute_uv=False), np.sqrt(np.diag(inv))
    cond = math.inf if sv[-1] == 0 else float(sv[0] / sv[-1])
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = np.where(np.isfinite(np.outer(d, d)), inv / np.outer(d, d), math.nan)
    for j in np.flatnonzero(norms <= NOISE_MARGIN * noise):
        found.append(f"the data do not see {names[j]}: across its bounds it moves the residuals by {norms[j]:.3g}")
    for i, j in zip(*np.triu_indices(p, 1)):
        if abs(corr[i, j]) > MAX_CORRELATION:
            found.append(
                f"{names[i]} and {names[j]} are correlated at {corr[i, j]:.3f}: the data cannot tell them apart"
            )
    if cond > MAX_CONDITION:
        found.append(
            f"the Jacobian is near-singular (condition number {cond:.1e}): the data do not fix every parameter"
        )
    return inv, corr, cond, found


def _frozen(values: Any, dtype: type = float) -> NDArray[Any]:
    out = np.array(values, dtype=dtype)
    out.setflags(write=False)
    return out


def calibrate(
    model: Callable[[NDArray[np.float64]], Any],
    observations: Sequence[Observation],
    parameters: Sequence[Parameter],
    *,
    rows: Sequence[int] | None = None,
    cache: dict | None = None,
    model_tolerance: float = MODEL_TOLERANCE,
    max_trials: int = MAX_TRIALS,
    failures: tuple[type[BaseException], ...] = DEFAULT_FAILURES,
) -> Calibration:
    """Fit the parameters to the observations (module docstring for the method).

    Parameters
    ----------
    model : callable
        ``model(theta)``, theta shape (p,) in the parameters' units, returns every observation's
        prediction, shape (n,); it may raise one of ``failures`` or return NaN where it cannot.
    observations, parameters : sequence of Observation (n), of Parameter (p)
    rows : sequence of int, optional
        The observations fitted (default all); the others are predicted only.
    cache : dict, optional
        The model's evaluations, filled here; pass one dict to several fits of one model to share.
    model_tolerance, max_trials
        The model's relative accuracy (>= 0), the optimiser's trial points at most (>= 1).

    Returns
    -------
    Calibration
        ``status="failed"`` (no exception) when the model fails at the start or at every point of
        a derivative's stencil, or the trials run out.

    Raises
    ------
    CalibrationInputError
        Before any model call (:func:`check_inputs`, ``"model"``, ``"model_tolerance"``,
        ``"max_trials"``); ``"model"`` for a model returning the wrong shape.
    """
    obs, params, used = check_inputs(observations, parameters, rows)
    if not callable(model):
        raise CalibrationInputError("model", f"must be callable, got {model!r}")
    if not (_finite(model_tolerance) and model_tolerance >= 0):
        raise CalibrationInputError("model_tolerance", f"must be finite and >= 0, got {model_tolerance!r}")
    if not (isinstance(max_trials, int) and max_trials >= 1):
        raise CalibrationInputError("max_trials", f"must be an integer >= 1, got {max_trials!r}")
    cache = {} if cache is None else cache
    before, problem = len(cache), _Problem(model, tuple(failures), cache, obs, params, used)
    names, p, n_used = tuple(q.name for q in params), len(params), len(used)
    start = np.array([(q.low + q.high) / 2 if q.start is None else q.start for q in params], dtype=float)
    u = np.clip((start - problem.low) / problem.width, 1e-10, 1 - 1e-10)
    jac, found, at_bound, identifiable = np.full((len(obs), p), math.nan), [], np.zeros(p, bool), False
    inv = corr = np.full((p, p), math.nan)
    cond, status = math.nan, "failed"
    if not problem.usable(problem.predict(u)):
        message = f"the model fails at the start {np.array2string(problem.theta(u), precision=6)}"
    else:
        from scipy.optimize import least_squares

        try:
            result = least_squares(
                problem.residuals, u, jac=lambda x: problem.jacobian(x)[problem.used], bounds=(0.0, 1.0),
                method="trf", x_scale=1.0, ftol=1e-8, xtol=XTOL, gtol=1e-8, max_nfev=max_trials,
            )  # fmt: skip
            u, jac = result.x, problem.jacobian(result.x)
        except _StencilFailed as failed:
            u, message = failed.args[1], f"the model fails at every difference point of {names[failed.args[0]]}"
        else:
            jr, mask, r = jac[problem.used], result.active_mask, problem.residuals(u)
            gradient = jr.T @ r  # a parameter is held by its bound where S falls beyond it
            at_bound = ((mask < 0) | (u <= XTOL)) & (gradient > 0) | ((mask > 0) | (u >= 1 - XTOL)) & (gradient < 0)
            noise = model_tolerance * np.linalg.norm(problem.predict(u)[problem.used] / problem.scale[problem.used])
            inv, corr, cond, found = _diagnose(names, jr, float(noise) / (math.sqrt(2.0) * STEP))
            identifiable = not found
            for j in np.flatnonzero(at_bound):
                value = f"{problem.theta(u)[j]:.6g} {params[j].unit}".strip()
                found.append(f"the fit lies at a bound of {names[j]} ({value}): the data pull it beyond")
            free = ~at_bound  # S falls by |P r|^2 to its linearised minimum, P the projection on J's free columns
            short = np.sum((jr[:, free] @ np.linalg.lstsq(jr[:, free], r, rcond=None)[0]) ** 2) if free.any() else 0
            # a parameter the data do not determine has no minimum to stop short of, and no bound
            # that holds it for a reason: not_identifiable goes before both
            if result.status == 0:
                message = f"the optimiser ran out of trials ({max_trials}) before converging"
            elif not identifiable:
                status, message = "not_identifiable", "the data do not determine every parameter"
            elif short > SHORT_OF_MINIMUM**2 * np.sum(r**2) / max(n_used - p, 1):
                message = "the fit stopped short of the minimum" + ", where the model fails" * bool(problem.unusable)
            elif at_bound.any():
                status, message = "at_bound", "the fit lies at a bound: its standard errors assume an inner minimum"
            else:
                status, message = "converged", f"converged: {result.message}"
    f = problem.predict(u)
    r = (f - problem.measured) / problem.scale
    ssr = float(np.sum(r[problem.used] ** 2))
    s2 = ssr / (n_used - p) if n_used > p else math.nan
    with np.errstate(invalid="ignore"):
        cov = np.where(np.isnan(inv), math.nan, s2 * inv * np.outer(problem.width, problem.width))
    if n_used == p:
        found.append("as many observations as parameters: s2 and the standard errors are undefined (NaN)")
    if problem.unusable:
        found.append(f"the model failed at {len(problem.unusable)} theta(s) of the fit, left out as unusable")
    (log.info if status == "converged" else log.warning)("calibration of %s: %s: %s", names, status, message)
    for sentence in found:
        log.warning("calibration of %s: %s", names, sentence)
    return Calibration(
        parameters=params, observations=obs, rows_used=used, values=_frozen(problem.theta(u)),
        standard_errors=_frozen(np.sqrt(np.diag(cov))), covariance=_frozen(cov), correlation=_frozen(corr),
        residuals=_frozen(r), predicted=_frozen(f), jacobian=_frozen(jac * problem.scale[:, None] / problem.width),
        dof=n_used - p, s2=s2, condition_number=cond, at_bound=_frozen(at_bound, bool), identifiable=identifiable,
        warnings=tuple(found), success=status == "converged", status=status, message=message,
        evaluations=len(cache) - before, failed_trials=len(problem.unusable),
    )  # fmt: skip
