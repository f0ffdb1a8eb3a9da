"""The region of a body where its material may yield, and its response at a displacement.

Plasticity in ``fem_axi`` stays in the few elements near the contact: a body's *plastic region*
is its elements of a yielding material within a radius of the contact point, and the rest of
the body stays elastic and keeps its factorisation. With the plastic strain eps_p at the
region's quadrature points, the body's internal force is

    f_int(q) = K_e q - U p,    p = E^T W (D_e eps - sigma) = E^T W D_e eps_p,

K_e the elastic stiffness of the whole body, U the selection of the region's coordinates, E
the strain operator at the region's points (Voigt, :func:`~.axisym.strain`), W the points'
weights r dA (per radian, as in :func:`~.axisym.axisym_stiffness`), D_e the elastic matrix and
sigma the stress of the return map (:mod:`.plasticity`). The consistent tangent differs from
K_e only on the coordinates of the yielded points,

    K_t = K_e + U dK U^T,    dK = E^T W (D_t - D_e) E,

so its inverse is K_e's factor and a dense correction of the size of the yielded points'
coordinates (Woodbury): K_t^-1 = K_e^-1 - K_e^-1 U Z U^T K_e^-1 with Z = (I + dK S)^-1 dK and
S = U^T K_e^-1 U (:mod:`.indentation` uses it).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import Basis

from rodimpact.model.materials import Material
from rodimpact.solvers.fem_axi.axisym import strain
from rodimpact.solvers.fem_axi.plasticity import J2Material, J2State, return_map

__all__ = ["PlasticRegion", "RegionResponse", "YieldGuard", "j2_material", "plastic_region"]


def j2_material(material: Material) -> J2Material:
    """The J2 material of a yielding :class:`~rodimpact.model.materials.Material` (H = 0 when it
    declares none)."""
    if material.yield_stress_pa is None:
        raise ValueError(f"material {material.name or ''!r}: has no yield stress")
    return J2Material(
        material.youngs_modulus_pa,
        material.poisson_ratio,
        material.yield_stress_pa,
        material.hardening_modulus_pa or 0.0,
    )


@dataclass(frozen=True)
class PlasticRegion:
    """The elements of one body where a material may yield.

    Attributes
    ----------
    elements : ndarray of int, shape (e,)
        The region's triangles.
    coordinates : ndarray of int, shape (m,)
        The body's free coordinates the region's elements touch (U selects them).
    strain_operator : scipy.sparse.csr_matrix, shape (4 P, m)
        Strains at the region's P points from the region's coordinates: rows 4 p .. 4 p + 3
        are point p's [e_rr, e_zz, e_tt, gamma_rz].
    weights : ndarray, shape (P,)
        r dA of each point (the per-radian quadrature weight), m^3.
    materials : tuple of J2Material
        The region's materials.
    point_material : ndarray of int, shape (P,)
        Index into ``materials`` of each point's material.
    radius_m : float
        The region's radius about the contact point, m.
    """

    elements: NDArray[np.int64]
    coordinates: NDArray[np.int64]
    strain_operator: sp.csr_matrix
    weights: NDArray[np.float64]
    materials: tuple[J2Material, ...]
    point_material: NDArray[np.int64]
    radius_m: float

    @property
    def points(self) -> int:
        """P, the number of quadrature points."""
        return len(self.weights)

    def virgin(self) -> J2State:
        """No plastic strain at the region's points."""
        return J2State.virgin(self.points)

    def respond(self, q_region: NDArray[np.float64], state: J2State) -> RegionResponse:
        """The return map at the region's coordinates ``q_region`` (m, shape (m,)) from ``state``."""
        eps = (self.strain_operator @ q_region).reshape(-1, 4)
        relaxed = np.empty_like(eps)  # D_e eps - sigma = D_e eps_p at each point
        tangent_change = np.zeros((len(eps), 4, 4))
        plastic = np.empty_like(eps)
        alpha = np.empty(len(eps))
        work = np.zeros(len(eps))
        yielded = np.zeros(len(eps), dtype=bool)
        for k, material in enumerate(self.materials):
            at = np.flatnonzero(self.point_material == k)
            update = return_map(
                material, eps[at], J2State(state.plastic_strain[at], state.equivalent_plastic_strain[at])
            )
            relaxed[at] = eps[at] @ material.elastic_tangent.T - update.stress
            plastic[at] = update.state.plastic_strain
            alpha[at] = update.state.equivalent_plastic_strain
            tangent_change[at] = update.tangent - material.elastic_tangent
            yielded[at] = update.yielded
            work[at] = update.plastic_work
        load = self.strain_operator.T @ (self.weights[:, None] * relaxed).ravel()
        hit = np.flatnonzero(yielded)
        if hit.size:
            blocks = sp.block_diag([self.weights[i] * tangent_change[i] for i in hit], format="csr")
            rows = self.strain_operator[(4 * hit[:, None] + np.arange(4)).ravel()]
            change = sp.csr_matrix(rows.T @ blocks @ rows)
        else:
            change = sp.csr_matrix((len(self.coordinates), len(self.coordinates)))
        return RegionResponse(
            load=np.asarray(load, dtype=float),
            tangent_change=change,
            state=J2State(plastic, alpha),
            yielded=yielded,
            plastic_work_J=2.0 * math.pi * float(self.weights @ work),
        )


