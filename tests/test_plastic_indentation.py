"""The continuum's elastic-plastic static indentation: J2 in the plastic region, the elastic rest
condensed once; checked against the elastic solve, the published sphere-on-flat fits, and by its
unloading (a dent and dissipated work)."""

from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import Basis

from rodimpact.contact.sphere_flat import (
    critical_force,
    jackson_green_force,
    kogut_etsion_critical_interference,
    kogut_etsion_force,
)
from rodimpact.contact.tabulated import TabulatedLaw, TabulatedMemoryLaw
from rodimpact.solvers.fem_axi import indentation
from rodimpact.solvers.fem_axi.aximodel import build_model, material_groups
from rodimpact.solvers.fem_axi.axisym import axisym_stiffness
from rodimpact.solvers.fem_axi.indentation import static_indentation
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.plastic_region import plastic_region
from rodimpact.solvers.fem_axi.plasticity import J2Material
from rodimpact.storage.curves import read_contact_curve, write_contact_curve
from rodimpact.tools.sphere_flat import (
    RADIUS_M,
    SPHERE,
    contact_modulus,
    critical_interference,
    sphere_flat_path,
    sphere_flat_problem,
)

COARSE = FEMAxiOptions(elements_across=8, contact_extent=2.5, plastic_extent=2.0, continuum_diameters=None)


@pytest.fixture(scope="module")
def loading():
    """The hemisphere on the flat, loaded to omega* = 8 on the coarse mesh (5 % increments)."""
    path = sphere_flat_path((4.0, 8.0), 1.05)
    result = static_indentation(sphere_flat_problem(8.0), path * critical_interference(), COARSE)
    return path, result


def test_strain_operator_reproduces_the_stiffness():
    """E^T W D_e E over the region's points is the region's elastic stiffness (rtol 1e-10)."""
    problem = sphere_flat_problem(4.0)
    model = build_model(problem, COARSE, dynamic=False)
    imp = model.impactor
    _, groups = material_groups(problem, model)
    region = plastic_region(imp.basis, imp.T, groups, 1.5 * model.scales.contact_radius_m, held=[imp.n - 1])
    assert region is not None and len(region.coordinates) > 100
    part = Basis(imp.basis.mesh, imp.basis.elem, elements=region.elements)
    K = imp.T.T @ axisym_stiffness(part, SPHERE.youngs_modulus_pa, SPHERE.poisson_ratio) @ imp.T
    K = sp.csr_matrix(K)[region.coordinates][:, region.coordinates].toarray()
    D = J2Material(SPHERE.youngs_modulus_pa, SPHERE.poisson_ratio, SPHERE.yield_stress_pa).elastic_tangent
    blocks = sp.block_diag([w * D for w in region.weights])
    assembled = (region.strain_operator.T @ blocks @ region.strain_operator).toarray()
    np.testing.assert_allclose(assembled, K, rtol=1e-10, atol=1e-10 * np.abs(K).max())


def test_a_yield_stress_never_reached_gives_the_elastic_solve():
    """With a yield stress far above the stresses, the plastic path (condensed rest, Newton) gives the
    elastic solve's forces and mean displacements to 1e-9."""
    problem = sphere_flat_problem(4.0)
    strong = dataclasses.replace(problem, impactor_material=dataclasses.replace(SPHERE, yield_stress_pa=1e15))
    elastic = dataclasses.replace(problem, impactor_material=dataclasses.replace(SPHERE, yield_stress_pa=None))
    d = np.array([0.5, 1.0, 2.0, 4.0]) * critical_interference()
    plastic_run = static_indentation(strong, d, COARSE)
    elastic_run = static_indentation(elastic, d, COARSE)
    assert elastic_run.plastic_work_J is None
    assert plastic_run.success and plastic_run.plastic_work_J is not None
    np.testing.assert_array_equal(plastic_run.yielded_points, 0)
    np.testing.assert_allclose(plastic_run.force_N, elastic_run.force_N, rtol=1e-9)
    np.testing.assert_allclose(plastic_run.face_displacement_m, elastic_run.face_displacement_m, rtol=1e-9, atol=1e-18)
    np.testing.assert_allclose(plastic_run.contact_radius_m, elastic_run.contact_radius_m, rtol=0)
    # one Newton iteration per displacement: nothing yields
    assert plastic_run.newton_iterations == len(d)


