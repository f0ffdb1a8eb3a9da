"""Hertz's quasi-static contact between a sphere and a flat end face.

The contact law is P = k alpha^(3/2), with alpha the approach (mutual convergence) of the
two bodies. For a sphere of radius R pressed on a flat,

    k = (4/3) E* sqrt(R),    1/E* = (1 - mu1^2)/E1 + (1 - mu2^2)/E2,

which for one material reduces to the paper's k = 2 E sqrt(R) / (3 (1 - mu^2)); the paper
prints only that one-material form (docs/paper-notes.md, "Hertz constant").

:class:`HertzLaw` is the :class:`~rodimpact.contact.law.ContactLaw` of every method that
takes a contact law; the functions are the paper's closed forms it is built from.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.contact.law import ContactLaw, ElasticMaterial, RigidImpact, StepNotConverged

__all__ = [
    "HERTZ_TIME_FACTOR",
    "ElasticMaterial",
    "HertzImpact",
    "HertzLaw",
    "effective_modulus",
    "hertz_constant",
    "hertz_rigid_impact",
    "solve_hertz_step",
]

#: Contact time of a Hertz impact on a rigid wall in units of alpha_max / v0:
#: 2 * integral_0^1 dx / sqrt(1 - x^(5/2)) = (4/5) B(2/5, 1/2) = 2.943275..., with
#: B(a, b) = Gamma(a) Gamma(b) / Gamma(a + b) (equal to the last bit to scipy.special.beta).
HERTZ_TIME_FACTOR: float = 0.8 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)


def effective_modulus(first: ElasticMaterial, second: ElasticMaterial | None = None) -> float:
    """Effective contact modulus E*, Pa.

    Parameters
    ----------
    first, second : Material
        The two bodies' materials; ``second=None`` means the same material as ``first``.

    Returns
    -------
    float
        E* with 1/E* = (1 - mu1^2)/E1 + (1 - mu2^2)/E2.
    """
    second = first if second is None else second
    compliance = sum((1.0 - m.poisson_ratio**2) / m.youngs_modulus_pa for m in (first, second))
    return 1.0 / compliance


def hertz_constant(radius_m: float, first: ElasticMaterial, second: ElasticMaterial | None = None) -> float:
    """Hertz constant k of a sphere of radius R on a flat, N/m^(3/2).

    Parameters
    ----------
    radius_m : float
        Radius R of the impactor's spherical profile, m (> 0).
    first, second : Material
        Materials of the sphere and of the flat; ``second=None`` for one material.

    Returns
    -------
    float
        k = (4/3) E* sqrt(R).
    """
    if not (math.isfinite(radius_m) and radius_m > 0):
        raise ValueError(f"radius_m must be > 0, got {radius_m!r}")
    return 4.0 / 3.0 * effective_modulus(first, second) * math.sqrt(radius_m)


HertzImpact = RigidImpact  # the closed-form Hertz impact is the law's rigid impact


def hertz_rigid_impact(mass_kg: float, velocity_m_s: float, hertz_k: float) -> RigidImpact:
    """Closed-form solution of m alpha'' = -k alpha^(3/2), alpha(0) = 0, alpha'(0) = v0.

    alpha_max = (5 m v0^2 / (4 k))^(2/5), the contact time HERTZ_TIME_FACTOR alpha_max / v0
    and the peak force k alpha_max^(3/2).

    Parameters
    ----------
    mass_kg : float
        Impactor mass m, kg (> 0).
    velocity_m_s : float
        Impact velocity v0, m/s (> 0).
    hertz_k : float
        Hertz constant k, N/m^(3/2) (> 0).
    """
    for name, value in (("mass_kg", mass_kg), ("velocity_m_s", velocity_m_s), ("hertz_k", hertz_k)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be > 0, got {value!r}")
    alpha_max = (5.0 * mass_kg * velocity_m_s**2 / (4.0 * hertz_k)) ** 0.4
    return RigidImpact(
        max_approach_m=alpha_max,
        contact_time_s=HERTZ_TIME_FACTOR * alpha_max / velocity_m_s,
        peak_force_N=hertz_k * alpha_max**1.5,
    )


def solve_hertz_step(a: float, b: float, k: float, guess: float) -> tuple[float, int]:
    """Root alpha >= 0 of alpha + b k alpha^(3/2) = a (a > 0, b >= 0); also the iteration count.

    The implicit step of any scheme in which the approach is affine in the new force,
    alpha = a - b P, with P = k alpha^(3/2) (b > 0 gives a unique root).

    f is increasing and convex on alpha >= 0, so Newton converges monotonically from any
    start after its first step; ``guess`` is clipped to [0, upper bound]. Near the root the
    next correction is at most f''/(2 f') step^2 <= step^2 / (4 alpha), so a step below
    1e-8 alpha leaves an error below 3e-17 alpha: the iteration stops there.
    """
    bk = b * k
    upper = a if bk <= 0 else min(a, (a / bk) ** (2.0 / 3.0))
    alpha = min(max(guess, 0.0), upper)
    sqrt = math.sqrt
    for iteration in range(1, 60):
        root = sqrt(alpha)
        step = (alpha + bk * alpha * root - a) / (1.0 + 1.5 * bk * root)
        alpha_new = alpha - step
        if alpha_new < 0.0:
            alpha_new = 0.5 * alpha
        elif abs(step) <= 1e-8 * alpha_new:
            return alpha_new, iteration
        alpha = alpha_new
    raise StepNotConverged(f"Newton on the Hertz law did not converge (a={a!r}, b={b!r})")


@dataclass(frozen=True)
class HertzLaw(ContactLaw):
    """Hertz's law P = k alpha^(3/2) of a sphere on a flat.

    Parameters
    ----------
    k : float
        Hertz constant, N/m^(3/2) (> 0), e.g. :func:`hertz_constant`.
    sphere_radius_m : float or None
        Radius R of the sphere, m; gives the contact radius sqrt(R alpha). None: no geometry.
    """

    k: float
    sphere_radius_m: float | None = None
    name = "hertz"
    label = "Hertz"
    reading = "Hertz contact"

    def __post_init__(self) -> None:
        if not (math.isfinite(self.k) and self.k > 0):
            raise ValueError(f"k must be > 0, got {self.k!r}")
        if self.sphere_radius_m is not None and not (math.isfinite(self.sphere_radius_m) and self.sphere_radius_m > 0):
            raise ValueError(f"sphere_radius_m must be > 0 or None, got {self.sphere_radius_m!r}")

    @classmethod
    def from_bodies(
        cls, spec: Mapping[str, Any], sphere_radius_m: float, impactor: ElasticMaterial, rod: ElasticMaterial
    ) -> HertzLaw:
        """The law of a case (``spec`` is its ``contact`` block; Hertz has no parameters)."""
        return cls(hertz_constant(sphere_radius_m, impactor, rod), sphere_radius_m)

    def force(self, approach_m: float) -> float:
        return self.k * approach_m**1.5 if approach_m > 0.0 else 0.0

    def stiffness(self, approach_m: float) -> float:
        return 1.5 * self.k * math.sqrt(max(approach_m, 0.0))

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        return 0.4 * self.k * np.maximum(approach_m, 0.0) ** 2.5

    def approach(self, force_N: float) -> float:
        return (max(force_N, 0.0) / self.k) ** (2.0 / 3.0)

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float | None:
        if self.sphere_radius_m is None:
            return None
        return np.sqrt(self.sphere_radius_m * np.maximum(approach_m, 0.0))

    def summary(self) -> dict[str, float | str]:
        return {"contact_law": self.name, "hertz_k": self.k}

    def solve_step(self, a: float, b: float, guess: float) -> tuple[float, int]:
        return solve_hertz_step(a, b, self.k, guess)

    def rigid_impact(self, mass_kg: float, velocity_m_s: float) -> RigidImpact:
        return hertz_rigid_impact(mass_kg, velocity_m_s, self.k)
