"""Hertz's contact through a thin bonded film: the ``hertz_film`` law.

A sphere of radius R presses a thin layer (thickness h, Young's modulus E_f, Poisson's
ratio nu_f) bonded to a much stiffer flat. Where the contact radius a is much larger than
h, each column of the layer is compressed with no lateral strain (the layer's material is
held by the substrate below and by its neighbours), so the layer is a bed of springs of
stiffness M / h per unit area, with M the constrained (oedometric) modulus

    M = E_f (1 - nu_f) / ((1 + nu_f) (1 - 2 nu_f)).

Under a sphere that compresses the layer by delta the local compression is
w(r) = delta - r^2 / (2 R) for r < a = sqrt(2 R delta), and

    P = int_0^a 2 pi r (M / h) w(r) dr = (pi M R / h) delta^2 = c delta^2.

The film's compression and the Hertz approach of ball and substrate carry the same force
in series, so the approach of the law is

    alpha(P) = (P / k)^(2/3) + (P / c)^(1/2).

Everything is computed in s = P^(1/6), in which alpha = A s^4 + B s^3 (A = k^(-2/3),
B = c^(-1/2)) is a polynomial increasing and convex for s > 0: the force at a given
approach and the implicit step are one Newton iteration from an upper bound, which
converges monotonically. The stored energy is int P d alpha = (2/5) A s^10 + (1/3) B s^9.

The derivation, its assumptions and the range of contact radius over thickness where the
law holds (measured against the continuum) are in docs/contact-laws.md.
"""

from __future__ import annotations

import functools
import logging
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.contact.film_impact import thin_layer_rigid_impact
from rodimpact.contact.hertz import ElasticMaterial, hertz_constant
from rodimpact.contact.law import MAX_STEP_ITERATIONS, ContactLaw, LawSettings, Needs, RigidImpact, StepNotConverged
from rodimpact.settings.declare import REQUIRED, Material, OptionError, Settings, setting

__all__ = [
    "DEFAULT_THICKNESS_TOLERANCE",
    "FILM_VALIDITY_RATIO",
    "FilmLayer",
    "FilmSettings",
    "HertzFilmLaw",
    "HertzFilmSettings",
    "constrained_modulus",
    "film_constant",
]

log = logging.getLogger(__name__)

#: The thin-layer law is used with a warning where the contact radius at the largest
#: approach is below this many film thicknesses (docs/contact-laws.md, "Range of validity").
FILM_VALIDITY_RATIO = 10.0


#: The film's thickness range when its source gives none: +/- this fraction of the thickness.
DEFAULT_THICKNESS_TOLERANCE = 0.10


@dataclass(frozen=True, kw_only=True)
class FilmSettings(Settings):
    """A film bonded on the rod's struck end (the experiment's piezoelectric sensor)."""

    thickness_m: float = setting(REQUIRED, "Thickness h of the film.", unit="m", exclusive_minimum=0)
    thickness_range_m: list[float] | None = setting(
        None,
        "[low, high] of the thickness, from the film's source or tolerance (null: +/- 10 % of "
        "thickness_m); the prediction band reads it.",
        unit="m",
        exclusive_minimum=0,
        items=(2, 2),
        nullable=True,
    )
    area_m2: float | None = setting(
        None,
        "Area of the film patch (null: the whole end face); fem_axi meshes a disc of this area.",
        unit="m^2",
        exclusive_minimum=0,
        nullable=True,
    )
    material: Mapping[str, Any] = setting(
        REQUIRED, "The film's material: a name from the materials file, or an inline material.", kind=Material
    )
    source: str = setting("", "Where the film's thickness and size come from.", kind=str)

    def __post_init__(self) -> None:
        super().__post_init__()
        thickness = self.thickness_m
        if self.thickness_range_m is None:
            tolerance = DEFAULT_THICKNESS_TOLERANCE
            object.__setattr__(self, "thickness_range_m", [(1 - tolerance) * thickness, (1 + tolerance) * thickness])
        low, high = (float(x) for x in self.thickness_range_m)
        if not (low < high and low <= thickness <= high):
            raise OptionError(
                "thickness_range_m",
                f"the thickness {thickness:g} m must lie inside a non-empty range, got [{low:g}, {high:g}]",
            )
        object.__setattr__(self, "thickness_range_m", [low, high])


@dataclass(frozen=True, kw_only=True)
class HertzFilmSettings(LawSettings):
    """The ``hertz_film`` law's settings: the film."""

    film: FilmSettings = setting(REQUIRED, "The film bonded on the rod's struck end.", kind=FilmSettings)


