"""The ``fem_axi`` model assembled: both bodies meshed, their operators and the contact's candidates.

:func:`build_model` meshes the rod (:mod:`.meshes`, or with a film or stack :mod:`.film_mesh`)
and the impactor (a ball or an elastic cap with a rigid rear part), assembles each body's
per-radian stiffness and mass (:mod:`.axisym`) into its reduced operators (:mod:`.axibody`),
joins a far bar (:mod:`.farbar`) when the rod is long, and picks the candidate contact nodes
with their gap rows and initial gaps (:class:`AxiModel`). :func:`~.solver.solve_fem_axi` steps
it in time; :mod:`.indentation` solves it statically.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import Basis, ElementTriP1, ElementTriP2, ElementVector

from rodimpact.model.materials import Material
from rodimpact.solvers.fem_axi.axibody import AxiBody, dofs_of
from rodimpact.solvers.fem_axi.axisym import axis_dofs, axisym_mass, axisym_stiffness
from rodimpact.solvers.fem_axi.farbar import FarBar, continuum_length
from rodimpact.solvers.fem_axi.film_mesh import FilmRodMesh, film_rod_mesh
from rodimpact.solvers.fem_axi.film_model import film_contact, film_rod_matrices
from rodimpact.solvers.fem_axi.meshes import ball_mesh, cap_mesh, rod_mesh
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact, AxiScales
from rodimpact.solvers.options import OptionError

__all__ = ["AxiModel", "build_model", "material_groups"]

log = logging.getLogger(__name__)

#: Elements across the largest (estimated) contact radius below which a run warns.
RECOMMENDED_ELEMENTS_ACROSS = 10


@dataclass(frozen=True)
class AxiModel:
    """The two bodies assembled, the contact's candidate nodes and the scales they were sized by.

    ``B_rod`` and ``B_imp`` (shape (c, d_rod) and (c, d_imp)) map each body's DOFs to the
    closing of the c candidate gaps; ``gap0`` (c,) is the initial gap, ``r_c`` (c,) the
    candidates' radii, m. With a film, ``rod`` is the rod and its film in one body (two
    materials) and ``film`` its mesh; the rod's end face stays at z = 0 and the film's
    surface is z = -h.
    """

    rod: AxiBody
    impactor: AxiBody
    B_rod: Any
    B_imp: Any
    gap0: NDArray[np.float64]
    r_c: NDArray[np.float64]
    scales: AxiScales
    fine_size_m: float
    film: FilmRodMesh | None = None


def _basis(mesh, element: str) -> Basis:
    return Basis(mesh, ElementVector(ElementTriP2() if element == "P2" else ElementTriP1()))


def _volume(basis: Basis) -> float:
    """Volume of the meshed solid of revolution, m^3 (2 pi * integral of r dA)."""
    ones = np.zeros(basis.N)
    ones[basis.nodal_dofs[1]] = 1.0
    if basis.facet_dofs.size:
        ones[basis.facet_dofs[1]] = 1.0
    return 2 * math.pi * float(ones @ (axisym_mass(basis, 1.0) @ ones))


def _mass(basis: Basis, density: float, dynamic: bool) -> sp.spmatrix:
    """The per-radian mass matrix of ``basis`` (kg), or zeros of its shape when not ``dynamic``."""
    return axisym_mass(basis, density) if dynamic else sp.csr_matrix((basis.N, basis.N))


def build_model(
    problem: AxiImpact, options: FEMAxiOptions, *, dynamic: bool = True, continuum_cover_m: float = 0.0
) -> AxiModel:
    """Mesh and assemble both bodies and the contact's candidate gaps.

    Without a film the rod's end face z = 0 is struck, the impactor's sphere touches it at the
    origin, and the candidates are the impactor's surface nodes. With a film or a stack
    (:mod:`.film_mesh`, :mod:`.film_model`) its surface z = -H is struck over r <= r_f and the
    bare face z = 0 beyond; the impactor, meshed in its own frame (touching the origin), stands H lower
    (its forms do not depend on z, so only its gaps see this); the candidates are the rod's
    struck-surface nodes.

    ``dynamic=False`` (a static solve, :mod:`.indentation`) leaves the mass matrices out: the
    bodies get zero masses (the stiffnesses, candidates and gaps are the same bit for bit).

    The rod is a continuum over 0 <= z <= z_c and a 1-D bar beyond (:func:`~.farbar.continuum_length`,
    from ``continuum_diameters``): ``continuum_cover_m`` (m; the gauges',
    :func:`~.gauges.continuum_cover_m`) makes the continuum reach at least that far, and 0
    (default) leaves the model as it is without gauges, bit for bit.
    """
    scales = problem.scales()
    a_contact = scales.contact_radius_m
    if options.elements_across < RECOMMENDED_ELEMENTS_ACROSS:
        log.warning(
            "elements_across=%d: fewer than %d elements across the largest contact radius "
            "(a convergence-study level, not a result)",
            options.elements_across,
            RECOMMENDED_ELEMENTS_ACROSS,
        )
    fine = a_contact / options.elements_across
    extent = options.contact_extent * a_contact
    R = problem.sphere_radius_m
    film_mesh = None
    z_c = continuum_length(problem.rod_radius_m, problem.rod_length_m, options.continuum_diameters, continuum_cover_m)
    meshed_length = problem.rod_length_m if z_c is None else z_c
    if problem.stack is None:
        rod = rod_mesh(problem.rod_radius_m, meshed_length, fine, extent)
    else:
        film_mesh = film_rod_mesh(
            problem.rod_radius_m,
            meshed_length,
            fine,
            extent,
            problem.film_radius_m,
            [layer.thickness_m for layer in problem.stack.layers],
            options.film_layers,
        )
        rod = film_mesh.body
    rod_basis = _basis(rod.mesh, options.element)
    removed = axis_dofs(rod_basis)
    far = rod.boundaries["far"]
    bar, joint = None, np.empty(0, dtype=np.int64)
    if z_c is not None:
        bar = FarBar(
            start_m=z_c,
            length_m=problem.rod_length_m,
            radius_m=problem.rod_radius_m,
            youngs_modulus_pa=problem.rod_material.youngs_modulus_pa,
            density_kg_m3=problem.rod_material.density_kg_m3,
            fixed=problem.far_end == "fixed",
        )
        joint = dofs_of(rod_basis, far, 1)
    elif problem.far_end == "fixed":
        removed = np.union1d(removed, np.union1d(dofs_of(rod_basis, far, 0), dofs_of(rod_basis, far, 1)))
    if film_mesh is None:
        rod_body = AxiBody(
            rod_basis,
            axisym_stiffness(rod_basis, problem.rod_material.youngs_modulus_pa, problem.rod_material.poisson_ratio),
            _mass(rod_basis, problem.rod_material.density_kg_m3, dynamic),
            removed,
            bar=bar,
            joint=joint,
        )
    else:
        rod_body = AxiBody(
            rod_basis, *film_rod_matrices(rod_basis, film_mesh, problem, mass=dynamic), removed, bar=bar, joint=joint
        )
    mat = problem.impactor_material
    if problem.body == "sphere":
        imp = ball_mesh(R, fine, extent)
        imp_basis = _basis(imp.mesh, options.element)
        density = problem.mass_kg / _volume(imp_basis)  # the meshed ball weighs exactly m
        imp_body = AxiBody(
            imp_basis,
            axisym_stiffness(imp_basis, mat.youngs_modulus_pa, mat.poisson_ratio),
            _mass(imp_basis, density, dynamic),
            axis_dofs(imp_basis),
        )
    else:
        height = options.cap_height * R
        imp = cap_mesh(R, height, fine, extent)
        imp_basis = _basis(imp.mesh, options.element)
        back = imp.boundaries["back"]
        cap_mass = mat.density_kg_m3 * _volume(imp_basis)
        if cap_mass >= problem.mass_kg:
            raise OptionError(
                "cap_height",
                f"={options.cap_height}: the elastic cap ({cap_mass:.3g} kg) outweighs "
                f"the impactor ({problem.mass_kg:.3g} kg); use a smaller cap_height",
            )
        imp_body = AxiBody(
            imp_basis,
            axisym_stiffness(imp_basis, mat.youngs_modulus_pa, mat.poisson_ratio),
            _mass(imp_basis, mat.density_kg_m3, dynamic),
            np.union1d(axis_dofs(imp_basis), dofs_of(imp_basis, back, 0)),
            rigid=dofs_of(imp_basis, back, 1),
            rigid_mass_kg=problem.mass_kg - cap_mass,
        )
    if film_mesh is not None:
        B_rod, B_imp, gap0, r_c = film_contact(rod_body, film_mesh, imp_body, imp, R, extent)
        return AxiModel(
            rod=rod_body,
            impactor=imp_body,
            B_rod=B_rod,
            B_imp=B_imp,
            gap0=gap0,
            r_c=r_c,
            scales=scales,
            fine_size_m=fine,
            film=film_mesh,
        )
    # candidate contact nodes: the impactor's surface u_z DOFs within the extent
    surface_uz = dofs_of(imp_basis, imp.boundaries["surface"], 1)
    locs = imp_basis.doflocs[:, surface_uz]
    # near the contact point, not the far pole, and facing the rod
    keep = (locs[0] <= extent) & (locs[1] >= -2.0 * extent) & (locs[0] <= problem.rod_radius_m)
    surface_uz, locs = surface_uz[keep], locs[:, keep]
    order = np.argsort(locs[0])
    surface_uz, locs = surface_uz[order], locs[:, order]
    pick = sp.csr_matrix(
        (np.ones(len(surface_uz)), (np.arange(len(surface_uz)), surface_uz)), shape=(len(surface_uz), imp_basis.N)
    )
    B_imp = -imp_body.reduce_rows(pick)
    B_rod = rod_body.uz_probe_rows(np.vstack([locs[0], np.zeros(len(locs[0]))]))
    # the rod face is z = 0; the sphere's surface at radius r lies at z = -(R - sqrt(R^2 - r^2))
    gap0 = R - np.sqrt(R**2 - locs[0] ** 2)
    return AxiModel(
        rod=rod_body,
        impactor=imp_body,
        B_rod=B_rod,
        B_imp=B_imp,
        gap0=gap0,
        r_c=locs[0],
        scales=scales,
        fine_size_m=fine,
    )


def material_groups(
    problem: AxiImpact, model: AxiModel
) -> tuple[list[tuple[NDArray[np.int64], Material]], list[tuple[NDArray[np.int64], Material]]]:
    """The elements of the rod and of the impactor by material: (elements, Material) pairs.

    The rod's are its own and, with a film or stack, each layer's (a layer's material from its
    constants, its yield stress and hardening modulus included); the impactor's are all its own.
    """
    rod_elements = np.arange(model.rod.basis.mesh.t.shape[1], dtype=np.int64)
    imp_elements = np.arange(model.impactor.basis.mesh.t.shape[1], dtype=np.int64)
    imp = [(imp_elements, problem.impactor_material)]
    if model.film is None or problem.stack is None:
        return [(rod_elements, problem.rod_material)], imp
    rod = [(np.asarray(model.film.rod_elements, dtype=np.int64), problem.rod_material)]
    for layer, elements in zip(problem.stack.layers, model.film.layer_elements):
        material = Material(
            layer.youngs_modulus_pa,
            layer.poisson_ratio,
            layer.density_kg_m3,
            name=layer.name,
            yield_stress_pa=layer.yield_stress_pa,
            hardening_modulus_pa=layer.hardening_modulus_pa,
        )
        rod.append((np.asarray(elements, dtype=np.int64), material))
    return rod, imp
