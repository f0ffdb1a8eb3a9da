"""Isotropic materials: linear elastic, and, where a material declares a yield stress,
elastic-plastic (von Mises, with linear isotropic hardening where it declares a hardening
modulus). Their values come from config/materials.yaml."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from rodimpact.settings.declare import Material as MaterialSetting

__all__ = ["Material", "wave_speed"]


@dataclass(frozen=True)
class Material:
    """An isotropic material: linear elastic, elastic-plastic where it has a yield stress.

    Parameters
    ----------
    youngs_modulus_pa : float
        Young's modulus E, Pa. Must be > 0.
    poisson_ratio : float
        Poisson's ratio mu, dimensionless, in the open interval (-1, 0.5).
    density_kg_m3 : float
        Mass density rho, kg/m^3. Must be > 0.
    name : str
        A label, for messages only.
    yield_stress_pa : float or None
        Uniaxial yield stress Y, Pa (> 0); None: the material stays elastic.
    hardening_modulus_pa : float or None
        Linear isotropic hardening modulus H (the slope of the uniaxial stress against the
        plastic strain), Pa (>= 0 and below E); None: perfectly plastic. Only with a yield stress.
    """

    youngs_modulus_pa: float
    poisson_ratio: float
    density_kg_m3: float
    name: str = ""
    yield_stress_pa: float | None = None
    hardening_modulus_pa: float | None = None

    def __post_init__(self) -> None:
        label = f"material {self.name!r}: " if self.name else ""
        if not (math.isfinite(self.youngs_modulus_pa) and self.youngs_modulus_pa > 0):
            raise ValueError(f"{label}youngs_modulus_pa must be > 0, got {self.youngs_modulus_pa!r}")
        if not (math.isfinite(self.density_kg_m3) and self.density_kg_m3 > 0):
            raise ValueError(f"{label}density_kg_m3 must be > 0, got {self.density_kg_m3!r}")
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise ValueError(f"{label}poisson_ratio must lie in (-1, 0.5), got {self.poisson_ratio!r}")
        problem = MaterialSetting.plastic_problem(
            self.youngs_modulus_pa, self.yield_stress_pa, self.hardening_modulus_pa
        )
        if problem is not None:
            field, reason = problem
            raise ValueError(f"{label}{field} {reason}")

    @property
    def yields(self) -> bool:
        """The material has a yield stress (it is elastic-plastic)."""
        return self.yield_stress_pa is not None

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any]) -> Material:
        """Build from a resolved config mapping (keys as in ``config/materials.yaml``)."""
        return cls(
            youngs_modulus_pa=float(data["youngs_modulus_pa"]),
            poisson_ratio=float(data["poisson_ratio"]),
            density_kg_m3=float(data["density_kg_m3"]),
            name=str(data.get("name", "")),
            yield_stress_pa=_optional(data.get("yield_stress_pa")),
            hardening_modulus_pa=_optional(data.get("hardening_modulus_pa")),
        )


def _optional(value: Any) -> float | None:
    return None if value is None else float(value)


def wave_speed(material: Material) -> float:
    """Longitudinal bar wave speed a = sqrt(E / rho), m/s."""
    return math.sqrt(material.youngs_modulus_pa / material.density_kg_m3)
