"""A contact law given as a measured or computed curve P(alpha): the ``tabulated`` law.

The curve comes from the continuum's static indentation of the case's own ball, film and
rod (the workflow's ``indentation`` rule, written by :mod:`rodimpact.storage.curves`); the 1-D
methods then use it as their contact law, so the quasi-static contact is the continuum's
and not the thin-layer or half-space idealisation.

Interpolation: monotone piecewise-cubic Hermite (Fritsch-Carlson slopes, as
``scipy.interpolate.PchipInterpolator``) of ln P against ln alpha. In these coordinates
every power law P = C alpha^n is a straight line, which the interpolant reproduces exactly
(Hertz's law, the thin film's P = c delta^2 at small loads), and the interpolant is monotone
and C1, so P is monotone and dP/dalpha = n(alpha) P / alpha is continuous: the step solve
has one root and the implicit scheme keeps its order. Outside the table the end slopes
extend the curve as power laws (a run that reaches beyond the table's largest approach is
reported in its summary). The interpolation error is measured by the indentation rule
(every other point left out) and shown in ``results/tables/film_indentation.csv``.
"""

from __future__ import annotations

import logging
import math
from bisect import bisect_right
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.contact.film import FilmSettings
from rodimpact.contact.hertz import ElasticMaterial
from rodimpact.contact.law import ContactLaw, LawSettings, Needs
from rodimpact.contact.stack import StackSettings
from rodimpact.settings.declare import REQUIRED, OptionError, setting

__all__ = ["CURVE_NUMERICS", "CURVE_SOURCES", "CurveMissing", "TabulatedLaw", "TabulatedSettings", "pchip_slopes"]

log = logging.getLogger(__name__)

# 8-point Gauss-Legendre nodes and weights on [0, 1]
_GX, _GW = np.polynomial.legendre.leggauss(8)
_GX, _GW = 0.5 * (_GX + 1.0), 0.5 * _GW


#: Where a curve may come from -> the workflow rule that computes it.
CURVE_SOURCES = {"fem_axi_indentation": "indentation"}
#: That rule -> the method whose numerics (``numerics.<method>``) are its settings.
CURVE_NUMERICS = {"indentation": "fem_axi"}


