"""Parameters and options of the semi-analytical method (SEM)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal, Mapping

from ..hertz import HertzImpact, hertz_constant, hertz_rigid_impact
from ..materials import Material
from ..result import check_stepping
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
        spring (fixed far end), plus one wave round trip when it is finite; and, on a rod
        that is not finite with a fixed end, plus 25 m/Z when the rod cannot carry the
        rigid-rod Hertz force (Z v0 below it): the impactor then pushes the rod's impedance
        Z like a dashpot and its velocity decays as exp(-t Z/m) (measured: contacts of 14
        to 23 m/Z on a semi-infinite steel wire). On a fixed finite rod the rod's spring
        ends that stage within its half period.
        """
        estimate = self.rigid_hertz.contact_time_s
        if self.rod.far_end == "fixed" and math.isfinite(self.rod.length_m):
            estimate += math.pi * math.sqrt(self.mass_kg * self.rod.static_compliance)
        if math.isfinite(self.rod.reflection_period):
            estimate += self.rod.reflection_period
        impedance = self.rod.impedance
        bounded = self.rod.far_end == "fixed" and math.isfinite(self.rod.length_m)
        if not bounded and impedance * self.velocity_m_s < self.rigid_hertz.peak_force_N:
            estimate += 25.0 * self.mass_kg / impedance
        return estimate


@dataclass(frozen=True)
class SEMOptions:
    """Numerical options of :func:`rodimpact.sem.solve_sem`.

    Parameters
    ----------
    scheme : {"implicit", "paper"}
        Time-stepping scheme (see :data:`SCHEMES`).
    dt_s : float or None
        Time step, s. ``None``: from ``steps_per_contact``, or chosen from the case.
    steps_per_contact : int or None
        Steps per rigid-rod Hertz contact time when ``dt_s`` is None (>= 10). ``None`` with
        ``dt_s`` None: the implicit scheme chooses its step for ``tolerance`` from the case's
        time scales and checks it by step doubling; the paper scheme needs one of the two.
    tolerance : float
        Relative error aimed at, and checked, on the first contact time and the largest
        force of the first contact when the step is chosen automatically (0 < tol < 1).
    energy_tolerance : float
        A run whose energy balance ``|energy_error|`` exceeds this fails (0 < tol).
    max_time_factor : float
        The run stops at ``max_time_factor * contact_time_estimate()`` at the latest (> 1).
    max_contacts : int
        The run stops after this many contacts (>= 1).
    max_steps : int
        Step budget of one run; a run that needs more fails with a message (>= 10).
    allow_unstable : bool
        Let the paper scheme take a step beyond its stability limit
        (:func:`rodimpact.sem.stability.paper_step_limit`); otherwise such a step is refused.
    """

    scheme: Literal["implicit", "paper"] = "implicit"
    dt_s: float | None = None
    steps_per_contact: int | None = None
    tolerance: float = 1e-5
    energy_tolerance: float = 1e-2
    max_time_factor: float = 100.0
    max_contacts: int = 50
    max_steps: int = 5_000_000
    allow_unstable: bool = False

    def __post_init__(self) -> None:
        if self.scheme not in SCHEMES:
            raise ValueError(f"scheme must be one of {SCHEMES}, got {self.scheme!r}")
        check_stepping(self.dt_s, self.steps_per_contact, 10, self.max_time_factor, self.max_contacts,
                       steps_optional=True)
        if self.scheme == "paper" and self.dt_s is None and self.steps_per_contact is None:
            raise ValueError("the paper scheme needs dt_s or steps_per_contact (it has no automatic step)")
        if not (0.0 < self.tolerance < 1.0):
            raise ValueError(f"tolerance must be in (0, 1), got {self.tolerance!r}")
        if not (self.energy_tolerance > 0.0):
            raise ValueError(f"energy_tolerance must be > 0, got {self.energy_tolerance!r}")
        if int(self.max_steps) != self.max_steps or self.max_steps < 10:
            raise ValueError(f"max_steps must be an integer >= 10, got {self.max_steps!r}")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], scheme: str) -> "SEMOptions":
        """Build from a resolved ``numerics.<method>`` mapping (missing fields: defaults)."""
        def value(name: str, kind: type) -> Any:
            item = data.get(name, getattr(cls, name))
            return None if item is None else kind(item)

        return cls(
            scheme=scheme,  # type: ignore[arg-type]
            dt_s=value("dt_s", float),
            steps_per_contact=value("steps_per_contact", int),
            tolerance=value("tolerance", float),
            energy_tolerance=value("energy_tolerance", float),
            max_time_factor=value("max_time_factor", float),
            max_contacts=value("max_contacts", int),
            max_steps=value("max_steps", int),
            allow_unstable=value("allow_unstable", bool),
        )

    @property
    def automatic_step(self) -> bool:
        """True when the step is chosen from the case (and checked by step doubling)."""
        return self.dt_s is None and self.steps_per_contact is None

    def step(self, problem: ImpactProblem) -> float:
        """The (first) time step to use for ``problem``, s."""
        if self.dt_s is not None:
            return self.dt_s
        if self.steps_per_contact is not None:
            return problem.rigid_hertz.contact_time_s / self.steps_per_contact
        from .stability import implicit_step

        return implicit_step(problem, self.tolerance)
