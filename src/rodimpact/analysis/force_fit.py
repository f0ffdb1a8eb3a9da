"""A compact closed form of a computed contact force, to hand on to other studies.

The paper's conclusion asks for the contact force as an input to dynamic-buckling studies.
A run's force history P(t) is zero outside its contact intervals [t0_i, t1_i]; on each it is
fitted by a Chebyshev series

    P(t) = sum_{k=0}^{n_i} c_ik T_k(x),   x = (2 t - t0_i - t1_i) / (t1_i - t0_i),

(least squares on the computed samples, Chebyshev's own basis, so the fit is well conditioned
at any degree), and P(t) = 0 outside the intervals. Each interval's degree is the lowest that
brings the largest error over its samples to ``rel_tol`` of the run's largest force, up to
:data:`MAX_DEGREE`. The error is not assumed: :func:`fit_force` measures it on every sample of
the computed force, including those outside the intervals, and reports it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.polynomial import chebyshev
from numpy.typing import ArrayLike, NDArray

__all__ = ["DEFAULT_REL_TOL", "FORMULA", "MAX_DEGREE", "ContactPiece", "ForceFit", "fit_force"]

#: The largest degree of one interval's series.
MAX_DEGREE = 60
#: The default target of the largest error, as a fraction of the largest force.
DEFAULT_REL_TOL = 0.01
#: The formula, as the exported file states it.
FORMULA = (
    "P(t) = sum_k c[k] T_k(x) with x = (2 t - t0 - t1) / (t1 - t0) on each contact interval "
    "t0 <= t <= t1 (T_k the Chebyshev polynomials of the first kind: T_0 = 1, T_1 = x, "
    "T_k+1 = 2 x T_k - T_k-1); P(t) = 0 outside the intervals. SI units: t in s, P in N."
)


@dataclass(frozen=True)
class ContactPiece:
    """One contact interval and its series.

    Attributes
    ----------
    t0_s, t1_s : float
        The interval, s.
    coefficients : tuple of float
        c_0 .. c_n, N.
    max_abs_error_N : float
        The largest |fit - computed force| over the run's samples inside the interval, N.
    """

    t0_s: float
    t1_s: float
    coefficients: tuple[float, ...]
    max_abs_error_N: float

    def evaluate(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The series at times ``t`` inside the interval, N."""
        x = (2.0 * t - self.t0_s - self.t1_s) / (self.t1_s - self.t0_s)
        return chebyshev.chebval(x, np.asarray(self.coefficients))


@dataclass(frozen=True)
class ForceFit:
    """The closed form of a force history and its measured error.

    Attributes
    ----------
    pieces : tuple of ContactPiece
        One per contact interval, in time order.
    peak_force_N : float
        The computed force's largest value, N.
    max_abs_error_N : float
        The largest |fit - computed force| over every sample of the run, N.
    rel_tol : float
        The target the degrees were chosen for (fraction of ``peak_force_N``).
    """

    pieces: tuple[ContactPiece, ...]
    peak_force_N: float
    max_abs_error_N: float
    rel_tol: float

    @property
    def max_rel_error(self) -> float:
        """The largest error as a fraction of the largest force."""
        return self.max_abs_error_N / self.peak_force_N if self.peak_force_N > 0 else 0.0

    def evaluate(self, t: ArrayLike) -> NDArray[np.float64]:
        """P(t), N, shape of ``t``: each piece inside its interval, zero elsewhere."""
        t = np.asarray(t, dtype=float)
        out = np.zeros_like(t)
        for piece in self.pieces:
            inside = (t >= piece.t0_s) & (t <= piece.t1_s)
            out[inside] = piece.evaluate(t[inside])
        return out

    def to_mapping(self) -> dict[str, Any]:
        """Plain JSON types: the formula, each interval's coefficients, the errors."""
        return {
            "formula": FORMULA,
            "intervals": [
                {
                    "t0_s": p.t0_s,
                    "t1_s": p.t1_s,
                    "degree": len(p.coefficients) - 1,
                    "coefficients_N": list(p.coefficients),
                    "max_abs_error_N": p.max_abs_error_N,
                }
                for p in self.pieces
            ],
            "peak_force_N": self.peak_force_N,
            "max_abs_error_N": self.max_abs_error_N,
            "max_rel_error": self.max_rel_error,
            "rel_tol": self.rel_tol,
        }


def _fit_piece(
    t: NDArray[np.float64], force: NDArray[np.float64], t0: float, t1: float, target_N: float
) -> ContactPiece:
    """The lowest-degree series on [t0, t1] within ``target_N`` on the samples there."""
    inside = (t >= t0) & (t <= t1)
    ts, ps = t[inside], force[inside]
    x = (2.0 * ts - t0 - t1) / (t1 - t0)
    best = None
    for degree in range(0, min(MAX_DEGREE, max(len(ts) - 1, 0)) + 1):
        coefficients = chebyshev.chebfit(x, ps, degree)
        error = float(np.max(np.abs(chebyshev.chebval(x, coefficients) - ps), initial=0.0))
        best = (coefficients, error)
        if error <= target_N:
            break
    coefficients, error = best if best is not None else (np.zeros(1), 0.0)
    return ContactPiece(float(t0), float(t1), tuple(float(c) for c in coefficients), error)


def fit_force(
    t: ArrayLike, force: ArrayLike, intervals: Sequence[tuple[float, float]], rel_tol: float = DEFAULT_REL_TOL
) -> ForceFit:
    """Fit a computed force history by a Chebyshev series on each contact interval.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, s, increasing.
    force : array_like, shape (n,)
        The computed contact force at ``t``, N (zero outside the contacts).
    intervals : sequence of (float, float)
        The contact intervals [t0, t1], s, in time order.
    rel_tol : float
        Target of the largest error, as a fraction of the largest force (> 0).

    Returns
    -------
    ForceFit
        The series and the error measured on every sample of ``force``.
    """
    t, force = np.asarray(t, dtype=float), np.asarray(force, dtype=float)
    if t.shape != force.shape or t.ndim != 1:
        raise ValueError(f"t and force must be 1-D of one length, got {t.shape} and {force.shape}")
    if not rel_tol > 0:
        raise ValueError(f"rel_tol must be > 0, got {rel_tol!r}")
    peak = float(np.max(force, initial=0.0))
    pieces = tuple(_fit_piece(t, force, float(t0), float(t1), rel_tol * peak) for t0, t1 in intervals if t1 > t0)
    fit = ForceFit(pieces, peak, 0.0, rel_tol)
    error = float(np.max(np.abs(fit.evaluate(t) - force), initial=0.0))
    return ForceFit(pieces, peak, error, rel_tol)
