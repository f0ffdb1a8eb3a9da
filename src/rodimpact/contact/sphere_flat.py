"""Published finite-element fits of an elastic-perfectly-plastic sphere pressed on a rigid flat.

Two studies meshed a deformable sphere of a yielding material (von Mises, no hardening) pressed
by a rigid, frictionless flat and fitted the force P against the interference omega (the
flat's displacement into the sphere). The continuum's elastic-plastic indentation is checked
against both (``make sphere-flat``, ``docs/verification.md``):

* Jackson and Green (2005), *A finite element study of elasto-plastic hemispherical contact
  against a rigid flat*, J. Tribol. 127, 343-354: with C = 1.295 exp(0.736 nu),

      omega_c = (pi C S_y / (2 E'))^2 R,   P_c = (4/3) E' sqrt(R) omega_c^(3/2),

  Hertz up to omega* = omega / omega_c = 1.9, beyond

      P / P_c = exp(-omega*^(5/12) / 4) omega*^(3/2)
                + (4 H_G / (C S_y)) (1 - exp(-omega*^(5/9) / 25)) omega*,
      H_G / S_y = 2.84 (1 - exp(-0.82 (a / R)^(-0.7))),
      a^2 = R omega (omega* / 1.9)^B,   B = 0.14 exp(23 S_y / E').

* Kogut and Etsion (2002), *Elastic-plastic contact analysis of a sphere and a rigid flat*,
  J. Appl. Mech. 69, 657-662: with K = 0.454 + 0.41 nu and H = 2.8 Y,

      omega_c = (pi K H / (2 E'))^2 R,   P_c = (4/3) E' sqrt(R) omega_c^(3/2),
      P / P_c = 1.03 omega*^1.425 (1 <= omega* <= 6),   1.40 omega*^1.263 (6 <= omega* <= 110).

E' is the contact modulus of the pair (:func:`~rodimpact.contact.hertz.effective_modulus`'s
1 / E' = (1 - nu1^2) / E1 + (1 - nu2^2) / E2; E / (1 - nu^2) on a rigid flat). The
coefficients were taken from open implementations of both papers (two independent ones for
each); the papers' own statement of their fits' accuracy could not be read, so the check
takes the two studies' difference from each other as the published result's spread: from
-2.9 % to +3.9 % over 1 <= omega* <= 24 for nu = 0.32 (``make sphere-flat``, column
``fits_diff_pct``). 1.9 is where Jackson and Green's fit leaves Hertz, although yield starts
at omega* = 1.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "jackson_green_critical_interference",
    "jackson_green_force",
    "kogut_etsion_critical_interference",
    "kogut_etsion_force",
    "critical_force",
]


def jackson_green_critical_interference(
    radius_m: float, contact_modulus_pa: float, yield_stress_pa: float, poisson_ratio: float
) -> float:
    """omega_c = (pi C S_y / (2 E'))^2 R, C = 1.295 exp(0.736 nu): first yield under Hertz, m."""
    c = 1.295 * math.exp(0.736 * poisson_ratio)
    return (math.pi * c * yield_stress_pa / (2.0 * contact_modulus_pa)) ** 2 * radius_m


def kogut_etsion_critical_interference(
    radius_m: float, contact_modulus_pa: float, yield_stress_pa: float, poisson_ratio: float
) -> float:
    """omega_c = (pi K H / (2 E'))^2 R, K = 0.454 + 0.41 nu, H = 2.8 Y, m."""
    kh = (0.454 + 0.41 * poisson_ratio) * 2.8 * yield_stress_pa
    return (math.pi * kh / (2.0 * contact_modulus_pa)) ** 2 * radius_m


def critical_force(radius_m: float, contact_modulus_pa: float, critical_interference_m: float) -> float:
    """P_c, the Hertz force at the critical interference, N."""
    return 4.0 / 3.0 * contact_modulus_pa * math.sqrt(radius_m) * critical_interference_m**1.5


def jackson_green_force(
    ratio: ArrayLike, radius_m: float, contact_modulus_pa: float, yield_stress_pa: float, poisson_ratio: float
) -> NDArray[np.float64]:
    """Jackson and Green's P / P_c at omega* = ``ratio`` (the module docstring), dimensionless.

    Parameters
    ----------
    ratio : array_like
        omega / omega_c (Jackson and Green's omega_c), >= 0.
    radius_m, contact_modulus_pa, yield_stress_pa, poisson_ratio : float
        R (m), E' (Pa), S_y (Pa) and the sphere's nu.
    """
    w = np.asarray(ratio, dtype=float)
    c = 1.295 * math.exp(0.736 * poisson_ratio)
    omega_c = jackson_green_critical_interference(radius_m, contact_modulus_pa, yield_stress_pa, poisson_ratio)
    b = 0.14 * math.exp(23.0 * yield_stress_pa / contact_modulus_pa)
    plastic = np.maximum(w, 1.9)
    a = np.sqrt(radius_m * plastic * omega_c * (plastic / 1.9) ** b)
    hardness = 2.84 * (1.0 - np.exp(-0.82 * (a / radius_m) ** -0.7))
    fit = (
        np.exp(-0.25 * plastic ** (5.0 / 12.0)) * plastic**1.5
        + 4.0 * hardness / c * (1.0 - np.exp(-(plastic ** (5.0 / 9.0)) / 25.0)) * plastic
    )
    return np.where(w <= 1.9, w**1.5, fit)


def kogut_etsion_force(ratio: ArrayLike) -> NDArray[np.float64]:
    """Kogut and Etsion's P / P_c at omega* = ``ratio`` in [1, 110] (their omega_c); Hertz below 1.

    Raises
    ------
    ValueError
        A ratio above 110, beyond their fit.
    """
    w = np.asarray(ratio, dtype=float)
    if np.any(w > 110.0):
        raise ValueError(f"ratio: Kogut and Etsion's fit ends at omega* = 110, got {float(np.max(w))!r}")
    return np.where(w < 1.0, w**1.5, np.where(w <= 6.0, 1.03 * w**1.425, 1.40 * w**1.263))
