"""J2 (von Mises) plasticity with linear isotropic hardening, at the points of an axisymmetric body.

Small strains. A point's strain is the axisymmetric Voigt vector of :mod:`.axisym`,
eps = [e_rr, e_zz, e_tt, gamma_rz] (gamma_rz = 2 e_rz, the engineering shear; the hoop strain
e_tt = u_r / r is a strain like the others, deviatoric parts included), and its stress
sigma = [s_rr, s_zz, s_tt, s_rz]. The material is elastic (Lame's lambda, mu; bulk modulus K)
with the yield function

    f = q - (Y + H alpha),    q = sqrt(3/2 s:s),

s the deviatoric stress, Y the uniaxial yield stress, H the linear isotropic hardening
modulus (0: perfectly plastic) and alpha the equivalent plastic strain.

:func:`return_map` is the implicit (backward Euler) update of a step, the radial return of Simo
and Hughes (*Computational Inelasticity*, 1998, box 3.2): the elastic trial stress from the
step's total strain less the last plastic strain; where the trial yield function is positive,
the plastic multiplier in closed form, d gamma = f_trial / (3 mu + H) (exact for linear
hardening), the deviatoric stress scaled back onto the yield surface along the trial's own
direction, and the consistent (algorithmic) tangent

    D = K m m^T + 2 mu (1 - 3 mu dgamma / q_trial) P_dev
        + 6 mu^2 (dgamma / q_trial - 1 / (3 mu + H)) n n^T,

n the unit deviatoric direction (de Souza Neto, Peric and Owen, *Computational Methods for
Plasticity*, 2008, eq. 7.120), which keeps a Newton iteration on the equilibrium quadratic. In
the Voigt form with engineering shear, m = [1, 1, 1, 0], P_dev is the deviatoric projector
(normal block delta_ij - 1/3, shear 1/2), and n n^T acts on the engineering shear directly
(n : d eps = n_rr de_rr + n_zz de_zz + n_tt de_tt + n_rz d gamma_rz).

Everything is vectorized over the points: a body's plastic region is a few elements near the
contact, so only their points are passed here; the rest of the mesh stays elastic and keeps its
factorization.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["YIELD_TOLERANCE", "J2Material", "J2State", "J2Update", "return_map"]

YIELD_TOLERANCE = 1e-10
"""A step is plastic at a point where the trial yield function exceeds this fraction of the
current yield stress: a point left on the yield surface by the last step (to rounding) starts
the next one elastic, as an unloading point must."""

#: m, the unit tensor in Voigt form.
_M = np.array([1.0, 1.0, 1.0, 0.0])
#: The deviatoric projector in Voigt form with engineering shear.
_P_DEV = np.array(
    [
        [2.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0, 0.0],
        [-1.0 / 3.0, 2.0 / 3.0, -1.0 / 3.0, 0.0],
        [-1.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0, 0.0],
        [0.0, 0.0, 0.0, 0.5],
    ]
)
#: Weights of s:s in Voigt form: the shear component counts twice.
_DOUBLE_SHEAR = np.array([1.0, 1.0, 1.0, 2.0])


@dataclass(frozen=True)
class J2Material:
    """An isotropic elastic-plastic material (von Mises, linear isotropic hardening).

    Parameters
    ----------
    youngs_modulus_pa : float
        E, Pa (> 0).
    poisson_ratio : float
        nu, in (-1, 0.5).
    yield_stress_pa : float
        Y, the uniaxial yield stress, Pa (> 0).
    hardening_modulus_pa : float
        H, Pa, in [0, E): the slope of the uniaxial stress against the plastic strain.
    """

    youngs_modulus_pa: float
    poisson_ratio: float
    yield_stress_pa: float
    hardening_modulus_pa: float = 0.0
    lam: float = field(init=False, repr=False, compare=False)
    mu: float = field(init=False, repr=False, compare=False)
    bulk: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        e, nu = self.youngs_modulus_pa, self.poisson_ratio
        if not (math.isfinite(e) and e > 0):
            raise ValueError(f"youngs_modulus_pa must be > 0, got {e!r}")
        if not -1.0 < nu < 0.5:
            raise ValueError(f"poisson_ratio must lie in (-1, 0.5), got {nu!r}")
        if not (math.isfinite(self.yield_stress_pa) and self.yield_stress_pa > 0):
            raise ValueError(f"yield_stress_pa must be > 0, got {self.yield_stress_pa!r}")
        if not (math.isfinite(self.hardening_modulus_pa) and 0 <= self.hardening_modulus_pa < e):
            raise ValueError(f"hardening_modulus_pa must lie in [0, E), got {self.hardening_modulus_pa!r}")
        object.__setattr__(self, "lam", e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)))
        object.__setattr__(self, "mu", e / (2.0 * (1.0 + nu)))
        object.__setattr__(self, "bulk", e / (3.0 * (1.0 - 2.0 * nu)))

    @property
    def elastic_tangent(self) -> NDArray[np.float64]:
        """The elastic matrix in Voigt form, (4, 4), Pa: K m m^T + 2 mu P_dev."""
        return self.bulk * np.outer(_M, _M) + 2.0 * self.mu * _P_DEV


@dataclass(frozen=True)
class J2State:
    """The history at each point: what a step starts from.

    Attributes
    ----------
    plastic_strain : ndarray, shape (n, 4)
        The plastic strain in Voigt form (engineering shear).
    equivalent_plastic_strain : ndarray, shape (n,)
        alpha, the accumulated equivalent plastic strain (>= 0).
    """

    plastic_strain: NDArray[np.float64]
    equivalent_plastic_strain: NDArray[np.float64]

    @classmethod
    def virgin(cls, points: int) -> J2State:
        """No plastic strain at ``points`` points."""
        return cls(np.zeros((points, 4)), np.zeros(points))


@dataclass(frozen=True)
class J2Update:
    """The result of :func:`return_map` at each point.

    Attributes
    ----------
    stress : ndarray, shape (n, 4)
        sigma at the step's end, Pa.
    state : J2State
        The history at the step's end.
    tangent : ndarray, shape (n, 4, 4)
        The consistent tangent d sigma / d eps, Pa (the elastic matrix where the step is elastic).
    yielded : ndarray of bool, shape (n,)
        The step is plastic at the point.
    plastic_work : ndarray, shape (n,)
        sigma : d eps_p over the step (backward Euler: q d gamma), J/m^3; of it H d gamma^2 / 2
        plus H alpha_n d gamma is stored by the hardening, the rest dissipated.
    """

    stress: NDArray[np.float64]
    state: J2State
    tangent: NDArray[np.float64]
    yielded: NDArray[np.bool_]
    plastic_work: NDArray[np.float64]


def return_map(material: J2Material, strain: ArrayLike, state: J2State) -> J2Update:
    """The stress, history and consistent tangent after a step to the total ``strain``.

    Parameters
    ----------
    material : J2Material
        The material.
    strain : array_like, shape (n, 4)
        The total strain at the step's end, Voigt form (engineering shear).
    state : J2State
        The history at the step's start.

    Returns
    -------
    J2Update
        Elastic where the trial yield function is not positive; otherwise the radial return
        (the module docstring).
    """
    eps = np.atleast_2d(np.asarray(strain, dtype=float))
    mu, bulk, hardening = material.mu, material.bulk, material.hardening_modulus_pa
    elastic = eps - state.plastic_strain
    volumetric = elastic[:, :3].sum(axis=1)
    # the deviatoric trial stress, tensor components (shear s_rz = mu gamma_rz)
    deviatoric = 2.0 * mu * (elastic @ _P_DEV.T)
    norm = np.sqrt(np.einsum("ij,ij,j->i", deviatoric, deviatoric, _DOUBLE_SHEAR))
    q_trial = math.sqrt(1.5) * norm
    f_trial = q_trial - (material.yield_stress_pa + hardening * state.equivalent_plastic_strain)
    # a point on the yield surface to rounding (the history a converged step left) stays elastic
    yielded = f_trial > YIELD_TOLERANCE * (material.yield_stress_pa + hardening * state.equivalent_plastic_strain)
    dgamma = np.where(yielded, f_trial / (3.0 * mu + hardening), 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        direction = np.where(yielded[:, None], deviatoric / norm[:, None], 0.0)  # unit n, tensor components
        scale = np.where(yielded, 1.0 - 3.0 * mu * dgamma / q_trial, 1.0)
    stress = deviatoric * scale[:, None] + (bulk * volumetric)[:, None] * _M
    # d eps_p = dgamma sqrt(3/2) n; the engineering shear component doubles
    increment = (math.sqrt(1.5) * dgamma)[:, None] * direction * np.array([1.0, 1.0, 1.0, 2.0])
    new_state = J2State(state.plastic_strain + increment, state.equivalent_plastic_strain + dgamma)
    tangent = np.broadcast_to(material.elastic_tangent, (len(eps), 4, 4)).copy()
    if yielded.any():
        q = q_trial[yielded]
        g = dgamma[yielded]
        n = direction[yielded]
        beta = 1.0 - 3.0 * mu * g / q
        gamma_bar = 6.0 * mu * mu * (g / q - 1.0 / (3.0 * mu + hardening))
        tangent[yielded] = (
            bulk * np.outer(_M, _M)[None]
            + (2.0 * mu * beta)[:, None, None] * _P_DEV[None]
            + gamma_bar[:, None, None] * np.einsum("pi,pj->pij", n, n)
        )
    plastic_work = np.where(yielded, (q_trial - 3.0 * mu * dgamma) * dgamma, 0.0)
    return J2Update(stress=stress, state=new_state, tangent=tangent, yielded=yielded, plastic_work=plastic_work)