@dataclass(frozen=True)
class RegionResponse:
    """The region's response at a displacement (:meth:`PlasticRegion.respond`).

    Attributes
    ----------
    load : ndarray, shape (m,)
        p = E^T W (D_e eps - sigma), the plastic strain's load on the region's coordinates, N
        per radian (f_int = K_e q - U p).
    tangent_change : scipy.sparse.csr_matrix, shape (m, m)
        dK = E^T W (D_t - D_e) E, N/m per radian: nonzero on the yielded points' coordinates only.
    state : J2State
        The points' history at this displacement.
    yielded : ndarray of bool, shape (P,)
        The step is plastic at the point.
    plastic_work_J : float
        The plastic work of the step from the history it started from, J (3D).
    """

    load: NDArray[np.float64]
    tangent_change: sp.csr_matrix
    state: J2State
    yielded: NDArray[np.bool_]
    plastic_work_J: float


def _strain_rows(basis: Basis, elements: NDArray[np.int64]) -> tuple[sp.csr_matrix, NDArray[np.float64]]:
    """The strain operator (4 P, N full DOFs) at the points of ``elements`` and their weights r dA."""
    part = Basis(basis.mesh, basis.elem, elements=elements)
    r = part.default_parameters()["x"][0]  # (e, points)
    local = np.array([strain(phi[0], r) for phi in part.basis])  # (local, 4, e, points)
    n_local, _, n_el, n_pts = local.shape
    # point index p = e * n_pts + k; row 4 p + component
    point = (np.arange(n_el)[:, None] * n_pts + np.arange(n_pts)[None, :]).ravel()
    rows = (4 * point[None, :, None] + np.arange(4)[None, None, :]).repeat(n_local, axis=0)
    values = np.moveaxis(local, 1, -1).reshape(n_local, n_el * n_pts, 4)
    cols = np.broadcast_to(
        np.repeat(part.element_dofs[:, :, None], n_pts, axis=2).reshape(n_local, -1, 1), values.shape
    )
    operator = sp.csr_matrix((values.ravel(), (rows.ravel(), cols.ravel())), shape=(4 * n_el * n_pts, basis.N))
    weights = (r * part.dx).ravel()
    return operator, weights