def constrained_modulus(youngs_modulus_pa: float, poisson_ratio: float) -> float:
    """The constrained (oedometric) modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)), Pa.

    Parameters
    ----------
    youngs_modulus_pa : float
        Young's modulus E, Pa (> 0).
    poisson_ratio : float
        Poisson's ratio nu, in (-1, 0.5).
    """
    if not (math.isfinite(youngs_modulus_pa) and youngs_modulus_pa > 0):
        raise ValueError(f"youngs_modulus_pa must be > 0, got {youngs_modulus_pa!r}")
    if not (-1.0 < poisson_ratio < 0.5):
        raise ValueError(f"poisson_ratio must lie in (-1, 0.5), got {poisson_ratio!r}")
    nu = poisson_ratio
    return youngs_modulus_pa * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))


def film_constant(sphere_radius_m: float, thickness_m: float, modulus_pa: float) -> float:
    """The thin layer's constant c of P = c delta^2 under a sphere, N/m^2.

    Parameters
    ----------
    sphere_radius_m : float
        Radius R of the sphere, m (> 0).
    thickness_m : float
        Thickness h of the layer, m (> 0).
    modulus_pa : float
        The layer's constrained modulus M, Pa (> 0), see :func:`constrained_modulus`.

    Returns
    -------
    float
        c = pi M R / h.
    """
    for name, value in (("sphere_radius_m", sphere_radius_m), ("thickness_m", thickness_m), ("modulus_pa", modulus_pa)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be > 0, got {value!r}")
    return math.pi * modulus_pa * sphere_radius_m / thickness_m


@dataclass(frozen=True)
class FilmLayer:
    """A film bonded to the rod's struck end (a case's ``contact.film``).

    Parameters
    ----------
    thickness_m : float
        Thickness h, m (> 0).
    youngs_modulus_pa, poisson_ratio, density_kg_m3 : float
        The film's material.
    area_m2 : float or None
        Area of the film patch, m^2; None: it covers the whole end face. The continuum model
        meshes it as a disc of the same area, centred on the axis.
    name : str
        The material's name, for messages.
    yield_stress_pa, hardening_modulus_pa : float or None
        The material's yield stress and hardening modulus, Pa, where it yields (read by the
        continuum, whose layers may yield; the thin-layer law is elastic).
    """

    thickness_m: float
    youngs_modulus_pa: float
    poisson_ratio: float
    density_kg_m3: float
    area_m2: float | None = None
    name: str = ""
    yield_stress_pa: float | None = None
    hardening_modulus_pa: float | None = None

    def __post_init__(self) -> None:
        for field in ("thickness_m", "youngs_modulus_pa", "density_kg_m3"):
            value = getattr(self, field)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{field} must be > 0, got {value!r}")
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise ValueError(f"poisson_ratio must lie in (-1, 0.5), got {self.poisson_ratio!r}")
        if self.area_m2 is not None and not (math.isfinite(self.area_m2) and self.area_m2 > 0):
            raise ValueError(f"area_m2 must be > 0 or None, got {self.area_m2!r}")

    @classmethod
    def from_mapping(cls, film: Mapping[str, Any]) -> FilmLayer:
        """From a resolved ``contact.film`` mapping (its material resolved to its constants)."""
        material = film["material"]
        area = film.get("area_m2")
        return cls(
            thickness_m=float(film["thickness_m"]),
            youngs_modulus_pa=float(material["youngs_modulus_pa"]),
            poisson_ratio=float(material["poisson_ratio"]),
            density_kg_m3=float(material["density_kg_m3"]),
            area_m2=None if area is None else float(area),
            name=str(material.get("name") or ""),
            yield_stress_pa=None if material.get("yield_stress_pa") is None else float(material["yield_stress_pa"]),
            hardening_modulus_pa=(
                None if material.get("hardening_modulus_pa") is None else float(material["hardening_modulus_pa"])
            ),
        )

    @property
    def constrained_modulus_pa(self) -> float:
        """The film's constrained modulus M, Pa."""
        return constrained_modulus(self.youngs_modulus_pa, self.poisson_ratio)

    def disc_radius(self, rod_radius_m: float) -> float:
        """Radius of the disc of the patch's area on a rod of radius ``rod_radius_m``, m."""
        if self.area_m2 is None:
            return rod_radius_m
        return min(math.sqrt(self.area_m2 / math.pi), rod_radius_m)


def _root(coefficients: tuple[float, float, float], target: float) -> tuple[float, int]:
    """The root s >= 0 of C6 s^6 + A s^4 + B s^3 = target (target > 0), and the iterations.

    The left side is increasing and convex for s > 0: Newton from an upper bound (the root
    of each term alone is above the root of the sum) decreases monotonically to the root.
    """
    c6, a4, b3 = coefficients
    bounds = [(target / c) ** (1.0 / p) for c, p in ((c6, 6.0), (a4, 4.0), (b3, 3.0)) if c > 0.0]
    s = min(bounds)
    for iteration in range(1, MAX_STEP_ITERATIONS + 1):
        s2 = s * s
        s3 = s2 * s
        f = (c6 * s3 + a4 * s) * s3 + b3 * s3 - target
        slope = (6.0 * c6 * s3 + 4.0 * a4 * s + 3.0 * b3) * s2
        if f <= 0.0 or slope <= 0.0:
            return s, iteration
        s_new = s - f / slope
        if s_new >= s or s - s_new <= 4e-16 * s:
            return max(s_new, 0.0), iteration
        s = s_new
    raise StepNotConverged(f"the hertz_film law's root did not converge (target={target!r})")


@dataclass(frozen=True)
class HertzFilmLaw(ContactLaw):
    """Hertz's law in series with a thin bonded film: alpha = (P/k)^(2/3) + (P/c)^(1/2).

    Parameters
    ----------
    k : float
        Hertz constant of the sphere on the substrate, N/m^(3/2) (> 0).
    c : float
        The film's constant pi M R / h, N/m^2 (> 0; ``inf`` is no film: Hertz's law).
    sphere_radius_m : float or None
        Radius R of the sphere, m (gives the contact radius).
    thickness_m : float or None
        The film's thickness h, m (gives the ratio of contact radius to thickness).
    """

    k: float
    c: float
    sphere_radius_m: float | None = None
    thickness_m: float | None = None
    name = "hertz_film"
    label = "Hertz with a thin film (approximation)"
    approximation = True
    reading = "Hertz contact in series with the film"
    settings = HertzFilmSettings
    needs = Needs(film=True)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.k) and self.k > 0):
            raise ValueError(f"k must be > 0, got {self.k!r}")
        if not (self.c > 0):
            raise ValueError(f"c must be > 0, got {self.c!r}")
        for name in ("sphere_radius_m", "thickness_m"):
            value = getattr(self, name)
            if value is not None and not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be > 0 or None, got {value!r}")

    @classmethod
    def from_bodies(
        cls, spec: Mapping[str, Any], sphere_radius_m: float, impactor: ElasticMaterial, rod: ElasticMaterial
    ) -> HertzFilmLaw:
        """The law of a case: ``spec["film"]`` is the resolved film (see :class:`FilmLayer`)."""
        film = FilmLayer.from_mapping(spec["film"])
        return cls(
            k=hertz_constant(sphere_radius_m, impactor, rod),
            c=film_constant(sphere_radius_m, film.thickness_m, film.constrained_modulus_pa),
            sphere_radius_m=sphere_radius_m,
            thickness_m=film.thickness_m,
        )

    # -- the law in s = P^(1/6) ---------------------------------------------------------
    # (computed once per law: every force and every step asks for them)
    @functools.cached_property
    def _a(self) -> float:
        return self.k ** (-2.0 / 3.0)

    @functools.cached_property
    def _b(self) -> float:
        return 0.0 if math.isinf(self.c) else self.c**-0.5

    def _s(self, approach_m: float) -> float:
        if approach_m <= 0.0:
            return 0.0
        return _root((0.0, self._a, self._b), approach_m)[0]

    def force(self, approach_m: float) -> float:
        return self._s(approach_m) ** 6

    def stiffness(self, approach_m: float) -> float:
        s = self._s(approach_m)
        if s == 0.0:
            return 0.0
        # dP/dalpha = (dP/ds) / (dalpha/ds) = 6 s^5 / (4 A s^3 + 3 B s^2)
        return 6.0 * s**3 / (4.0 * self._a * s + 3.0 * self._b)

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha = np.asarray(approach_m, dtype=float)
        s = np.vectorize(self._s, otypes=[float])(alpha) if alpha.ndim else np.float64(self._s(float(alpha)))
        energy = (0.4 * self._a * s + self._b / 3.0) * s**9
        return energy if alpha.ndim else float(energy)

    def energy_between(self, lower_m: float, upper_m: float) -> float:
        """int_lower^upper P d alpha, J, in closed form and without cancellation.

        With alpha = A s^4 + B s^3 and E = 0.4 A s^10 + B s^9 / 3 (s = P^(1/6)), the differences
        factor as alpha_1 - alpha_0 = (s_1 - s_0) (A S_4 + B S_3) and E_1 - E_0 = (s_1 - s_0)
        (0.4 A S_10 + B S_9 / 3), where S_n = sum_k s_1^k s_0^(n-1-k) has no cancellation: s_1 -
        s_0 follows from the approaches' difference, never from two nearly equal roots.
        """
        lower, upper = max(lower_m, 0.0), max(upper_m, 0.0)
        if upper == lower:
            return 0.0
        if upper < lower:
            return -self.energy_between(upper, lower)
        s0, s1 = self._s(lower), self._s(upper)
        a, b = self._a, self._b
        s_sum = [0.0] * 11  # s_sum[n] = S_n
        power0 = [1.0] * 10  # s_0^j
        power1 = [1.0] * 10  # s_1^j
        for j in range(1, 10):
            power0[j] = power0[j - 1] * s0
            power1[j] = power1[j - 1] * s1
        for n in (3, 4, 9, 10):
            s_sum[n] = math.fsum(power1[k] * power0[n - 1 - k] for k in range(n))
        ds = (upper - lower) / (a * s_sum[4] + b * s_sum[3])
        return ds * (0.4 * a * s_sum[10] + b * s_sum[9] / 3.0)

    def _rigid_impact(self, mass_kg: float, velocity_m_s: float) -> RigidImpact:
        """:meth:`rigid_impact` in s, by Gauss-Legendre quadrature of an analytic integrand
        (:func:`~rodimpact.contact.film_impact.thin_layer_rigid_impact`)."""
        return thin_layer_rigid_impact(self._a, self._b, mass_kg, velocity_m_s)

    def approach(self, force_N: float) -> float:
        force = max(force_N, 0.0)
        return self._a * force ** (2.0 / 3.0) + self._b * math.sqrt(force)

    def film_compression(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        """The film's share delta = (P/c)^(1/2) of the approach, m (shape as ``approach_m``)."""
        alpha = np.asarray(approach_m, dtype=float)
        s = np.vectorize(self._s, otypes=[float])(alpha) if alpha.ndim else self._s(float(alpha))
        return self._b * np.asarray(s) ** 3 if alpha.ndim else self._b * s**3

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float | None:
        """a = sqrt(R (alpha_H + 2 delta)): Hertz's sqrt(R alpha_H) with no film, the bed of
        springs' sqrt(2 R delta) where the film takes the whole approach."""
        if self.sphere_radius_m is None:
            return None
        alpha = np.asarray(approach_m, dtype=float)
        if alpha.ndim:
            s = np.vectorize(self._s, otypes=[float])(alpha)
        else:
            s = self._s(float(alpha))
        radius = np.sqrt(self.sphere_radius_m * (self._a * s**4 + 2.0 * self._b * s**3))
        return radius if alpha.ndim else float(radius)

    def summary(self) -> dict[str, float | str]:
        summary: dict[str, float | str] = {"contact_law": self.name, "hertz_k": self.k, "film_c": self.c}
        if self.thickness_m is not None:
            summary["film_thickness_m"] = self.thickness_m
        return summary

    def run_summary(self, max_approach_m: float) -> dict[str, float]:
        """The ratio of the contact radius at the run's largest approach to the film thickness
        (``film_radius_to_thickness``), logged as a warning below :data:`FILM_VALIDITY_RATIO`."""
        if self.thickness_m is None or self.sphere_radius_m is None or not max_approach_m > 0:
            return {}
        ratio = float(self.contact_radius(max_approach_m)) / self.thickness_m
        if ratio < FILM_VALIDITY_RATIO:
            log.warning(
                "hertz_film: the contact radius is %.3g film thicknesses at the largest approach, below "
                "the thin-layer law's range (>= %g; docs/contact-laws.md)",
                ratio,
                FILM_VALIDITY_RATIO,
            )
        return {"film_radius_to_thickness": ratio}

    def solve_step(self, a: float, b: float, guess: float) -> tuple[float, int]:
        """The root of alpha + b P(alpha) = a, solved for s = P^(1/6) in
        b s^6 + A s^4 + B s^3 = a (one convex increasing polynomial)."""
        if a <= 0.0:
            return 0.0, 0
        s, iterations = _root((max(b, 0.0), self._a, self._b), a)
        return (self._a * s + self._b) * s**3, iterations

    def solve_step_force(self, a: float, b: float, guess: float) -> tuple[float, float, int]:
        """:meth:`solve_step` with the force s^6 from the same root."""
        if a <= 0.0:
            return 0.0, 0.0, 0
        s, iterations = _root((max(b, 0.0), self._a, self._b), a)
        return (self._a * s + self._b) * s**3, s**6, iterations
