"""Responses of the colliding bodies to a force applied at the contact point.

The semi-analytical method needs each body's displacement at the contact point per unit
impulse, Y(t) in m/(N s); the paper prints the responses to a unit *ramp* force instead
(docs/paper-notes.md, "Impulse responses"). Derived here:

Rod (d'Alembert, end x = 0 loaded, far end x = l fixed or free). In Laplace space the end
compliance is tanh(s T) / (Z s) (fixed) or coth(s T) / (Z s) (free), with T = l/a the one-way
travel time, a = sqrt(E/rho) and Z = E S / a the rod's impedance. Expanding in e^{-2sT},

    Z Y1(t) = sum_{j>=0} c_j H(t - 2 j T),   c_0 = 1,  c_j = 2 s^j,  s = -1 (fixed), +1 (free),

a square wave of height +-1/Z for the fixed end (period 4T, zero mean) and a staircase
1, 3, 5, ... /Z for the free end (mean slope 1/M_rod: the rigid-body motion). Integrating
once gives the step response (a triangle wave whose mean is the static compliance
l/(E S) for the fixed end) and twice the ramp response printed in the paper.

Rigid impactor (Newton): Y2(t) = t/m; its ramp response is the paper's t^3/(6 m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.model.materials import Material, wave_speed

__all__ = [
    "Rod",
    "rod_impulse_response",
    "rod_step_response",
    "rod_ramp_response",
    "paper_rod_ramp_response",
    "impactor_impulse_response",
    "impactor_ramp_response",
]

FarEnd = Literal["fixed", "free"]


@dataclass(frozen=True)
class Rod:
    """A straight prismatic elastic rod struck at one end.

    Parameters
    ----------
    length_m : float
        Length l, m (> 0; ``math.inf`` for a semi-infinite rod).
    area_m2 : float
        Cross-section area S, m^2 (> 0).
    material : Material
        The rod's material.
    far_end : {"fixed", "free"}
        Condition at x = l.
    """

    length_m: float
    area_m2: float
    material: Material
    far_end: FarEnd = "fixed"

    def __post_init__(self) -> None:
        if not (self.length_m > 0):
            raise ValueError(f"length_m must be > 0, got {self.length_m!r}")
        if not (math.isfinite(self.area_m2) and self.area_m2 > 0):
            raise ValueError(f"area_m2 must be > 0, got {self.area_m2!r}")
        if self.far_end not in ("fixed", "free"):
            raise ValueError(f"far_end must be 'fixed' or 'free', got {self.far_end!r}")

    @property
    def wave_speed(self) -> float:
        """Bar wave speed a, m/s."""
        return wave_speed(self.material)

    @property
    def impedance(self) -> float:
        """Mechanical impedance Z = E S / a = rho a S, N s/m."""
        return self.material.youngs_modulus_pa * self.area_m2 / self.wave_speed

    @property
    def reflection_period(self) -> float:
        """Round-trip travel time 2T = 2 l / a, s (inf for a semi-infinite rod)."""
        return 2.0 * self.length_m / self.wave_speed

    @property
    def reflection_sign(self) -> int:
        """s in c_j = 2 s^j: -1 for a fixed far end, +1 for a free one."""
        return -1 if self.far_end == "fixed" else 1

    @property
    def static_compliance(self) -> float:
        """l / (E S), m/N (meaningful for a fixed far end)."""
        return self.length_m / (self.material.youngs_modulus_pa * self.area_m2)

    @property
    def mass_kg(self) -> float:
        """rho S l, kg."""
        return self.material.density_kg_m3 * self.area_m2 * self.length_m


def _reflection_sum(t: ArrayLike, rod: Rod, power: int) -> NDArray[np.float64]:
    """Z * sum_j c_j (t - 2jT)_+^power / power!  (power 0: Heaviside with H(0) = 0)."""
    t = np.asarray(t, dtype=float)
    period = rod.reflection_period
    n_max = 0 if not math.isfinite(period) else int(np.max(t, initial=0.0) // period) + 1
    out = np.zeros_like(t)
    for j in range(n_max + 1):
        shifted = t - j * period
        coeff = 1.0 if j == 0 else 2.0 * rod.reflection_sign**j
        if power == 0:
            term = (shifted > 0).astype(float)
        else:
            term = np.where(shifted > 0, shifted, 0.0) ** power / math.factorial(power)
        out += coeff * term
    return out / rod.impedance


def rod_impulse_response(t: ArrayLike, rod: Rod) -> NDArray[np.float64]:
    """Displacement of the struck end per unit impulse, Y1(t), m/(N s).

    Parameters
    ----------
    t : array_like, shape (n,)
        Times after the impulse, s.
    rod : Rod
        The rod.

    Returns
    -------
    ndarray, shape (n,)
        (1/Z) sum_j c_j H(t - 2jT).
    """
    return _reflection_sum(t, rod, 0)


def rod_step_response(t: ArrayLike, rod: Rod) -> NDArray[np.float64]:
    """End displacement per unit step force, integral of Y1, m/N. Shape as ``t``."""
    return _reflection_sum(t, rod, 1)


def rod_ramp_response(t: ArrayLike, rod: Rod) -> NDArray[np.float64]:
    """End displacement under the force P(t) = t (unit ramp, N/s), m / (N/s). Shape as ``t``."""
    return _reflection_sum(t, rod, 2)


def paper_rod_ramp_response(t: ArrayLike, rod: Rod) -> NDArray[np.float64]:
    """The paper's printed "reaction to a unit impulse" of a rod with a fixed far end.

    As printed (three intervals, tau = a t / l, F the area):
    l^2/(2EFa) tau^2 on (0, 2); l^2/(2EFa) [8 - (4 - tau)^2] on (2, 4);
    l^2/(2EFa) [8 + (tau - 4)^2] on (4, 6). Defined here only on 0 <= tau <= 6; NaN beyond.
    It is the response to a unit ramp force (docs/paper-notes.md), kept to test the derivation.
    """
    t = np.asarray(t, dtype=float)
    e, area, a, length = rod.material.youngs_modulus_pa, rod.area_m2, rod.wave_speed, rod.length_m
    tau = a * t / length
    scale = length**2 / (2.0 * e * area * a)
    return scale * np.select(
        [tau < 0, tau <= 2, tau <= 4, tau <= 6],
        [np.zeros_like(tau), tau**2, 8.0 - (4.0 - tau) ** 2, 8.0 + (tau - 4.0) ** 2],
        default=np.nan,
    )


def impactor_impulse_response(t: ArrayLike, mass_kg: float) -> NDArray[np.float64]:
    """Rigid impactor: displacement per unit impulse, Y2(t) = t/m, m/(N s). Shape as ``t``."""
    t = np.asarray(t, dtype=float)
    return np.where(t > 0, t, 0.0) / mass_kg


def impactor_ramp_response(t: ArrayLike, mass_kg: float) -> NDArray[np.float64]:
    """Rigid impactor under a unit ramp force: t^3 / (6 m) (the paper's printed formula)."""
    t = np.asarray(t, dtype=float)
    return np.where(t > 0, t, 0.0) ** 3 / (6.0 * mass_kg)
