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

With memory (:class:`TabulatedMemoryLaw`: a case whose material yields, whose curve the
``indentation`` rule gives with unloading curves; :mod:`rodimpact.jobs.indentation`). The path
goes up to a first largest approach, down until the force vanishes, up again past it to the
next, and so on: the loading curve is the force each time the path goes beyond its largest
approach (a :class:`TabulatedLaw`), and each unloading curve k, from its largest approach
m_k, falls to zero at its dent r_k. An unloading curve is stored as its shape,

    P_unload(alpha; m) = P_load(m) f(xi)^(3/2),   xi = (alpha - r(m)) / (m - r(m)) in [0, 1],

f = (P / P(m))^(2/3) tabulated against xi and interpolated by the monotone cubic Hermite
interpolant: an unloading curve that is Hertz's with another radius (Thornton's, and the
continuum's near its dent) is a straight line in these coordinates. For a largest approach m
between two maxima the dent r(m) is the monotone cubic Hermite interpolant of the dents against
the maxima, and the shape f is the linear
mix of the two neighbours' shapes (both increase from 0 to 1, so their mix does, and the
branch is monotone). Below the first maximum the law mixes with the elastic unloading at the
largest approach where nothing has yielded (the loading curve itself, no dent); above the
last, the last shape is kept and the dent extrapolated on its end slope (a run's summary reports its
``unloading_reach``). The interpolation error of the unloading curves is measured as the
loading curve's: the law rebuilt from every other unloading curve, compared on those left out.
"""

from __future__ import annotations

import logging
import math
from bisect import bisect_right
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.contact.film import FilmSettings
from rodimpact.contact.hertz import ElasticMaterial
from rodimpact.contact.law import ContactLaw, LawSettings, MemoryLaw, Needs, StepNotConverged
from rodimpact.contact.stack import StackSettings
from rodimpact.settings.declare import REQUIRED, OptionError, setting

__all__ = [
    "CURVE_NUMERICS",
    "CURVE_SOURCES",
    "CurveMissing",
    "TabulatedLaw",
    "TabulatedMemoryLaw",
    "TabulatedSettings",
    "UnloadingBranch",
    "UnloadingShape",
    "pchip_slopes",
    "unloading_shape",
]

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
    ) -> TabulatedLaw | TabulatedMemoryLaw:
        """The law of a case: ``spec["curve"]`` holds ``approach_m``, ``force_N`` and
        optionally ``contact_radius_m`` (put there by the runner from the indentation file);
        with ``unloading`` and ``elastic_limit_m`` (a case whose material yields), the law with
        memory (:class:`TabulatedMemoryLaw`).

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
        loading = cls(
            tuple(map(float, curve["approach_m"])),
            tuple(map(float, curve["force_N"])),
            None if radius is None else tuple(map(float, radius)),
            str(spec.get("from", "")),
        )
        if curve.get("unloading") is None:
            return loading
        return TabulatedMemoryLaw.from_curve(loading, curve)

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


