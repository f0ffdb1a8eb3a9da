"""The film or stack in the continuum model: its material regions and the contact's candidate nodes.

The rod and its layers are one body (:mod:`.film_mesh`): the stiffness and the mass are the
sums of each region's, assembled with ``Basis(mesh, elem, elements=region)`` and the region's
material. The layers' strain and kinetic energies are therefore in the rod's.

The contact's candidates are the *rod's* struck-surface nodes (the stack's surface z = -H
and, should the contact zone reach beyond the disc, the bare face z = 0), each kept out of
the impactor's surface: without a film the impactor's nodes are the candidates, but a soft
thin film loaded only at the impactor's nodes bulges between them (a static indentation of a
10 um film by a stiff sphere gave 0.66 of the thin-layer force with impactor nodes 1.5 h
apart, 0.78 at 0.77 h, 0.96 at 0.5 h). The film's surface nodes are as fine as the rod's
face under the contact, and the stiff impactor's surface between its own nodes follows its
elements' interpolation: u_z on the impactor's boundary facet that spans the candidate's
radius (quadratic along the facet for P2).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import Basis

from rodimpact.solvers.fem_axi.axibody import AxiBody, dofs_of
from rodimpact.solvers.fem_axi.axisym import axisym_mass, axisym_stiffness
from rodimpact.solvers.fem_axi.film_mesh import FilmRodMesh
from rodimpact.solvers.fem_axi.meshes import BodyMesh
from rodimpact.solvers.fem_axi.problem import AxiImpact

__all__ = ["film_contact", "film_rod_matrices"]


def film_rod_matrices(
    basis: Basis, film_mesh: FilmRodMesh, problem: AxiImpact, *, mass: bool = True
) -> tuple[Any, Any]:
    """Per-radian stiffness (N/m) and mass (kg) of the rod and its layers on ``basis``'s DOFs,
    each region assembled with its own material (``problem.rod_material``, each layer of
    ``problem.stack``); ``mass=False``: zeros for the mass (a static solve)."""
    stack, rod = problem.stack, problem.rod_material
    if stack is None:
        raise ValueError("problem: has no film or stack")
    if len(film_mesh.layer_elements) != len(stack.layers):
        raise ValueError(f"film_mesh: {len(film_mesh.layer_elements)} layers meshed for a stack of {len(stack.layers)}")
    rod_part = Basis(basis.mesh, basis.elem, elements=film_mesh.rod_elements)
    stiffness = axisym_stiffness(rod_part, rod.youngs_modulus_pa, rod.poisson_ratio)
    masses = axisym_mass(rod_part, rod.density_kg_m3) if mass else sp.csr_matrix((basis.N, basis.N))
    for layer, elements in zip(stack.layers, film_mesh.layer_elements):
        part = Basis(basis.mesh, basis.elem, elements=elements)
        stiffness = stiffness + axisym_stiffness(part, layer.youngs_modulus_pa, layer.poisson_ratio)
        if mass:
            masses = masses + axisym_mass(part, layer.density_kg_m3)
    return stiffness.tocsr(), masses.tocsr()


def _surface_uz_rows(basis: Basis, body: BodyMesh, radii: NDArray[np.float64], sphere_radius: float) -> sp.csr_matrix:
    """u_z of the impactor's surface at radii r (on its near half, z >= -R), shape (k, N):
    the interpolation along the boundary facet whose ends bracket r."""
    mesh = body.mesh
    facets = body.boundaries["surface"]
    ends = mesh.facets[:, facets]
    near = (mesh.p[1, ends] >= -sphere_radius).all(axis=0)
    facets, ends = facets[near], ends[:, near]
    r_ends = mesh.p[0, ends]
    swap = r_ends[0] > r_ends[1]
    ends[:, swap] = ends[::-1, swap]
    r0, r1 = np.sort(r_ends, axis=0)
    rows, cols, vals = [], [], []
    p2 = basis.facet_dofs.size > 0
    for i, r in enumerate(radii):
        hit = np.nonzero((r0 <= r) & (r <= r1) & (r1 > r0))[0]
        if hit.size == 0:
            raise ValueError(f"no impactor surface facet spans r = {r!r} m")
        j = hit[0]
        s = (r - r0[j]) / (r1[j] - r0[j])
        dofs = [basis.nodal_dofs[1, ends[0, j]], basis.nodal_dofs[1, ends[1, j]]]
        if p2:
            dofs.append(basis.facet_dofs[1, facets[j]])
            weights = [(1 - s) * (1 - 2 * s), s * (2 * s - 1), 4 * s * (1 - s)]
        else:
            weights = [1 - s, s]
        rows += [i] * len(dofs)
        cols += dofs
        vals += weights
    return sp.csr_matrix((vals, (rows, cols)), shape=(len(radii), basis.N))


def film_contact(
    rod_body: AxiBody, film_mesh: FilmRodMesh, imp_body: AxiBody, imp: BodyMesh, sphere_radius_m: float, extent_m: float
) -> tuple[sp.csr_matrix, sp.csr_matrix, NDArray[np.float64], NDArray[np.float64]]:
    """The contact's candidates with a film: the rod's struck-surface u_z DOFs within
    ``extent_m`` of the axis (and within the impactor's radius).

    The impactor is meshed in its own frame (touching the origin) and stands h lower in the
    rod's: its sphere's surface at radius r lies at z = -h - (R - sqrt(R^2 - r^2)), so the
    initial gap of a candidate at (r, z_s) is z_s + h + R - sqrt(R^2 - r^2).

    Returns
    -------
    B_rod, B_imp : scipy.sparse.csr_matrix, shape (c, rod DOFs) and (c, impactor DOFs)
        The closing of each gap from each body's free coordinates (u_z of the rod's node;
        minus u_z of the impactor's surface at the node's radius).
    gap0, r_c : ndarray, shape (c,)
        Initial gaps and the candidates' radii, m, sorted by radius.
    """
    basis, body = rod_body.basis, film_mesh.body
    R, h = sphere_radius_m, film_mesh.film_thickness_m
    faces = np.concatenate([body.boundaries["film"], body.boundaries["end"]])
    struck = dofs_of(basis, faces, 1)
    locs = basis.doflocs[:, struck]
    keep = locs[0] <= min(extent_m, R)
    struck, locs = struck[keep], locs[:, keep]
    order = np.lexsort((-locs[1], locs[0]))
    struck, locs = struck[order], locs[:, order]
    pick = sp.csr_matrix((np.ones(len(struck)), (np.arange(len(struck)), struck)), shape=(len(struck), basis.N))
    B_rod = rod_body.reduce_rows(pick)
    B_imp = -imp_body.reduce_rows(_surface_uz_rows(imp_body.basis, imp, locs[0], R))
    gap0 = (R - np.sqrt(R**2 - locs[0] ** 2)) + (locs[1] + h)
    return B_rod, B_imp, gap0, locs[0]