def test_first_yield_at_the_critical_interference(loading):
    """First yield within 10 % of Jackson and Green's omega_c (from a half-space's Hertz stress; the
    coarse mesh yields one point at 0.94)."""
    path, result = loading
    assert result.success, result.message
    assert np.all(result.yielded_points[path < 0.9] == 0)
    assert np.all(result.yielded_points[path > 1.1] > 0)


@pytest.mark.parametrize("ratio, rtol", [(4.0, 0.03), (8.0, 0.04)])
def test_sphere_on_a_flat_against_the_published_fits(loading, ratio, rtol):
    """P / P_c of the coarse mesh against Jackson and Green's and Kogut and Etsion's fits: within
    their own spread (they differ by up to 1.3 % here; the finer meshes, make sphere-flat)."""
    path, result = loading
    e_prime, nu, s_y = contact_modulus(), SPHERE.poisson_ratio, SPHERE.yield_stress_pa
    omega_c = critical_interference()
    p_c = critical_force(RADIUS_M, e_prime, omega_c)
    fe = result.force_N[np.argmin(np.abs(path - ratio))] / p_c
    omega_ke = kogut_etsion_critical_interference(RADIUS_M, e_prime, s_y, nu)
    ke = kogut_etsion_force(ratio * omega_c / omega_ke) * critical_force(RADIUS_M, e_prime, omega_ke) / p_c
    jg = jackson_green_force(ratio, RADIUS_M, e_prime, s_y, nu)
    assert fe == pytest.approx(float(jg), rel=rtol)
    assert fe == pytest.approx(float(ke), rel=rtol)
    # and clearly below Hertz: the sphere has yielded
    assert fe < 0.96 * ratio**1.5


def test_a_failed_increment_is_cut_and_resumed_from_the_last_state(loading, monkeypatch):
    """With too few Newton iterations allowed for the full increments (omega* 2, 4, 6, 8), each
    failing increment is retried in halves from the last converged state (the failed attempt rolled
    back): the path completes, reports its cuts, and lands within 1 % of the 5 % increments' force at
    8 omega_c (a J2 path's small dependence on its steps); without cuts allowed it fails, naming the
    displacement."""
    path, fine = loading
    omega_c = critical_interference()
    coarse = np.array([2.0, 4.0, 6.0, 8.0]) * omega_c
    monkeypatch.setattr(indentation, "MAX_NEWTON", 5)  # the full increments need 6
    cut = static_indentation(sphere_flat_problem(8.0), coarse, COARSE)
    assert cut.success, cut.message
    assert cut.increment_cuts > 0
    assert cut.force_N[-1] == pytest.approx(fine.force_N[np.argmin(np.abs(path - 8.0))], rel=0.01)
    assert np.all(np.diff(cut.plastic_work_J) > 0)
    monkeypatch.setattr(indentation, "MAX_CUTS", 0)
    failed = static_indentation(sphere_flat_problem(8.0), coarse, COARSE)
    assert failed.status == "not_converged"
    assert len(failed.force_N) < len(coarse)


def test_unloading_leaves_a_dent_and_the_work_is_dissipated():
    """Loaded to 6 omega_c and unloaded: the force falls below the loading curve, vanishes at a dent
    (a positive interference), and the plastic work grows on loading only."""
    omega_c = critical_interference()
    up = sphere_flat_path((6.0,), 1.1)
    down = np.linspace(6.0, 0.0, 25)[1:]
    path = np.concatenate([up, down])
    result = static_indentation(sphere_flat_problem(6.0), path * omega_c, COARSE)
    assert result.success, result.message
    forces = result.force_N
    top = len(up) - 1
    loading = np.interp(down[:-1], up, forces[: top + 1])
    assert np.all(forces[top + 1 : -1] <= loading + 1e-12 * forces[top])
    assert forces[-1] == 0.0
    dent = down[np.argmax(forces[top + 1 :] == 0.0)]
    assert dent > 0.0  # contact is lost above zero interference
    work = result.plastic_work_J
    assert np.all(np.diff(work) >= -1e-12 * work[-1])
    assert work[top] > 0 and math.isclose(work[-1], work[top], rel_tol=0.05)