@dataclass(frozen=True)
class UnloadingShape:
    """One unloading curve's shape: f = (P / P(m))^(2/3) against xi = (alpha - r) / (m - r).

    Parameters
    ----------
    xi : tuple of float
        Strictly increasing, from 0 to 1.
    f : tuple of float
        Strictly increasing, from 0 to 1.
    """

    xi: tuple[float, ...]
    f: tuple[float, ...]
    _d: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _integral: NDArray[np.float64] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        x, y = np.asarray(self.xi, float), np.asarray(self.f, float)
        if x.ndim != 1 or x.shape != y.shape or len(x) < 3:
            raise ValueError("xi and f must be 1-D of the same length >= 3")
        if x[0] != 0.0 or x[-1] != 1.0 or y[0] != 0.0 or y[-1] != 1.0:
            raise ValueError("xi and f must run from 0 to 1")
        if np.any(np.diff(x) <= 0) or np.any(np.diff(y) <= 0):
            raise ValueError("xi and f must be strictly increasing (a monotone unloading curve)")
        object.__setattr__(self, "_d", pchip_slopes(x, y))
        # the nodes as Python floats, for the scalar path the steppers call per iteration
        object.__setattr__(self, "_nodes", (x.tolist(), y.tolist(), self._d.tolist()))
        # int_0^xi_j f^(3/2): Gauss on each piece (smooth on each)
        integral = np.zeros(len(x))
        for j in range(len(x) - 1):
            nodes = x[j] + (x[j + 1] - x[j]) * _GX
            integral[j + 1] = integral[j] + (x[j + 1] - x[j]) * float(_GW @ self.power(nodes))
        object.__setattr__(self, "_integral", integral)

    def value(self, xi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """f and df/dxi at ``xi`` (clipped into [0, 1])."""
        x = np.clip(np.asarray(xi, dtype=float), 0.0, 1.0)
        xs, ys = np.asarray(self.xi), np.asarray(self.f)
        i = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2)
        return _hermite(x, xs[i], xs[i + 1], ys[i], ys[i + 1], self._d[i], self._d[i + 1])

    def value_scalar(self, xi: float) -> tuple[float, float]:
        """:meth:`value` at one ``xi``, in Python floats (the same operations)."""
        xs, ys, ds = self._nodes
        x = min(max(xi, 0.0), 1.0)
        i = min(max(bisect_right(xs, x) - 1, 0), len(xs) - 2)
        return _hermite(x, xs[i], xs[i + 1], ys[i], ys[i + 1], ds[i], ds[i + 1])

    def power(self, xi: ArrayLike) -> NDArray[np.float64]:
        """f^(3/2) at ``xi``: the force over P(m)."""
        f, _ = self.value(xi)
        return np.maximum(f, 0.0) ** 1.5

    def integral(self, xi: ArrayLike) -> NDArray[np.float64]:
        """int_0^xi f^(3/2), dimensionless (xi clipped into [0, 1])."""
        x = np.clip(np.asarray(xi, dtype=float), 0.0, 1.0)
        xs = np.asarray(self.xi)
        i = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2)
        start = xs[i]
        width = x - start
        inside = width * (self.power(start[..., None] + width[..., None] * _GX) @ _GW)
        return self._integral[i] + inside


def unloading_shape(approach_m: Sequence[float], force_N: Sequence[float]) -> tuple[float, UnloadingShape]:
    """The dent and the shape of one unloading curve from its points.

    Parameters
    ----------
    approach_m, force_N : sequence of float
        The unloading curve from its largest approach down (approach decreasing), m and N; the
        force positive at the first point, falling to zero at the end or not.

    Returns
    -------
    residual_m : float
        The dent r: where the curve's last two positive points, straight in (alpha, P^(2/3)),
        reach zero force, m (0 where that falls below zero).
    shape : UnloadingShape
    """
    alpha = np.asarray(approach_m, float)
    force = np.asarray(force_N, float)
    positive = force > 0
    if positive.sum() < 3 or not positive[0]:
        raise ValueError("an unloading curve needs its largest approach and at least two more points with force")
    alpha, force = alpha[positive], force[positive]
    if np.any(np.diff(alpha) >= 0) or np.any(np.diff(force) >= 0):
        raise ValueError("an unloading curve must fall: approach and force decreasing")
    g = force ** (2.0 / 3.0)
    slope = (g[-2] - g[-1]) / (alpha[-2] - alpha[-1])
    # no dent below zero (a curve just past first yield, straight to rounding)
    residual = max(float(alpha[-1] - g[-1] / slope), 0.0)
    top = alpha[0]
    xi = np.concatenate([[0.0], (alpha[::-1] - residual) / (top - residual)])
    f = np.concatenate([[0.0], g[::-1] / g[0]])
    xi[-1], f[-1] = 1.0, 1.0
    return residual, UnloadingShape(tuple(xi.tolist()), tuple(f.tolist()))


