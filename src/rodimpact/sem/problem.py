"""Parameters and options of the semi-analytical method (SEM)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal, Mapping

from ..hertz import HertzImpact, hertz_constant, hertz_rigid_impact
from ..materials import Material
from ..responses import Rod

__all__ = ["ImpactProblem", "SEMOptions", "SCHEMES"]

#: ``implicit``: piecewise-linear force, exact product integration, contact force implicit.
#: ``paper``: the paper's step-by-step formula, force held constant and lagged one step.
SCHEMES = ("implicit", "paper")


@dataclass(frozen=True)
class ImpactProblem:
    """A rigid impactor with a spherical nose striking the free end of an elastic rod.

    Parameters
    ----------
    mass_kg : float
        Impactor mass m, kg.
    velocity_m_s : float
        Impact velocity v0 (towards the rod), m/s.
    hertz_k : float
        Hertz constant k in P = k alpha^(3/2), N/m^(3/2).
    rod : Rod
        The struck rod.
    sphere_radius_m : float, optional
        Radius R of the spherical profile; when given, the contact radius is reported
        (Hertz: a = sqrt(R alpha)).
    """

    mass_kg: float
    velocity_m_s: float
    hertz_k: float
    rod: Rod
    sphere_radius_m: float | None = None

    def __post_init__(self) -> None:
        for name in ("mass_kg", "velocity_m_s", "hertz_k"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be > 0, got {value!r}")

    @classmethod
    def from_case(cls, case: Mapping[str, Any]) -> "ImpactProblem":
        """Build from a resolved case mapping (see ``rodimpact.config``)."""
        imp, rod = case["impactor"], case["rod"]
        imp_mat = Material.from_mapping(imp["material"])
        rod_mat = Material.from_mapping(rod["material"])
        return cls(
            mass_kg=float(imp["mass_kg"]),
            velocity_m_s=float(imp["velocity_m_s"]),
            hertz_k=hertz_constant(float(imp["radius_m"]), imp_mat, rod_mat),
            rod=Rod(
                length_m=float(rod["length_m"]),
                area_m2=float(rod["area_m2"]),
                material=rod_mat,
                far_end=rod.get("far_end", "fixed"),
            ),
            sphere_radius_m=float(imp["radius_m"]),
        )

    @property
    def rigid_hertz(self) -> HertzImpact:
        """The closed-form Hertz impact on a rigid rod (the stiff-rod limit)."""
        return hertz_rigid_impact(self.mass_kg, self.velocity_m_s, self.hertz_k)

    @property
    def kinetic_energy_J(self) -> float:
        """Impactor's kinetic energy before impact, J."""
        return 0.5 * self.mass_kg * self.velocity_m_s**2

    def contact_time_estimate(self) -> float:
        """A rough upper-side estimate of the contact time, s.

        Hertz time on a rigid rod, plus half a period of the impactor on the rod's static
        spring (fixed far end), plus one wave round trip when it is finite.
        """
        estimate = self.rigid_hertz.contact_time_s
        if self.rod.far_end == "fixed" and math.isfinite(self.rod.length_m):
            estimate += math.pi * math.sqrt(self.mass_kg * self.rod.static_compliance)
        if math.isfinite(self.rod.reflection_period):
            estimate += self.rod.reflection_period
        return estimate


@dataclass(frozen=True)
class SEMOptions:
    """Numerical options of :func:`rodimpact.sem.solve_sem`.

    Parameters
    ----------
    scheme : {"implicit", "paper"}
        Time-stepping scheme (see :data:`SCHEMES`).
    dt_s : float or None
        Time step, s; ``None`` chooses ``hertz_time / steps_per_contact``, with
        ``hertz_time`` the closed-form rigid-rod contact time.
    steps_per_contact : int
        Steps per Hertz contact time when ``dt_s`` is None (>= 10).
    max_time_factor : float
        The run stops at ``max_time_factor * contact_time_estimate()`` at the latest (> 1).
    max_contacts : int
        The run stops after this many contacts (>= 1).
    """

    scheme: Literal["implicit", "paper"] = "implicit"
    dt_s: float | None = None
    steps_per_contact: int = 2000
    max_time_factor: float = 100.0
    max_contacts: int = 50

    def __post_init__(self) -> None:
        if self.scheme not in SCHEMES:
            raise ValueError(f"scheme must be one of {SCHEMES}, got {self.scheme!r}")
        if self.dt_s is not None and not (math.isfinite(self.dt_s) and self.dt_s > 0):
            raise ValueError(f"dt_s must be > 0 or None, got {self.dt_s!r}")
        if int(self.steps_per_contact) != self.steps_per_contact or self.steps_per_contact < 10:
            raise ValueError(f"steps_per_contact must be an integer >= 10, got {self.steps_per_contact!r}")
        if not (self.max_time_factor > 1):
            raise ValueError(f"max_time_factor must be > 1, got {self.max_time_factor!r}")
        if int(self.max_contacts) != self.max_contacts or self.max_contacts < 1:
            raise ValueError(f"max_contacts must be an integer >= 1, got {self.max_contacts!r}")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], scheme: str) -> "SEMOptions":
        """Build from a resolved ``numerics.<method>`` mapping."""
        dt = data.get("dt_s")
        return cls(
            scheme=scheme,  # type: ignore[arg-type]
            dt_s=None if dt is None else float(dt),
            steps_per_contact=int(data.get("steps_per_contact", cls.steps_per_contact)),
            max_time_factor=float(data.get("max_time_factor", cls.max_time_factor)),
            max_contacts=int(data.get("max_contacts", cls.max_contacts)),
        )

    def step(self, problem: ImpactProblem) -> float:
        """The time step to use for ``problem``, s."""
        if self.dt_s is not None:
            return self.dt_s
        return problem.rigid_hertz.contact_time_s / self.steps_per_contact
