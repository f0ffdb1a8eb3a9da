"""Linear elastic, isotropic materials (their values come from config/materials.yaml)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["Material", "wave_speed"]


@dataclass(frozen=True)
class Material:
    """A linear elastic isotropic material.

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
    """

    youngs_modulus_pa: float
    poisson_ratio: float
    density_kg_m3: float
    name: str = ""

    def __post_init__(self) -> None:
        label = f"material {self.name!r}: " if self.name else ""
        if not (math.isfinite(self.youngs_modulus_pa) and self.youngs_modulus_pa > 0):
            raise ValueError(f"{label}youngs_modulus_pa must be > 0, got {self.youngs_modulus_pa!r}")
        if not (math.isfinite(self.density_kg_m3) and self.density_kg_m3 > 0):
            raise ValueError(f"{label}density_kg_m3 must be > 0, got {self.density_kg_m3!r}")
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise ValueError(f"{label}poisson_ratio must lie in (-1, 0.5), got {self.poisson_ratio!r}")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any]) -> Material:
        """Build from a resolved config mapping (keys as in ``config/materials.yaml``)."""
        return cls(
            youngs_modulus_pa=float(data["youngs_modulus_pa"]),
            poisson_ratio=float(data["poisson_ratio"]),
            density_kg_m3=float(data["density_kg_m3"]),
            name=str(data.get("name", "")),
        )


def wave_speed(material: Material) -> float:
    """Longitudinal bar wave speed a = sqrt(E / rho), m/s."""
    return math.sqrt(material.youngs_modulus_pa / material.density_kg_m3)