def plastic_region(
    basis: Basis,
    reduction: sp.spmatrix,
    groups: Sequence[tuple[NDArray[np.int64], Material]],
    radius_m: float,
    held: Sequence[int] = (),
) -> PlasticRegion | None:
    """The elements of a yielding material within ``radius_m`` of the origin (the contact point).

    Parameters
    ----------
    basis : skfem.Basis
        The body's vector basis.
    reduction : sparse matrix, shape (N, n)
        u = T q, the body's map from free coordinates to DOFs (:class:`~.axibody.AxiBody`'s ``T``).
    groups : sequence of (elements, Material)
        The body's elements by material.
    radius_m : float
        The region's radius, m: an element belongs to it when its centroid lies within.
    held : sequence of int
        Free coordinates held at zero in the solve (the cap's rigid back): left out.

    Returns
    -------
    PlasticRegion or None
        None when no yielding material lies within the radius.
    """
    mesh = basis.mesh
    centroid = mesh.p[:, mesh.t].mean(axis=1)
    near = np.hypot(centroid[0], centroid[1]) <= radius_m
    chosen, materials, labels = [], [], []
    for elements, material in groups:
        if not material.yields:
            continue
        inside = np.asarray(elements, dtype=np.int64)[near[elements]]
        if inside.size:
            chosen.append(inside)
            labels.append(np.full(inside.size, len(materials)))
            materials.append(j2_material(material))
    if not chosen:
        return None
    elements = np.concatenate(chosen)
    element_label = np.concatenate(labels)
    operator, weights = _strain_rows(basis, elements)
    reduced = sp.csr_matrix(operator @ reduction)
    used = np.setdiff1d(np.unique(reduced.indices), np.asarray(held, dtype=np.int64))
    n_pts = len(weights) // len(elements)
    return PlasticRegion(
        elements=elements,
        coordinates=used.astype(np.int64),
        strain_operator=sp.csr_matrix(reduced[:, used]),
        weights=weights,
        materials=tuple(materials),
        point_material=np.repeat(element_label, n_pts).astype(np.int64),
        radius_m=float(radius_m),
    )


@dataclass(frozen=True)
class YieldGuard:
    """The yielding material's elements just beyond a plastic region, where the body must stay
    elastic: their strain operator on the body's DOFs, built once.

    Attributes
    ----------
    strain_operator : scipy.sparse.csr_matrix, shape (4 P, N)
        Strains at the points beyond the region from the body's full DOFs.
    materials : tuple of J2Material
        The materials of the points.
    point_material : ndarray of int, shape (P,)
        Index into ``materials`` of each point's material.
    """

    strain_operator: sp.csr_matrix
    materials: tuple[J2Material, ...]
    point_material: NDArray[np.int64]

    @classmethod
    def beyond(
        cls,
        basis: Basis,
        groups: Sequence[tuple[NDArray[np.int64], Material]],
        region: PlasticRegion,
        reach: float = 2.0,
    ) -> YieldGuard:
        """The yielding elements beyond ``region`` but within ``reach`` times its radius."""
        mesh = basis.mesh
        centroid = mesh.p[:, mesh.t].mean(axis=1)
        distance = np.hypot(centroid[0], centroid[1])
        ring = (distance > region.radius_m) & (distance <= reach * region.radius_m)
        operators, materials, labels = [], [], []
        for elements, material in groups:
            if not material.yields:
                continue
            outside = np.asarray(elements, dtype=np.int64)[ring[elements]]
            if not outside.size:
                continue
            operator, weights = _strain_rows(basis, outside)
            operators.append(operator)
            labels.append(np.full(len(weights), len(materials)))
            materials.append(j2_material(material))
        if not operators:
            return cls(sp.csr_matrix((0, basis.N)), (), np.empty(0, dtype=np.int64))
        return cls(sp.csr_matrix(sp.vstack(operators)), tuple(materials), np.concatenate(labels).astype(np.int64))

    def ratio(self, u: NDArray[np.float64]) -> float:
        """The largest von Mises stress over the yield stress at these points, elastic, for the
        body's DOFs ``u`` (m): 1 or more means the region is too small for the plastic zone."""
        if not self.materials:
            return 0.0
        eps = (self.strain_operator @ u).reshape(-1, 4)
        worst = 0.0
        for k, material in enumerate(self.materials):
            at = self.point_material == k
            deviatoric = 2.0 * material.mu * (eps[at] - (eps[at, :3].sum(axis=1) / 3.0)[:, None] * _TRACE)
            deviatoric[:, 3] *= 0.5  # the engineering shear: s_rz = mu gamma_rz
            mises = np.sqrt(1.5 * np.einsum("ij,ij,j->i", deviatoric, deviatoric, _DOUBLE))
            worst = max(worst, float(mises.max() / material.yield_stress_pa))
        return worst


_TRACE = np.array([1.0, 1.0, 1.0, 0.0])
_DOUBLE = np.array([1.0, 1.0, 1.0, 2.0])
