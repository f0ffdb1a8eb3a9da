"""An error relative to a reference, signed: the one definition every table, comparison and fit uses."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["relative_error_pct"]


def relative_error_pct(value: ArrayLike, reference: ArrayLike) -> float | NDArray[np.float64]:
    """The error of ``value`` relative to ``reference``, signed, %: 100 (value - reference) / |reference|.

    Parameters
    ----------
    value, reference : float or array_like
        Of one shape (or broadcastable), in one unit.

    Returns
    -------
    float or ndarray
        A float for scalars; NaN where the reference is zero or either is not finite. The
        paper's Table 2 reads |error| (an absolute value of this).
    """
    value_a, reference_a = np.asarray(value, float), np.asarray(reference, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        error = 100.0 * (value_a - reference_a) / np.abs(reference_a)
    error = np.where((reference_a == 0.0) | ~np.isfinite(error), math.nan, error)
    return float(error) if error.ndim == 0 else error
