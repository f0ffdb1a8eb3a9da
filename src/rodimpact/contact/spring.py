"""The linear contact spring P = c alpha: the ``spring`` law.

It is no body's law: a sphere on a flat is Hertz's P = k alpha^(3/2), a thin film's
P ~ alpha^2. It is a reference, for two uses:

- a force history without the t^(3/2) onset of every power law steeper than linear, so that
  a scheme shows its formal order in every norm (the error-against-run-time study's smooth
  case, docs/studies.md);
- closed forms: with a rigid flat the contact is half a period of a harmonic oscillator,
  and with a rod long enough that no wave returns during the contact it is half a period
  of a damped one (:func:`semi_infinite_rod_contact`).

A law that is only a force-approach relation: a continuum method, which meshes the bodies
and resolves the contact itself, cannot run it (``method_contact``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.contact.hertz import ElasticMaterial
from rodimpact.contact.law import ContactLaw, LawSettings, RigidImpact, check_positive
from rodimpact.settings.declare import REQUIRED, setting

__all__ = ["SpringLaw", "SpringSettings", "SemiInfiniteContact", "semi_infinite_rod_contact"]


@dataclass(frozen=True, kw_only=True)
class SpringSettings(LawSettings):
    """The ``spring`` law's settings: its stiffness."""

    stiffness_n_per_m: float = setting(
        REQUIRED, "Stiffness c of the linear contact spring, P = c alpha.", unit="N/m", exclusive_minimum=0
    )


@dataclass(frozen=True)
class SpringLaw(ContactLaw):
    """A linear contact spring P = c alpha (a reference law with closed forms; no body's law).

    Parameters
    ----------
    c : float
        Stiffness of the spring, N/m (> 0).
    """

    c: float
    name = "spring"
    label = "linear spring"
    reading = "a linear contact spring"
    settings = SpringSettings
    #: Only a force-approach relation: the continuum has no bodies to mesh for it.
    method_contact = frozenset({"law"})

    def __post_init__(self) -> None:
        check_positive(c=self.c)

    @classmethod
    def from_bodies(
        cls, spec: Mapping[str, Any], sphere_radius_m: float, impactor: ElasticMaterial, rod: ElasticMaterial
    ) -> SpringLaw:
        """The law of a case (``spec`` is its ``contact`` block); the bodies play no part."""
        return cls(float(spec["stiffness_n_per_m"]))

    def force(self, approach_m: float) -> float:
        return self.c * approach_m if approach_m > 0.0 else 0.0

    def stiffness(self, approach_m: float) -> float:
        return self.c if approach_m > 0.0 else 0.0

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha = np.maximum(approach_m, 0.0)
        return 0.5 * self.c * alpha * alpha

    def energy_between(self, lower_m: float, upper_m: float) -> float:
        return 0.5 * self.c * (upper_m - lower_m) * (upper_m + lower_m)

    def approach(self, force_N: float) -> float:
        return max(force_N, 0.0) / self.c

    def summary(self) -> dict[str, float | str]:
        return {"contact_law": self.name, "spring_stiffness_n_per_m": self.c}

    def solve_step(self, a: float, b: float, guess: float) -> tuple[float, int]:
        """alpha + b c alpha = a: alpha = a / (1 + b c) (a > 0), in one step."""
        return max(a, 0.0) / (1.0 + b * self.c), 1

    def rigid_impact(self, mass_kg: float, velocity_m_s: float) -> RigidImpact:
        """Half a period of the oscillator m alpha'' = -c alpha: t = pi sqrt(m / c),
        alpha_max = v0 sqrt(m / c), P_max = v0 sqrt(m c)."""
        check_positive(mass_kg=mass_kg, velocity_m_s=velocity_m_s)
        root = math.sqrt(mass_kg / self.c)
        return RigidImpact(
            max_approach_m=velocity_m_s * root,
            contact_time_s=math.pi * root,
            peak_force_N=velocity_m_s * math.sqrt(mass_kg * self.c),
        )


@dataclass(frozen=True)
class SemiInfiniteContact:
    """The linear spring's impact on a rod's end before any wave returns (a damped oscillator).

    Attributes
    ----------
    damping_ratio : float
        zeta = sqrt(m c) / (2 Z), Z = rho c0 A the rod's impedance, kg/s; < 1 for a contact
        that ends.
    contact_time_s : float
        pi / omega_d, omega_d = omega_0 sqrt(1 - zeta^2), omega_0 = sqrt(c / m), s.
    peak_force_N : float
        c alpha at the first zero of alpha', N.
    peak_time_s : float
        When the force peaks, s.
    """

    damping_ratio: float
    contact_time_s: float
    peak_force_N: float
    peak_time_s: float


def semi_infinite_rod_contact(
    stiffness_n_per_m: float, mass_kg: float, velocity_m_s: float, impedance_kg_s: float
) -> SemiInfiniteContact:
    """The closed form of a rigid mass striking, through a linear spring, a rod whose far end
    the struck end's wave does not reach back from during the contact.

    The rod's end answers a force as a dashpot, u' = P / Z; the impactor obeys m w'' = -P;
    so alpha = w - u obeys m alpha'' + (m c / Z) alpha' + c alpha = 0 with alpha(0) = 0,
    alpha'(0) = v0. The contact lasts while alpha > 0: half the damped period.

    Parameters
    ----------
    stiffness_n_per_m : float
        c, N/m.
    mass_kg : float
        m, kg.
    velocity_m_s : float
        v0, m/s.
    impedance_kg_s : float
        Z = rho c0 A of the rod, kg/s.

    Returns
    -------
    SemiInfiniteContact

    Raises
    ------
    ValueError
        A value that is not > 0, or a damping ratio >= 1 (the spring never separates).
    """
    check_positive(
        stiffness_n_per_m=stiffness_n_per_m, mass_kg=mass_kg, velocity_m_s=velocity_m_s, impedance_kg_s=impedance_kg_s
    )
    omega0 = math.sqrt(stiffness_n_per_m / mass_kg)
    zeta = math.sqrt(mass_kg * stiffness_n_per_m) / (2.0 * impedance_kg_s)
    if zeta >= 1.0:
        raise ValueError(f"damping ratio {zeta:.3g} >= 1: the contact never ends")
    omega_d = omega0 * math.sqrt(1.0 - zeta * zeta)
    # alpha = (v0 / omega_d) exp(-zeta omega0 t) sin(omega_d t); alpha' = 0 at tan(omega_d t) = omega_d / (zeta omega0)
    t_peak = math.atan2(omega_d, zeta * omega0) / omega_d
    alpha_peak = velocity_m_s / omega_d * math.exp(-zeta * omega0 * t_peak) * math.sin(omega_d * t_peak)
    return SemiInfiniteContact(
        damping_ratio=zeta,
        contact_time_s=math.pi / omega_d,
        peak_force_N=stiffness_n_per_m * alpha_peak,
        peak_time_s=t_peak,
    )
