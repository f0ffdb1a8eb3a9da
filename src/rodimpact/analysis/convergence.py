"""Observed orders of convergence and Roache's grid convergence index.

Pure tools for a sequence of solutions of one problem at refined resolutions:

- :func:`fitted_order`: the slope of log(error) against log(h) by least squares
  (``np.polyfit``), with the standard error of the slope, for errors measured against a
  reference;
- :func:`grid_convergence_index`: Roache's grid convergence index from three solutions at a
  constant refinement ratio r (no reference needed). With f1 the finest, f2 and f3 the coarser
  ones, the observed order is

      p = ln((f3 - f2) / (f2 - f1)) / ln r,

  the extrapolated value f_ext = f1 + (f1 - f2) / (r^p - 1), and the fine solution's
  uncertainty

      GCI_21 = Fs |(f1 - f2) / f1| / (r^p - 1),

  with the safety factor Fs = 1.25 for three grids (Roache 1994, J. Fluids Eng. 116, 405; the
  ASME V&V 20 procedure of Celik et al. 2008, J. Fluids Eng. 130, 078001). When (f3 - f2) and
  (f2 - f1) have opposite signs the convergence is oscillatory: p is not defined and neither is
  the index (NaN, with ``monotone`` False);
- :func:`oscillatory_uncertainty`: where the index is not defined, the uncertainty of an
  oscillatory convergence, half the range of the three solutions relative to the finest,
  U_osc = (max f - min f) / (2 |f1|) (Stern et al. 2001, J. Fluids Eng. 123, 793);
  :func:`numerical_uncertainty` gives the index where it is defined and U_osc otherwise;
- :func:`is_monotone`, :func:`changes_sign` and :func:`constant_ratio`: whether errors fall at
  every refinement, whether signed errors cross zero, and the refinement ratio of three levels
  when it is constant (the index needs one).

References are repeated in docs/studies.md in our own words.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = [
    "GCI_SAFETY_FACTOR",
    "FittedOrder",
    "GridConvergence",
    "NumericalUncertainty",
    "changes_sign",
    "constant_ratio",
    "fitted_order",
    "grid_convergence_index",
    "is_monotone",
    "numerical_uncertainty",
    "oscillatory_uncertainty",
]

#: Roache's safety factor for a study of three (or more) grids.
GCI_SAFETY_FACTOR = 1.25


@dataclass(frozen=True)
class FittedOrder:
    """The slope of log(error) against log(h).

    Attributes
    ----------
    order : float
        The fitted slope (NaN with fewer than two points).
    stderr : float
        Its standard error from the residuals of the fit (NaN with fewer than three points).
    points : int
        The number of (h, error) pairs fitted.
    """

    order: float
    stderr: float
    points: int


def fitted_order(h: Sequence[float], error: Sequence[float]) -> FittedOrder:
    """The observed order: least squares of log(error) on log(h).

    Parameters
    ----------
    h : sequence of float
        Mesh sizes or steps (any unit; only their ratios matter), > 0.
    error : sequence of float
        The errors at those resolutions, > 0 (same length).

    Returns
    -------
    FittedOrder
        The slope and its standard error sqrt(s^2 / sum (x - mean x)^2), s^2 the residuals'
        sum of squares over (n - 2).
    """
    x, y = np.log(np.asarray(h, float)), np.log(np.asarray(error, float))
    if x.shape != y.shape:
        raise ValueError(f"h and error differ in length: {x.size} and {y.size}")
    n = x.size
    if n < 2:
        return FittedOrder(math.nan, math.nan, n)
    slope, intercept = np.polyfit(x, y, 1)
    if n < 3:
        return FittedOrder(float(slope), math.nan, n)
    residual = y - (slope * x + intercept)
    spread = float(np.sum((x - x.mean()) ** 2))
    stderr = math.sqrt(float(np.sum(residual**2)) / (n - 2) / spread) if spread > 0 else math.nan
    return FittedOrder(float(slope), stderr, n)


def is_monotone(error: Sequence[float]) -> bool:
    """Whether errors ordered from coarse to fine strictly decrease in magnitude."""
    magnitude = np.abs(np.asarray(error, float))
    return bool(magnitude.size >= 2 and np.all(np.diff(magnitude) < 0))


def changes_sign(signed_error: Sequence[float]) -> bool:
    """Whether signed errors (any order, NaN ignored) take both signs: the error crosses zero
    between some of these levels, so a single level can look better than its resolution."""
    values = np.asarray(signed_error, float)
    values = values[np.isfinite(values)]
    return bool(np.any(values > 0) and np.any(values < 0))


def constant_ratio(resolutions: Sequence[float], rel: float = 1e-9) -> float:
    """The refinement ratio r of resolutions (proportional to 1/h, coarse to fine) when every
    consecutive ratio is the same within ``rel``, else NaN.

    Parameters
    ----------
    resolutions : sequence of float
        At least two resolutions, > 0, increasing (elements across, steps per contact...).
    rel : float
        Relative tolerance on the equality of the ratios.
    """
    values = np.asarray(resolutions, float)
    if values.size < 2 or np.any(values <= 0):
        return math.nan
    ratios = values[1:] / values[:-1]
    return float(ratios[0]) if np.allclose(ratios, ratios[0], rtol=rel, atol=0.0) and ratios[0] > 1 else math.nan


@dataclass(frozen=True)
class GridConvergence:
    """Roache's grid convergence index of the finest of three solutions (module docstring).

    Attributes
    ----------
    order : float
        The observed order p (NaN when the convergence is oscillatory).
    extrapolated : float
        f_ext, the Richardson extrapolation at that order.
    gci : float
        GCI_21, relative to f1 (a fraction; NaN when oscillatory).
    monotone : bool
        Whether (f3 - f2) and (f2 - f1) have the same sign.
    ratio : float
        The refinement ratio r.
    """

    order: float
    extrapolated: float
    gci: float
    monotone: bool
    ratio: float


def grid_convergence_index(
    fine: float, medium: float, coarse: float, ratio: float, safety_factor: float = GCI_SAFETY_FACTOR
) -> GridConvergence:
    """The grid convergence index of ``fine`` from three solutions at the constant ratio ``ratio``.

    Parameters
    ----------
    fine, medium, coarse : float
        f1, f2, f3: the quantity on the finest, the middle and the coarsest resolution.
    ratio : float
        r = h3 / h2 = h2 / h1 > 1.
    safety_factor : float
        Fs (1.25 for three grids).

    Raises
    ------
    ValueError
        ``ratio`` is not above 1.
    """
    if not ratio > 1.0:
        raise ValueError(f"ratio: the refinement ratio must be > 1, got {ratio}")
    e21, e32 = fine - medium, medium - coarse
    if e21 == 0.0:
        return GridConvergence(math.inf, fine, 0.0, True, ratio)
    if e32 == 0.0 or (e32 > 0) != (e21 > 0):
        return GridConvergence(math.nan, math.nan, math.nan, False, ratio)
    order = math.log(e32 / e21) / math.log(ratio)
    if order <= 0.0:  # the differences grow as the grid is refined: no convergence to extrapolate
        return GridConvergence(order, math.nan, math.nan, True, ratio)
    factor = ratio**order - 1.0
    return GridConvergence(order, fine + e21 / factor, safety_factor * abs(e21 / fine) / factor, True, ratio)


def oscillatory_uncertainty(fine: float, medium: float, coarse: float) -> float:
    """U_osc: half the range of three solutions, relative to |fine| (a fraction).

    The uncertainty Stern et al. (2001) give a solution whose convergence oscillates, where
    Richardson extrapolation and the grid convergence index are not defined.
    """
    values = (fine, medium, coarse)
    return 0.5 * (max(values) - min(values)) / abs(fine)


@dataclass(frozen=True)
class NumericalUncertainty:
    """The discretisation uncertainty of the finest of three solutions.

    Attributes
    ----------
    index : GridConvergence
        Roache's index of the three (its ``gci`` is NaN when oscillatory or diverging, or when
        the ratio is not constant).
    half_range : float
        U_osc of the three (a fraction of the finest), :func:`oscillatory_uncertainty`.
    """

    index: GridConvergence
    half_range: float

    @property
    def oscillatory(self) -> bool:
        """Whether the differences between the levels change sign."""
        return not self.index.monotone

    @property
    def value(self) -> float:
        """The uncertainty quoted (a fraction): the index where it is defined, else U_osc."""
        return self.index.gci if math.isfinite(self.index.gci) else self.half_range


def numerical_uncertainty(
    fine: float, medium: float, coarse: float, ratio: float, safety_factor: float = GCI_SAFETY_FACTOR
) -> NumericalUncertainty:
    """The GCI of ``fine`` where its three levels converge monotonically, else U_osc.

    Parameters
    ----------
    fine, medium, coarse : float
        f1, f2, f3 (as :func:`grid_convergence_index`).
    ratio : float
        The constant refinement ratio r > 1, or NaN when the ratio is not constant (then only
        U_osc, which needs none, is given).
    safety_factor : float
        Fs (1.25 for three grids).
    """
    half = oscillatory_uncertainty(fine, medium, coarse)
    if not ratio > 1.0:
        monotone = (fine - medium) * (medium - coarse) > 0 or fine == medium
        return NumericalUncertainty(GridConvergence(math.nan, math.nan, math.nan, monotone, ratio), half)
    return NumericalUncertainty(grid_convergence_index(fine, medium, coarse, ratio, safety_factor), half)