def test_a_plastic_region_too_small_is_reported():
    """The plastic zone outgrows a region of 0.3 contact radii: status 'plastic_region', a message
    naming plastic_extent, and only the displacements solved before."""
    options = dataclasses.replace(COARSE, plastic_extent=0.3)
    d = np.array([1.0, 2.0, 4.0, 8.0]) * critical_interference()
    result = static_indentation(sphere_flat_problem(8.0), d, options)
    assert not result.success
    assert result.status == "plastic_region"
    assert "plastic_extent" in result.message
    assert len(result.force_N) < len(d)


@pytest.fixture(scope="module")
def yielding_curve(shipped_project):
    """The indentation rule's curve of the lightest Table 2 ball on the 10 mm rod, ball and rod of
    yielding materials (the ball maker's 2.03 GPa, 6061-T6's 276 MPa), on a coarse mesh."""
    from rodimpact.jobs.indentation import indentation_curve

    case = copy.deepcopy(shipped_project.cases["ball_3.16mm-r10_l30_cal"])
    case["impactor"]["material"]["yield_stress_pa"] = 2.03e9
    case["rod"]["material"]["yield_stress_pa"] = 2.76e8
    settings = {"elements_across": 5, "contact_extent": 2.5, "plastic_extent": 4.0}
    return case, indentation_curve(case, settings)


def test_the_indentation_rule_gives_unloading_curves_where_a_material_yields(yielding_curve, tmp_path):
    """A yielding case's curve holds unloading curves, the elastic limit and their interpolation
    error; it is stored and read back whole; the law it makes has memory, and its rigid impact
    leaves a dent and dissipates what loading did not give back."""
    case, curve = yielding_curve
    summary = curve.summary
    assert summary["unloading_curves"] >= 3
    assert 0.0 < summary["elastic_limit_m"] < curve.data["approach_m"][-1]
    assert 0.0 < summary["unloading_interpolation_error_half"] < 0.05
    index = curve.data["unloading_curve"]
    assert np.all(np.diff(index) >= 0) and len(np.unique(index)) == summary["unloading_curves"]
    # every unloading curve starts at a point of the loading curve and falls
    for k in np.unique(index):
        alpha = curve.data["unloading_approach_m"][index == k]
        force = curve.data["unloading_force_N"][index == k]
        assert alpha[0] in curve.data["approach_m"]
        assert np.all(np.diff(force) <= 0) and force[-1] == 0.0
    path = write_contact_curve(tmp_path / "curve.h5", curve)
    back = read_contact_curve(path)
    for name, values in curve.data.items():
        np.testing.assert_array_equal(back.data[name], values)
    law = TabulatedLaw.from_bodies({"from": "fem_axi_indentation", "curve": back.law_curve()}, 0.00158, SPHERE, SPHERE)
    assert isinstance(law, TabulatedMemoryLaw)
    mass, velocity = case["impactor"]["mass_kg"], case["impactor"]["velocity_m_s"]
    impact = law.rigid_impact(mass, velocity)
    assert 0.5 < impact.restitution < 0.95 and impact.residual_approach_m > 0.0
    kinetic = 0.5 * mass * velocity**2
    dissipated = float(law.dissipated_energy(impact.max_approach_m))
    assert dissipated == pytest.approx(kinetic * (1.0 - impact.restitution**2), rel=1e-9)


def test_unloading_curves_without_their_elastic_limit_are_refused(yielding_curve, tmp_path):
    """A curve file with unloading curves must say where the contact stops being elastic."""
    _, curve = yielding_curve
    bare = dataclasses.replace(curve, summary={k: v for k, v in curve.summary.items() if k != "elastic_limit_m"})
    with pytest.raises(ValueError, match="elastic limit"):
        write_contact_curve(tmp_path / "bare.h5", bare)
    partial = dataclasses.replace(curve, data={k: v for k, v in curve.data.items() if k != "unloading_force_N"})
    with pytest.raises(ValueError, match="unloading datasets"):
        write_contact_curve(tmp_path / "partial.h5", partial)
