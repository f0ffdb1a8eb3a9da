"""Thornton's elastic-perfectly-plastic sphere contact: the ``thornton`` law, a law with memory.

Thornton (1997) truncates Hertz's pressure at a limiting contact pressure p_y. With the
effective modulus E* and the sphere's radius R (the Hertz constant k = 4/3 E* sqrt(R)):

- **loading**, Hertz's P = k alpha^(3/2) up to the approach where Hertz's peak pressure
  reaches p_y,

      alpha_y = R (pi p_y / (2 E*))^2,    P_y = k alpha_y^(3/2),

  and beyond it linear in the approach, P = P_y + pi p_y R (alpha - alpha_y);
- **unloading** from the largest approach alpha_m (force P_m > P_y), Hertzian about a residual
  approach alpha_p with an enlarged radius R_p (the flattened, dented contact):

      a_m^2 = (2 P_m + P_y) / (2 pi p_y),    R_p = 4 E* a_m^3 / (3 P_m),
      alpha_p = alpha_m - a_m^2 / R_p,       P = 4/3 E* sqrt(R_p) (alpha - alpha_p)^(3/2),

  a_m being the contact radius at P_m. Below alpha_y the law is Hertz's, elastic.

A rigid sphere striking a rigid flat through this law rebounds with Thornton's closed-form
coefficient of restitution, a function of V_y / V alone (V_y the impact velocity at which the
contact first reaches p_y):

    e = sqrt(6 sqrt(3) / 5 (1 - (V_y/V)^2 / 6))
        * ((V_y/V) / (V_y/V + 2 sqrt(6/5 - (V_y/V)^2 / 5)))^(1/4)      (V > V_y),

(:func:`thornton_restitution`); :meth:`ThorntonLaw.rigid_impact` gives the whole impact in
closed form (the loading time through the incomplete beta function, the plastic stage as
half an oscillation about a preload, the unloading as half a Hertz impact).

p_y is a model constant, not the yield stress Y: by default it is 1.6 Y of the softer of the
two bodies, the Hertz peak pressure at which yield first starts beneath a sphere (Johnson,
*Contact Mechanics*, 1985, section 6.2), so that the law is exactly Hertz's up to first yield.
Its mean pressure then tends to p_y at large loads, below the 2.8-3 Y of a fully plastic
indentation: Thornton's law underestimates the force well past yield (docs/contact-laws.md).

Reference: C. Thornton, "Coefficient of restitution for collinear collisions of
elastic-perfectly plastic spheres", J. Appl. Mech. 64 (1997) 383-386.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.contact.hertz import HERTZ_TIME_FACTOR, effective_modulus, solve_hertz_step
from rodimpact.contact.law import ContactLaw, LawSettings, MemoryLaw, RigidImpact, YieldingMaterial, check_positive
from rodimpact.settings.declare import setting

__all__ = [
    "YIELD_ONSET_FACTOR",
    "ThorntonBranch",
    "ThorntonLaw",
    "ThorntonSettings",
    "thornton_restitution",
    "yield_velocity",
]

#: p_0 / Y at first yield beneath a Hertz contact (Johnson 1985, section 6.2; nu = 0.3): the
#: default limiting pressure is this times the softer body's yield stress.
YIELD_ONSET_FACTOR = 1.6


@dataclass(frozen=True, kw_only=True)
class ThorntonSettings(LawSettings):
    """The ``thornton`` law's settings: its limiting contact pressure."""

    limiting_pressure_pa: float | None = setting(
        None,
        "Thornton's limiting contact pressure p_y: Hertz's pressure is capped at it. Null: 1.6 times the "
        "smaller yield stress of the impactor's and the rod's materials (the Hertz peak pressure at first "
        "yield); at least that where a material gives its yield stress.",
        unit="Pa",
        nullable=True,
        exclusive_minimum=0,
    )


def yield_velocity(mass_kg: float, hertz_k: float, yield_approach_m: float) -> float:
    """V_y, the impact velocity of a rigid mass on a rigid flat at which the contact first
    reaches the limiting pressure: m V_y^2 / 2 = 2/5 k alpha_y^(5/2), m/s."""
    return math.sqrt(0.8 * hertz_k * yield_approach_m**2.5 / mass_kg)


