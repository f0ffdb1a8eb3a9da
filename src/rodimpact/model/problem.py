"""The impact of a case as the one-dimensional methods see it (``sem``, ``sem_paper``, ``fem1d``).

A rigid impactor with a spherical nose strikes the free end of an elastic rod through a
contact law (:mod:`rodimpact.contact`). The problem also gives the time and force scales
every method and the cost model start from: the impact on a rigid rod through the same law
(:attr:`ImpactProblem.rigid_contact`) and an upper-side estimate of the contact time.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from rodimpact.contact.law import ContactLaw, RigidImpact
from rodimpact.contact.laws import build_law
from rodimpact.model.materials import Material
from rodimpact.model.responses import Rod

__all__ = ["ImpactProblem"]


@dataclass(frozen=True)
class ImpactProblem:
    """A rigid impactor with a spherical nose striking the free end of an elastic rod.

    Parameters
    ----------
    mass_kg : float
        Impactor mass m, kg.
    velocity_m_s : float
        Impact velocity v0 (towards the rod), m/s.
    contact : ContactLaw
        The contact law P(alpha).
    rod : Rod
        The struck rod.
    """

    mass_kg: float
    velocity_m_s: float
    contact: ContactLaw
    rod: Rod

    def __post_init__(self) -> None:
        for name in ("mass_kg", "velocity_m_s"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be > 0, got {value!r}")
        if not isinstance(self.contact, ContactLaw):
            raise TypeError(f"contact must be a ContactLaw, got {type(self.contact).__name__}")

    @classmethod
    def from_case(cls, case: Mapping[str, Any], *, estimate: bool = False) -> ImpactProblem:
        """Build from a resolved case mapping (see :mod:`rodimpact.config.load`).

        ``estimate=True``: for checks and cost estimates before any job, a law whose data
        a job computes is replaced by the law it calibrates (:func:`~rodimpact.contact.laws.build_law`).
        """
        imp, rod = case["impactor"], case["rod"]
        imp_mat = Material.from_mapping(imp["material"])
        rod_mat = Material.from_mapping(rod["material"])
        return cls(
            mass_kg=float(imp["mass_kg"]),
            velocity_m_s=float(imp["velocity_m_s"]),
            contact=build_law(case.get("contact"), float(imp["radius_m"]), imp_mat, rod_mat, estimate=estimate),
            rod=Rod(
                length_m=float(rod["length_m"]),
                area_m2=float(rod["area_m2"]),
                material=rod_mat,
                far_end=rod.get("far_end", "fixed"),
            ),
        )

    @property
    def law(self) -> ContactLaw:
        """The contact law (the name every problem gives it)."""
        return self.contact

    @functools.cached_property
    def rigid_contact(self) -> RigidImpact:
        """The impact on a rigid rod through the same law (the stiff-rod limit)."""
        return self.contact.rigid_impact(self.mass_kg, self.velocity_m_s)

    @property
    def kinetic_energy_J(self) -> float:
        """Impactor's kinetic energy before impact, J."""
        return 0.5 * self.mass_kg * self.velocity_m_s**2

    def contact_time_estimate(self) -> float:
        """A rough upper-side estimate of the contact time, s.

        The contact time on a rigid rod, plus half a period of the impactor on the rod's
        static spring (fixed far end), plus one wave round trip when it is finite; and, on a
        rod that is not finite with a fixed end, plus 25 m/Z when the rod cannot carry the
        rigid-rod contact force (Z v0 below it): the impactor then pushes the rod's impedance
        Z like a dashpot and its velocity decays as exp(-t Z/m) (measured: contacts of 14
        to 23 m/Z on a semi-infinite steel wire). On a fixed finite rod the rod's spring
        ends that stage within its half period.
        """
        rigid = self.rigid_contact
        estimate = rigid.contact_time_s
        if self.rod.far_end == "fixed" and math.isfinite(self.rod.length_m):
            estimate += math.pi * math.sqrt(self.mass_kg * self.rod.static_compliance)
        if math.isfinite(self.rod.reflection_period):
            estimate += self.rod.reflection_period
        impedance = self.rod.impedance
        bounded = self.rod.far_end == "fixed" and math.isfinite(self.rod.length_m)
        if not bounded and impedance * self.velocity_m_s < rigid.peak_force_N:
            estimate += 25.0 * self.mass_kg / impedance
        return estimate
