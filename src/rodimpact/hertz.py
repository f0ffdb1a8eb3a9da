"""Hertz's quasi-static contact between a sphere and a flat end face.

The contact law is P = k alpha^(3/2), with alpha the approach (mutual convergence) of the
two bodies. For a sphere of radius R pressed on a flat,

    k = (4/3) E* sqrt(R),    1/E* = (1 - mu1^2)/E1 + (1 - mu2^2)/E2,

which for one material reduces to the paper's k = 2 E sqrt(R) / (3 (1 - mu^2))
(NOTES.md item 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.special import beta

from .materials import Material

__all__ = [
    "HERTZ_TIME_FACTOR",
    "HertzImpact",
    "effective_modulus",
    "hertz_constant",
    "hertz_rigid_impact",
    "solve_hertz_step",
]

#: Contact time of a Hertz impact on a rigid wall in units of alpha_max / v0:
#: 2 * integral_0^1 dx / sqrt(1 - x^(5/2)) = (4/5) B(2/5, 1/2) = 2.943275...
HERTZ_TIME_FACTOR: float = 0.8 * float(beta(0.4, 0.5))


def effective_modulus(first: Material, second: Material | None = None) -> float:
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
    compliance = sum(
        (1.0 - m.poisson_ratio**2) / m.youngs_modulus_pa for m in (first, second)
    )
    return 1.0 / compliance


def hertz_constant(radius_m: float, first: Material, second: Material | None = None) -> float:
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


@dataclass(frozen=True)
class HertzImpact:
    """Closed-form Hertz impact of a rigid mass on a rigid flat (no wave in either body).

    Attributes
    ----------
    max_approach_m : float
        alpha_max = (5 m v0^2 / (4 k))^(2/5), m.
    contact_time_s : float
        HERTZ_TIME_FACTOR * alpha_max / v0, s.
    peak_force_N : float
        k alpha_max^(3/2), N.
    """

    max_approach_m: float
    contact_time_s: float
    peak_force_N: float


def hertz_rigid_impact(mass_kg: float, velocity_m_s: float, hertz_k: float) -> HertzImpact:
    """Closed-form solution of m alpha'' = -k alpha^(3/2), alpha(0) = 0, alpha'(0) = v0.

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
    return HertzImpact(
        max_approach_m=alpha_max,
        contact_time_s=HERTZ_TIME_FACTOR * alpha_max / velocity_m_s,
        peak_force_N=hertz_k * alpha_max**1.5,
    )


def solve_hertz_step(a: float, b: float, k: float, guess: float) -> tuple[float, int]:
    """Root alpha >= 0 of alpha + b k alpha^(3/2) = a (a > 0, b >= 0); also the iteration count.

    The implicit step of any scheme in which the approach is affine in the new force,
    alpha = a - b P, with P = k alpha^(3/2) (b > 0 gives a unique root).

    f is increasing and convex on alpha >= 0, so Newton converges monotonically from any
    start after its first step; ``guess`` is clipped to [0, upper bound].
    """
    bk = b * k
    upper = a if bk <= 0 else min(a, (a / bk) ** (2.0 / 3.0))
    alpha = min(max(guess, 0.0), upper)
    for iteration in range(1, 60):
        root = math.sqrt(alpha)
        f = alpha + bk * alpha * root - a
        step = f / (1.0 + 1.5 * bk * root)
        alpha_new = alpha - step
        if alpha_new < 0.0:
            alpha_new = 0.5 * alpha
        if abs(alpha_new - alpha) <= 1e-15 * alpha_new or alpha_new == alpha:
            return alpha_new, iteration
        alpha = alpha_new
    raise RuntimeError(f"Newton on the Hertz law did not converge (a={a!r}, b={b!r})")