def _hermite(x, x0, x1, y0, y1, d0, d1):
    """The cubic Hermite piece through (x0, y0) and (x1, y1) with slopes d0 and d1, and its
    slope, at ``x``: one formula for arrays (numpy) and for Python floats (the steppers' scalar
    path), so both give the same numbers."""
    h = x1 - x0
    t = (x - x0) / h
    t2, t3 = t * t, t * t * t
    y = (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * d0 + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * h * d1
    dy = (6 * t2 - 6 * t) * y0 / h + (3 * t2 - 4 * t + 1) * d0 + (-6 * t2 + 6 * t) * y1 / h + (3 * t2 - 2 * t) * d1
    return y, dy


@dataclass(frozen=True, kw_only=True)
class TabulatedSettings(LawSettings):
    """The ``tabulated`` law's settings: where its curve comes from, and the case's film or stack."""

    curve_from: str = setting(
        REQUIRED,
        "Where the curve comes from: fem_axi_indentation, the continuum's static indentation of the "
        "case's ball, film and rod.",
        kind=str,
        choices=tuple(CURVE_SOURCES),
        key="from",
    )
    film: FilmSettings | None = setting(
        None,
        "The film bonded on the rod's struck end, when the case has one (the continuum indents it).",
        kind=FilmSettings,
        nullable=True,
    )
    stack: StackSettings | None = setting(
        None,
        "The layers bonded on the rod's struck end, when the case has them (the continuum indents them).",
        kind=StackSettings,
        nullable=True,
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.film is not None and self.stack is not None:
            raise OptionError("stack", "cannot be given with a film: a film is a stack of one layer; give one of them")


class CurveMissing(ValueError):
    """A ``tabulated`` law was built without its curve (``field``: where it belongs)."""

    field = "contact.curve"


def pchip_slopes(x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
    """Fritsch-Carlson slopes of the monotone cubic Hermite interpolant of (x, y).

    Parameters
    ----------
    x, y : ndarray, shape (n,)
        Strictly increasing abscissae (n >= 2) and the values.

    Returns
    -------
    ndarray, shape (n,)
        dy/dx at each node: the weighted harmonic mean of the neighbouring secants where they
        have the same sign, 0 where they do not; the one-sided three-point formula at the
        ends, limited to keep the interpolant monotone (as scipy's ``PchipInterpolator``).
    """
    h = np.diff(x)
    delta = np.diff(y) / h
    n = len(x)
    d = np.zeros(n)
    if n == 2:
        return np.full(2, delta[0])
    w1 = 2.0 * h[1:] + h[:-1]
    w2 = h[1:] + 2.0 * h[:-1]
    same = np.sign(delta[1:]) * np.sign(delta[:-1]) > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        harmonic = (w1 + w2) / (w1 / delta[:-1] + w2 / delta[1:])
    d[1:-1] = np.where(same, harmonic, 0.0)
    for end, (h0, h1, m0, m1) in ((0, (h[0], h[1], delta[0], delta[1])), (-1, (h[-1], h[-2], delta[-1], delta[-2]))):
        slope = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
        if np.sign(slope) != np.sign(m0):
            slope = 0.0
        elif np.sign(m0) != np.sign(m1) and abs(slope) > abs(3.0 * m0):
            slope = 3.0 * m0
        d[end] = slope
    return d


@dataclass(frozen=True)
class TabulatedLaw(ContactLaw):
    """A contact law interpolated from a curve P(alpha) that a rule computes (the continuum's indentation).

    Parameters
    ----------
    approach_m : tuple of float
        The curve's approaches, m (strictly increasing, > 0; at least 2).
    force_N : tuple of float
        The forces there, N (strictly increasing, > 0).
    contact_radius_m : tuple of float or None
        The contact radii there, m (interpolated linearly in ln alpha); None: no geometry.
    source : str
        Where the curve comes from (e.g. ``fem_axi_indentation``), stored with every run.
    """

    approach_m: tuple[float, ...]
    force_N: tuple[float, ...]
    contact_radius_m: tuple[float, ...] | None = None
    source: str = ""
    name = "tabulated"
    label = "tabulated (continuum-calibrated)"
    reading = "contact law calibrated by the continuum"
    settings = TabulatedSettings
    #: The curve of each case, computed by the indentation rule before its runs (a sweep
    #: point's by its batch, for the point's own ball).
    needs = Needs(curve_rule=CURVE_SOURCES["fem_axi_indentation"])
    #: A curve is what the 1-D methods take; a continuum method resolves the bodies itself.
    method_contact = frozenset({"law"})
    _x: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _y: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _d: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _e: NDArray[np.float64] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        alpha, force = np.asarray(self.approach_m, float), np.asarray(self.force_N, float)
        if alpha.ndim != 1 or alpha.shape != force.shape or len(alpha) < 2:
            raise ValueError("approach_m and force_N must be 1-D of the same length >= 2")
        if not (np.all(np.isfinite(alpha)) and np.all(np.isfinite(force)) and alpha[0] > 0 and force[0] > 0):
            raise ValueError("approach_m and force_N must be finite and > 0")
        if np.any(np.diff(alpha) <= 0) or np.any(np.diff(force) <= 0):
            raise ValueError("approach_m and force_N must be strictly increasing (a monotone law)")
        if self.contact_radius_m is not None and len(self.contact_radius_m) != len(alpha):
            raise ValueError("contact_radius_m must have the length of approach_m")
        x, y = np.log(alpha), np.log(force)
        d = pchip_slopes(x, y)
        object.__setattr__(self, "_x", x)
        object.__setattr__(self, "_y", y)
        object.__setattr__(self, "_d", d)
        # the same nodes as Python floats, for the scalar path the steppers call per iteration
        object.__setattr__(self, "_nodes", (x.tolist(), y.tolist(), d.tolist()))
        # stored energy at the nodes: the power law below the first node, Gauss on each segment
        energy = np.empty(len(x))
        energy[0] = force[0] * alpha[0] / (d[0] + 1.0)
        for i in range(len(x) - 1):
            nodes = alpha[i] + (alpha[i + 1] - alpha[i]) * _GX
            energy[i + 1] = energy[i] + (alpha[i + 1] - alpha[i]) * float(_GW @ self._force_array(nodes))
        object.__setattr__(self, "_e", energy)

    @classmethod
    def from_bodies(
        cls, spec: Mapping[str, Any], sphere_radius_m: float, impactor: ElasticMaterial, rod: ElasticMaterial
    ) -> TabulatedLaw:
        """The law of a case: ``spec["curve"]`` holds ``approach_m``, ``force_N`` and
        optionally ``contact_radius_m`` (put there by the runner from the indentation file).

        Raises
        ------
        CurveMissing
            The spec has no curve.
        """
        curve = spec.get("curve")
        if curve is None:
            raise CurveMissing(
                f"contact: the tabulated law needs its curve (from {spec.get('from')!r}); "
                "the workflow's indentation rule computes it"
            )
        radius = curve.get("contact_radius_m")
        return cls(
            tuple(map(float, curve["approach_m"])),
            tuple(map(float, curve["force_N"])),
            None if radius is None else tuple(map(float, radius)),
            str(spec.get("from", "")),
        )

    # -- interpolation in (ln alpha, ln P) --------------------------------------------------
    def _log_force(self, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """ln P and its slope n = d ln P / d ln alpha at ln alpha = ``x`` (any shape)."""
        xs, ys, ds = self._x, self._y, self._d
        i = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2)
        y, dy = _hermite(x, xs[i], xs[i + 1], ys[i], ys[i + 1], ds[i], ds[i + 1])
        below, above = x < xs[0], x > xs[-1]
        y = np.where(below, ys[0] + ds[0] * (x - xs[0]), np.where(above, ys[-1] + ds[-1] * (x - xs[-1]), y))
        dy = np.where(below, ds[0], np.where(above, ds[-1], dy))
        return y, dy

    def _force_array(self, alpha: NDArray[np.float64]) -> NDArray[np.float64]:
        positive = alpha > 0
        y, _ = self._log_force(np.log(np.where(positive, alpha, 1.0)))
        return np.where(positive, np.exp(y), 0.0)

    def _log_force_scalar(self, x: float) -> tuple[float, float]:
        """:meth:`_log_force` at one ``x``, in Python floats: the same operations in the same
        order (so the same numbers), without numpy's per-call cost."""
        xs, ys, ds = self._nodes
        if x < xs[0]:
            return ys[0] + ds[0] * (x - xs[0]), ds[0]
        if x > xs[-1]:
            return ys[-1] + ds[-1] * (x - xs[-1]), ds[-1]
        i = min(max(bisect_right(xs, x) - 1, 0), len(xs) - 2)
        return _hermite(x, xs[i], xs[i + 1], ys[i], ys[i + 1], ds[i], ds[i + 1])

    def force(self, approach_m: float) -> float:
        if approach_m <= 0.0:
            return 0.0
        return math.exp(self._log_force_scalar(math.log(approach_m))[0])

    def stiffness(self, approach_m: float) -> float:
        if approach_m <= 0.0:
            return 0.0
        y, dy = self._log_force_scalar(math.log(approach_m))
        return dy * math.exp(y) / approach_m

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha = np.asarray(approach_m, dtype=float)
        flat = np.maximum(alpha.ravel(), 0.0)
        nodes = np.exp(self._x)
        i = np.searchsorted(nodes, flat, side="right") - 1  # -1: below the first node
        start = np.where(i >= 0, nodes[np.maximum(i, 0)], 0.0)
        base = np.where(i >= 0, self._e[np.maximum(i, 0)], 0.0)
        width = flat - start
        points = start[:, None] + width[:, None] * _GX[None, :]
        inside = width * (self._force_array(points) @ _GW)
        first = self._force_array(flat) * flat / (self._d[0] + 1.0)  # the power law below the table
        energy = np.where(i >= 0, base + inside, first)
        energy = np.where(flat > 0, energy, 0.0).reshape(alpha.shape)
        return energy if alpha.ndim else float(energy)

    def energy_between(self, lower_m: float, upper_m: float) -> float:
        """int_lower^upper P d alpha, J: Gauss-Legendre on each piece between the table's nodes
        (the interpolant is smooth on each piece, its second derivative jumps at the nodes)."""
        nodes = np.exp(self._x)
        cuts = np.array([lower_m, *nodes[(nodes > lower_m) & (nodes < upper_m)], upper_m])
        a, width = cuts[:-1], np.diff(cuts)
        forces = self._force_array(a[:, None] + width[:, None] * _GX[None, :])  # every piece's nodes at once
        total = 0.0
        for w, f in zip(width.tolist(), forces):  # piece by piece, in order
            total += w * float(f @ _GW)
        return total

    def approach(self, force_N: float) -> float:
        if force_N <= 0.0:
            return 0.0
        target = math.log(force_N)
        lo, hi = float(self._x[0]), float(self._x[-1])
        while self._log_force_scalar(lo)[0] > target:
            lo -= 1.0
        while self._log_force_scalar(hi)[0] < target:
            hi += 1.0
        for _ in range(200):  # bisection in ln alpha: ln P is increasing
            mid = 0.5 * (lo + hi)
            if self._log_force_scalar(mid)[0] < target:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 1e-15 * max(1.0, abs(mid)):
                break
        return math.exp(0.5 * (lo + hi))

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float | None:
        if self.contact_radius_m is None:
            return None
        alpha = np.asarray(approach_m, dtype=float)
        with np.errstate(divide="ignore"):
            x = np.log(np.maximum(alpha, 1e-300))
        radius = np.where(alpha > 0, np.interp(x, self._x, self.contact_radius_m), 0.0)
        return radius if alpha.ndim else float(radius)

    def summary(self) -> dict[str, float | str]:
        return {
            "contact_law": self.name,
            "table_source": self.source,
            "table_points": len(self.approach_m),
            "table_max_force_N": float(self.force_N[-1]),
            "table_max_approach_m": float(self.approach_m[-1]),
        }

    def run_summary(self, max_approach_m: float) -> dict[str, float]:
        """The run's largest approach over the table's (``table_reach``); above 1 the law was
        extrapolated by its last power law, and a warning is logged."""
        reach = max_approach_m / self.approach_m[-1]
        if reach > 1.0:
            log.warning(
                "tabulated law: the run's largest approach is %.3g times the table's; the law was "
                "extrapolated as a power law beyond it",
                reach,
            )
        return {"table_reach": float(reach)}