def thornton_restitution(velocity_ratio: float) -> float:
    """Thornton's (1997) closed-form coefficient of restitution of a rigid sphere on a rigid flat.

    Parameters
    ----------
    velocity_ratio : float
        V_y / V, the yield velocity over the impact velocity (> 0); 1 or more: an elastic impact.

    Returns
    -------
    float
        e = sqrt(6 sqrt(3)/5 (1 - r^2/6)) (r / (r + 2 sqrt(6/5 - r^2/5)))^(1/4), r = V_y / V;
        1 for r >= 1.
    """
    check_positive(velocity_ratio=velocity_ratio)
    r = velocity_ratio
    if r >= 1.0:
        return 1.0
    return (
        math.sqrt(6.0 * math.sqrt(3.0) / 5.0 * (1.0 - r * r / 6.0))
        * (r / (r + 2.0 * math.sqrt(6.0 / 5.0 - r * r / 5.0))) ** 0.25
    )


@dataclass(frozen=True)
class ThorntonLaw(MemoryLaw):
    """Thornton's elastic-perfectly-plastic contact of a sphere on a flat, with memory.

    Parameters
    ----------
    effective_modulus_pa : float
        E*, Pa (> 0): 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
    sphere_radius_m : float
        R, m (> 0).
    limiting_pressure_pa : float
        p_y, Pa (> 0).
    """

    effective_modulus_pa: float
    sphere_radius_m: float
    limiting_pressure_pa: float
    k: float = field(init=False, repr=False, compare=False)
    yield_approach_m: float = field(init=False, repr=False, compare=False)
    yield_force_N: float = field(init=False, repr=False, compare=False)
    plastic_stiffness_n_per_m: float = field(init=False, repr=False, compare=False)

    name = "thornton"
    label = "Thornton"
    reading = "Thornton's elastic-plastic contact"
    settings = ThorntonSettings
    #: A law with memory: a continuum method resolves plasticity in its own bodies.
    method_contact = frozenset({"law"})

    def __post_init__(self) -> None:
        check_positive(
            effective_modulus_pa=self.effective_modulus_pa,
            sphere_radius_m=self.sphere_radius_m,
            limiting_pressure_pa=self.limiting_pressure_pa,
        )
        e_star, radius, p_y = self.effective_modulus_pa, self.sphere_radius_m, self.limiting_pressure_pa
        k = 4.0 / 3.0 * e_star * math.sqrt(radius)
        alpha_y = radius * (math.pi * p_y / (2.0 * e_star)) ** 2
        object.__setattr__(self, "k", k)
        object.__setattr__(self, "yield_approach_m", alpha_y)
        object.__setattr__(self, "yield_force_N", k * alpha_y**1.5)
        object.__setattr__(self, "plastic_stiffness_n_per_m", math.pi * p_y * radius)

    @classmethod
    def limiting_pressure(
        cls, spec: Mapping[str, Any], impactor: YieldingMaterial, rod: YieldingMaterial
    ) -> float | None:
        """p_y of a case: the ``limiting_pressure_pa`` it gives, else :data:`YIELD_ONSET_FACTOR`
        times the smaller yield stress of its two materials; None when neither is given."""
        given = spec.get("limiting_pressure_pa")
        if given is not None:
            return float(given)
        yields = [y for y in (impactor.yield_stress_pa, rod.yield_stress_pa) if y is not None]
        return YIELD_ONSET_FACTOR * min(yields) if yields else None

    @classmethod
    def bodies_problem(
        cls, spec: Mapping[str, Any], impactor: YieldingMaterial, rod: YieldingMaterial
    ) -> tuple[str, str] | None:
        """No limiting pressure (none given, no yield stress in either material), or one below
        the Hertz pressure at which the softer material first yields."""
        yields = [y for y in (impactor.yield_stress_pa, rod.yield_stress_pa) if y is not None]
        given = spec.get("limiting_pressure_pa")
        if given is None and not yields:
            return (
                "limiting_pressure_pa",
                "missing; the thornton law needs it, or a yield_stress_pa in the impactor's or the rod's material",
            )
        if given is not None and yields and given < YIELD_ONSET_FACTOR * min(yields):
            return (
                "limiting_pressure_pa",
                f"{given:g} Pa lies below what the contact reaches elastically: Hertz's peak pressure first "
                f"yields the softer material at {YIELD_ONSET_FACTOR:g} x its yield stress {min(yields):g} Pa "
                f"= {YIELD_ONSET_FACTOR * min(yields):g} Pa",
            )
        return None

    @classmethod
    def from_bodies(
        cls, spec: Mapping[str, Any], sphere_radius_m: float, impactor: YieldingMaterial, rod: YieldingMaterial
    ) -> ThorntonLaw:
        """The law of a case (``spec`` is its ``contact`` block).

        Raises
        ------
        ValueError
            No limiting pressure: the block gives none and neither material a yield stress.
        """
        p_y = cls.limiting_pressure(spec, impactor, rod)
        if p_y is None:
            raise ValueError(
                "limiting_pressure_pa: the thornton law needs it, "
                "or a yield_stress_pa in the impactor's or the rod's material"
            )
        return cls(effective_modulus(impactor, rod), float(sphere_radius_m), p_y)

    # -- the virgin loading curve ------------------------------------------------------------
    def force(self, approach_m: float) -> float:
        if approach_m <= 0.0:
            return 0.0
        if approach_m <= self.yield_approach_m:
            return self.k * approach_m**1.5
        return self.yield_force_N + self.plastic_stiffness_n_per_m * (approach_m - self.yield_approach_m)

    def stiffness(self, approach_m: float) -> float:
        if approach_m <= self.yield_approach_m:
            return 1.5 * self.k * math.sqrt(max(approach_m, 0.0))
        return self.plastic_stiffness_n_per_m

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha = np.maximum(approach_m, 0.0)
        alpha_y = self.yield_approach_m
        excess = np.maximum(alpha - alpha_y, 0.0)
        elastic = 0.4 * self.k * np.minimum(alpha, alpha_y) ** 2.5
        return elastic + excess * (self.yield_force_N + 0.5 * self.plastic_stiffness_n_per_m * excess)

    def approach(self, force_N: float) -> float:
        force = max(force_N, 0.0)
        if force <= self.yield_force_N:
            return (force / self.k) ** (2.0 / 3.0)
        return self.yield_approach_m + (force - self.yield_force_N) / self.plastic_stiffness_n_per_m

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        """sqrt(R alpha) up to yield; beyond, Thornton's a^2 = (2 P + P_y) / (2 pi p_y)."""
        alpha = np.maximum(approach_m, 0.0)
        excess = np.maximum(alpha - self.yield_approach_m, 0.0)
        force = self.yield_force_N + self.plastic_stiffness_n_per_m * excess
        plastic = (2.0 * force + self.yield_force_N) / (2.0 * math.pi * self.limiting_pressure_pa)
        return np.sqrt(np.where(alpha <= self.yield_approach_m, self.sphere_radius_m * alpha, plastic))

    def summary(self) -> dict[str, float | str]:
        return {
            "contact_law": self.name,
            "hertz_k": self.k,
            "limiting_pressure_pa": self.limiting_pressure_pa,
            "yield_approach_m": self.yield_approach_m,
            "yield_force_N": self.yield_force_N,
        }

    def solve_step(self, a: float, b: float, guess: float) -> tuple[float, int]:
        return self.branch(0.0).solve_step(a, b, guess)

    # -- the memory ----------------------------------------------------------------------------
    def _unloading(self, max_approach_m: ArrayLike) -> tuple[NDArray[np.float64], ...]:
        """(P_m, alpha_p, R_p) of the unloading curves from ``max_approach_m`` (arrays; below
        yield the Hertz curve itself: alpha_p = 0, R_p = R)."""
        peak = np.maximum(np.asarray(max_approach_m, dtype=float), 0.0)
        plastic = peak > self.yield_approach_m
        excess = np.where(plastic, peak - self.yield_approach_m, 0.0)
        p_max = np.where(plastic, self.yield_force_N + self.plastic_stiffness_n_per_m * excess, self.k * peak**1.5)
        a2 = (2.0 * p_max + self.yield_force_N) / (2.0 * math.pi * self.limiting_pressure_pa)
        with np.errstate(divide="ignore", invalid="ignore"):
            radius_p = np.where(
                plastic, 4.0 * self.effective_modulus_pa * a2**1.5 / (3.0 * p_max), self.sphere_radius_m
            )
            residual = np.where(plastic, peak - a2 / radius_p, 0.0)
        return p_max, residual, radius_p

    def branch(self, max_approach_m: float) -> ThorntonBranch:
        return ThorntonBranch(self, max(float(max_approach_m), 0.0))

    def residual_approach(self, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        return self._unloading(max_approach_m)[1]

    def dissipated_energy(self, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        peak = np.maximum(np.asarray(max_approach_m, dtype=float), 0.0)
        p_max, residual, _ = self._unloading(peak)
        returned = 0.4 * p_max * (peak - residual)
        return np.where(peak > self.yield_approach_m, self.energy(peak) - returned, 0.0)

    def stored_energy(self, approach_m: ArrayLike, max_approach_m: ArrayLike) -> NDArray[np.float64] | float:
        _, residual, radius_p = self._unloading(max_approach_m)
        k_p = 4.0 / 3.0 * self.effective_modulus_pa * np.sqrt(radius_p)
        return 0.4 * k_p * np.maximum(np.asarray(approach_m, dtype=float) - residual, 0.0) ** 2.5

    def contact_radius_after(self, approach_m: ArrayLike, max_approach_m: ArrayLike) -> NDArray[np.float64]:
        _, residual, radius_p = self._unloading(max_approach_m)
        return np.sqrt(radius_p * np.maximum(np.asarray(approach_m, dtype=float) - residual, 0.0))

    def run_summary(self, max_approach_m: float) -> dict[str, float]:
        """Whether the run yielded: its largest approach over the yield approach alpha_y."""
        return {"approach_over_yield": float(max_approach_m) / self.yield_approach_m}

    # -- a rigid mass on a rigid flat, in closed form -------------------------------------------
    def rigid_impact(self, mass_kg: float, velocity_m_s: float) -> RigidImpact:
        """The impact of a rigid mass on a rigid flat through this law, in closed form.

        Loading: the Hertz stage to alpha_y in (alpha*/V) (2/5) B(2/5, 1/2) I_u(2/5, 1/2),
        alpha* = (5 m V^2 / (4 k))^(2/5), u = (alpha_y / alpha*)^(5/2) (I the regularized
        incomplete beta function); the plastic stage, m alpha'' = -P_y - c (alpha - alpha_y), a
        quarter oscillation about the preload's offset, atan2(v_y / omega, P_y / c) / omega,
        omega = sqrt(c / m), v_y the velocity at alpha_y. Unloading: half a Hertz impact with
        k_p from alpha_m to alpha_p, which returns 2/5 P_m (alpha_m - alpha_p) as kinetic energy.
        Below V_y: Hertz's impact, e = 1.
        """
        from scipy.special import beta, betainc

        check_positive(mass_kg=mass_kg, velocity_m_s=velocity_m_s)
        m, v = float(mass_kg), float(velocity_m_s)
        kinetic = 0.5 * m * v * v
        alpha_y, p_y, c = self.yield_approach_m, self.yield_force_N, self.plastic_stiffness_n_per_m
        yield_energy = 0.4 * self.k * alpha_y**2.5
        elastic_max = (5.0 * m * v * v / (4.0 * self.k)) ** 0.4
        if kinetic <= yield_energy:
            return RigidImpact(
                max_approach_m=elastic_max,
                contact_time_s=HERTZ_TIME_FACTOR * elastic_max / v,
                peak_force_N=self.k * elastic_max**1.5,
            )
        excess = kinetic - yield_energy
        depth = 2.0 * excess / (p_y + math.sqrt(p_y * p_y + 2.0 * c * excess))
        peak = alpha_y + depth
        p_max = p_y + c * depth
        hertz_time = (
            (elastic_max / v) * 0.4 * beta(0.4, 0.5) * betainc(0.4, 0.5, min((alpha_y / elastic_max) ** 2.5, 1.0))
        )
        omega = math.sqrt(c / m)
        v_y = math.sqrt(2.0 * excess / m)
        plastic_time = math.atan2(v_y / omega, p_y / c) / omega
        _, residual, _ = self._unloading(peak)
        recovery = peak - float(residual)
        rebound = math.sqrt(0.8 * p_max * recovery / m)
        return RigidImpact(
            max_approach_m=peak,
            contact_time_s=float(hertz_time) + plastic_time + 0.5 * HERTZ_TIME_FACTOR * recovery / rebound,
            peak_force_N=p_max,
            restitution=rebound / v,
            residual_approach_m=float(residual),
        )


@dataclass(frozen=True)
class ThorntonBranch(ContactLaw):
    """The curve a :class:`ThorntonLaw` contact follows while its largest approach is
    ``max_approach_m``: Hertzian unloading about the residual approach below it (no force up
    to the residual), the virgin loading curve above it. A monotone elastic law.

    Parameters
    ----------
    law : ThorntonLaw
        The law.
    max_approach_m : float
        alpha_m, m (>= 0).
    """

    law: ThorntonLaw
    max_approach_m: float
    peak_force_N: float = field(init=False, repr=False, compare=False)
    residual_approach_m: float = field(init=False, repr=False, compare=False)
    unloading_radius_m: float = field(init=False, repr=False, compare=False)
    unloading_k: float = field(init=False, repr=False, compare=False)
    stored_at_peak_J: float = field(init=False, repr=False, compare=False)

    name = ThorntonLaw.name
    label = ThorntonLaw.label
    reading = ThorntonLaw.reading

    def __post_init__(self) -> None:
        p_max, residual, radius_p = (float(x) for x in self.law._unloading(self.max_approach_m))
        k_p = 4.0 / 3.0 * self.law.effective_modulus_pa * math.sqrt(radius_p)
        object.__setattr__(self, "peak_force_N", p_max)
        object.__setattr__(self, "residual_approach_m", residual)
        object.__setattr__(self, "unloading_radius_m", radius_p)
        object.__setattr__(self, "unloading_k", k_p)
        object.__setattr__(self, "stored_at_peak_J", 0.4 * k_p * max(self.max_approach_m - residual, 0.0) ** 2.5)

    def force(self, approach_m: float) -> float:
        if approach_m > self.max_approach_m:
            return self.law.force(approach_m)
        if approach_m <= self.residual_approach_m:
            return 0.0
        return self.unloading_k * (approach_m - self.residual_approach_m) ** 1.5

    def stiffness(self, approach_m: float) -> float:
        if approach_m > self.max_approach_m:
            return self.law.stiffness(approach_m)
        return 1.5 * self.unloading_k * math.sqrt(max(approach_m - self.residual_approach_m, 0.0))

    def energy(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha = np.asarray(approach_m, dtype=float)
        below = (
            0.4
            * self.unloading_k
            * np.maximum(np.minimum(alpha, self.max_approach_m) - self.residual_approach_m, 0.0) ** 2.5
        )
        above = np.where(
            alpha > self.max_approach_m,
            self.law.energy(np.maximum(alpha, self.max_approach_m)) - self.law.energy(self.max_approach_m),
            0.0,
        )
        total = below + above
        return float(total) if total.ndim == 0 else total

    def approach(self, force_N: float) -> float:
        if force_N > self.peak_force_N:
            return self.law.approach(force_N)
        return self.residual_approach_m + (max(force_N, 0.0) / self.unloading_k) ** (2.0 / 3.0)

    def contact_radius(self, approach_m: ArrayLike) -> NDArray[np.float64] | float:
        alpha = np.asarray(approach_m, dtype=float)
        below = np.sqrt(self.unloading_radius_m * np.maximum(alpha - self.residual_approach_m, 0.0))
        return np.where(alpha > self.max_approach_m, self.law.contact_radius(alpha), below)

    def solve_step(self, a: float, b: float, guess: float) -> tuple[float, int]:
        """The root of alpha + b P(alpha) = a, piece by piece in closed form or by the Hertz
        step: f is increasing, so its value at the kinks (alpha_m, alpha_y) says which piece
        holds the root."""
        peak, residual = self.max_approach_m, self.residual_approach_m
        if a <= peak + b * self.peak_force_N:  # on the unloading curve
            if a <= residual:
                return max(a, 0.0), 1
            alpha, iterations = solve_hertz_step(a - residual, b, self.unloading_k, guess - residual)
            return residual + alpha, iterations
        law = self.law
        alpha_y = law.yield_approach_m
        if alpha_y > peak and a <= alpha_y + b * law.yield_force_N:  # loading, still Hertz
            return solve_hertz_step(a, b, law.k, guess)
        c = law.plastic_stiffness_n_per_m  # loading, plastic: alpha + b (P_y + c (alpha - alpha_y)) = a
        return (a - b * law.yield_force_N + b * c * alpha_y) / (1.0 + b * c), 1