@dataclass(frozen=True)
class TabulatedMemoryLaw(MemoryLaw):
    """The ``tabulated`` law with memory: the continuum's loading curve and unloading curves.

    Parameters
    ----------
    loading : TabulatedLaw
        The virgin curve.
    elastic_limit_m : float
        The largest approach at which the continuum dissipated nothing: below it the law
        unloads on its loading curve and leaves no dent, m (> 0).
    max_approach_m : tuple of float
        The largest approaches m_k of the unloading curves, m (strictly increasing, above
        ``elastic_limit_m``).
    residual_approach_m : tuple of float
        Their dents r_k, m (0 <= r_k < m_k).
    shapes : tuple of UnloadingShape
        Their shapes.
    """

    loading: TabulatedLaw
    elastic_limit_m: float
    max_approach_m: tuple[float, ...]
    residual_approach_m: tuple[float, ...]
    shapes: tuple[UnloadingShape, ...]
    _dents: tuple[NDArray[np.float64], ...] = field(init=False, repr=False, compare=False)
    name: ClassVar[str] = "tabulated"
    label: ClassVar[str] = "tabulated with memory (continuum-calibrated, elastic-plastic)"
    reading: ClassVar[str] = "contact law with memory calibrated by the continuum"
    settings = TabulatedSettings
    needs = Needs(curve_rule=CURVE_SOURCES["fem_axi_indentation"])
    method_contact = frozenset({"law"})

    @classmethod
    def from_curve(cls, loading: TabulatedLaw, curve: Mapping[str, Any]) -> TabulatedMemoryLaw:
        """The law of a curve with unloading curves (``curve["unloading"]``: ``curve`` (the index
        of each point's curve), ``approach_m``, ``force_N``; ``curve["elastic_limit_m"]``)."""
        unloading = curve["unloading"]
        index = np.asarray(unloading["curve"], dtype=float).astype(int)
        alpha = np.asarray(unloading["approach_m"], dtype=float)
        force = np.asarray(unloading["force_N"], dtype=float)
        tops, dents, shapes = [], [], []
        for k in np.unique(index):
            dent, shape = unloading_shape(alpha[index == k], force[index == k])
            tops.append(float(alpha[index == k][0]))
            dents.append(dent)
            shapes.append(shape)
        return cls(loading, float(curve["elastic_limit_m"]), tuple(tops), tuple(dents), tuple(shapes))

    def __post_init__(self) -> None:
        m = np.asarray(self.max_approach_m, float)
        r = np.asarray(self.residual_approach_m, float)
        if m.ndim != 1 or len(m) < 1 or m.shape != r.shape or len(self.shapes) != len(m):
            raise ValueError("max_approach_m, residual_approach_m and shapes must have one entry per unloading curve")
        if not (self.elastic_limit_m > 0 and m[0] > self.elastic_limit_m) or np.any(np.diff(m) <= 0):
            raise ValueError("max_approach_m must increase from above elastic_limit_m")
        if np.any(r < 0) or np.any(r >= m):
            raise ValueError("each residual approach must lie in [0, its largest approach)")
        # the dents' interpolant, from no dent at the elastic limit (every branch a stepper makes reads it)
        tops = np.concatenate([[self.elastic_limit_m], m])
        dents = np.concatenate([[0.0], r])
        object.__setattr__(self, "_dents", (tops, dents, pchip_slopes(tops, dents)))

    # -- the virgin curve ---------------------------------------------------------------------
    def force(self, approach_m: float) -> float:
        return self.loading.force(approach_m)

    def stiffness(self, approach_m: float) -> float:
        return self.loading.stiffness(approach_m)

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        return self.loading.energy(approach_m)

    def energy_between(self, lower_m: float, upper_m: float) -> float:
        return self.loading.energy_between(lower_m, upper_m)

    def approach(self, force_N: float) -> float:
        return self.loading.approach(force_N)

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float | None:
        return self.loading.contact_radius(approach_m)

    # -- the memory -----------------------------------------------------------------------------
    def residual_approach(self, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        """The dent r(m): the monotone cubic Hermite interpolant of the dents against the largest
        approaches (from no dent at the elastic limit), its end slope beyond the last, m."""
        peak = np.asarray(max_approach_m, dtype=float)
        tops, dents, slopes = self._dents
        i = np.clip(np.searchsorted(tops, peak, side="right") - 1, 0, len(tops) - 2)
        inside, _ = _hermite(peak, tops[i], tops[i + 1], dents[i], dents[i + 1], slopes[i], slopes[i + 1])
        out = np.where(peak > tops[-1], dents[-1] + slopes[-1] * (peak - tops[-1]), inside)
        out = np.where(peak <= self.elastic_limit_m, 0.0, np.clip(out, 0.0, None))
        return out if peak.ndim else float(out)

    def mix(self, peak: float) -> tuple[int, float]:
        """The unloading curve at or below the largest approach ``peak`` (-1: the elastic limit)
        and the weight of the next one in the shape's mix."""
        tops = self.max_approach_m
        if peak >= tops[-1]:
            return len(tops) - 1, 0.0
        k = int(np.searchsorted(tops, peak, side="right")) - 1
        low = self.elastic_limit_m if k < 0 else tops[k]
        return k, (peak - low) / (tops[k + 1] - low)

    def shape_value(self, k: int, xi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """f and df/dxi of unloading curve ``k`` at ``xi`` (k = -1: the elastic limit's, the
        loading curve up to it)."""
        if k >= 0:
            return self.shapes[k].value(xi)
        top = self.elastic_limit_m
        x = np.clip(np.asarray(xi, dtype=float), 0.0, 1.0)
        load_top = self.loading.force(top)
        p = np.asarray([self.loading.force(float(a)) for a in np.ravel(x * top)]).reshape(x.shape)
        dp = np.asarray([self.loading.stiffness(float(a)) for a in np.ravel(x * top)]).reshape(x.shape) * top
        f = (p / load_top) ** (2.0 / 3.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            df = np.where(p > 0, (2.0 / 3.0) * f * dp / np.where(p > 0, p, 1.0), 0.0)
        return f, df

    def shape_value_scalar(self, k: int, xi: float) -> tuple[float, float]:
        """:meth:`shape_value` at one ``xi``, in Python floats."""
        if k >= 0:
            return self.shapes[k].value_scalar(xi)
        top = self.elastic_limit_m
        x = min(max(xi, 0.0), 1.0)
        p = self.loading.force(x * top)
        if p <= 0.0:
            return 0.0, 0.0
        f = (p / self.loading.force(top)) ** (2.0 / 3.0)
        return f, (2.0 / 3.0) * f * self.loading.stiffness(x * top) * top / p

    def shape_power(self, peak: float, xi: ArrayLike) -> NDArray[np.float64]:
        """P / P_load(peak) on the unloading curve from ``peak``: f^(3/2) of the mixed f, at ``xi``."""
        k, w = self.mix(peak)
        f, _ = self.shape_value(k, xi)
        if w > 0.0:
            f = (1.0 - w) * f + w * self.shape_value(k + 1, xi)[0]
        return np.maximum(f, 0.0) ** 1.5

    def branch(self, max_approach_m: float) -> ContactLaw:
        peak = float(max_approach_m)
        if peak <= self.elastic_limit_m:
            return self.loading
        return UnloadingBranch(self, peak, float(self.residual_approach(peak)))

    def stored_energy(self, approach_m: ArrayLike, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha, peak = np.broadcast_arrays(np.asarray(approach_m, float), np.asarray(max_approach_m, float))
        out = np.array(
            [float(self.branch(float(p)).energy(float(a))) for a, p in zip(alpha.ravel(), peak.ravel())], dtype=float
        ).reshape(alpha.shape)
        return out if alpha.ndim else float(out)

    def dissipated_energy(self, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        peak = np.asarray(max_approach_m, dtype=float)
        loaded = np.asarray(self.loading.energy(np.maximum(peak, 0.0)), dtype=float)
        out = np.maximum(loaded - np.asarray(self.stored_energy(peak, peak), dtype=float), 0.0)
        return out if peak.ndim else float(out)

    def summary(self) -> dict[str, float | str]:
        return {
            **self.loading.summary(),
            "unloading_curves": len(self.max_approach_m),
            "elastic_limit_m": float(self.elastic_limit_m),
            "unloading_max_approach_m": float(self.max_approach_m[-1]),
        }

    def run_summary(self, max_approach_m: float) -> dict[str, float]:
        return {
            **self.loading.run_summary(max_approach_m),
            "unloading_reach": float(max_approach_m / self.max_approach_m[-1]),
        }


@dataclass(frozen=True)
class UnloadingBranch(ContactLaw):
    """The curve a :class:`TabulatedMemoryLaw` contact follows while its largest approach is
    ``peak`` (m): no force up to the dent ``dent`` (m), the unloading curve up to ``peak``, the
    loading curve beyond."""

    law: TabulatedMemoryLaw
    peak: float
    dent: float
    name: ClassVar[str] = "tabulated"
    top_force: float = field(init=False, repr=False, compare=False)
    _mix: tuple[int, float] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        #: the loading curve's force at the largest approach, N
        object.__setattr__(self, "top_force", self.law.loading.force(self.peak))
        object.__setattr__(self, "_mix", self.law.mix(self.peak))

    def _shape(self, xi: float) -> tuple[float, float]:
        """The mixed f and df/dxi at one ``xi``."""
        k, w = self._mix
        f, df = self.law.shape_value_scalar(k, xi)
        if w > 0.0:
            f1, df1 = self.law.shape_value_scalar(k + 1, xi)
            f, df = (1.0 - w) * f + w * f1, (1.0 - w) * df + w * df1
        return f, df

    def force(self, approach_m: float) -> float:
        if approach_m <= self.dent:
            return 0.0
        if approach_m >= self.peak:
            return self.law.loading.force(approach_m)
        f, _ = self._shape((approach_m - self.dent) / (self.peak - self.dent))
        return self.top_force * max(f, 0.0) ** 1.5

    def stiffness(self, approach_m: float) -> float:
        if approach_m <= self.dent:
            return 0.0
        if approach_m >= self.peak:
            return self.law.loading.stiffness(approach_m)
        span = self.peak - self.dent
        f, df = self._shape((approach_m - self.dent) / span)
        return self.top_force * 1.5 * math.sqrt(max(f, 0.0)) * df / span

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha = np.asarray(approach_m, dtype=float)
        out = np.array([self._energy(float(a)) for a in alpha.ravel()]).reshape(alpha.shape)
        return out if alpha.ndim else float(out)

    def _energy(self, alpha: float) -> float:
        return self.energy_between(self.dent, alpha) if alpha > self.dent else 0.0

    def _shape_integral(self, lower: float, upper: float) -> float:
        """int_lower^upper of the mixed f^(3/2) d xi (0 <= lower <= upper <= 1): Gauss on every
        piece between the mixed shapes' nodes (each smooth there)."""
        k, w = self._mix
        if k >= 0 and w == 0.0:
            shape = self.law.shapes[k]
            return float(shape.integral(upper) - shape.integral(lower))
        nodes = [np.asarray(self.law.shapes[j].xi) for j in (k, k + 1) if j >= 0]
        inner = np.concatenate(nodes) if nodes else np.empty(0)
        if k < 0:  # the elastic limit's shape: the loading curve's nodes, scaled
            inner = np.concatenate([inner, np.asarray(self.law.loading.approach_m) / self.law.elastic_limit_m])
        cuts = np.unique(np.concatenate([[lower, upper], inner[(inner > lower) & (inner < upper)]]))
        points = cuts[:-1, None] + np.diff(cuts)[:, None] * _GX[None, :]
        return float(np.diff(cuts) @ (self.law.shape_power(self.peak, points) @ _GW))

    def energy_between(self, lower_m: float, upper_m: float) -> float:
        """int_lower^upper P d alpha, J: the unloading curve's part by Gauss on its shape's pieces,
        the loading curve's beyond the largest approach by its own."""
        span = self.peak - self.dent
        total = 0.0
        low, high = max(lower_m, self.dent), min(upper_m, self.peak)
        if high > low:
            total += self.top_force * span * self._shape_integral((low - self.dent) / span, (high - self.dent) / span)
        if upper_m > self.peak:
            total += self.law.loading.energy_between(max(lower_m, self.peak), upper_m)
        return total

    def approach(self, force_N: float) -> float:
        if force_N <= 0.0:
            return self.dent
        if force_N >= self.top_force:
            return self.law.loading.approach(force_N)
        lo, hi = self.dent, self.peak
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if self.force(mid) < force_N:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 1e-15 * hi:
                return 0.5 * (lo + hi)
        raise StepNotConverged(f"the tabulated unloading curve did not give the force {force_N!r}")

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float | None:
        return None
