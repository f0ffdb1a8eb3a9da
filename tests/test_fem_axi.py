"""fem_axi: the axisymmetric continuum model with real contact, verified against
mathematics (Hertz's static contact, d'Alembert's waves, energy and momentum) and against
the SEM on coarse settings. The forms themselves are verified in test_axisym.py, the meshes
in test_meshes.py; the converged comparison is the workflow's convergence study."""

import math

import numpy as np
import pytest
from skfem import Basis, ElementTriP2, ElementVector

from rodimpact.contact.hertz import effective_modulus, hertz_constant
from rodimpact.solvers.fem_axi.axibody import AxiBody, dofs_of
from rodimpact.solvers.fem_axi.axisym import (
    axis_dofs,
    axisym_load,
    axisym_mass,
    axisym_stiffness,
    cross_section_mean_uz,
)
from rodimpact.solvers.fem_axi.indentation import static_indentation
from rodimpact.solvers.fem_axi.meshes import rod_mesh
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import solve_fem_axi
from rodimpact.solvers.sem.options import SEMOptions
from rodimpact.solvers.sem.solver import solve_sem

from helpers.paper import STEEL, end_pulse_response, model_problem


def test_static_indentation_is_hertzian():
    """Rigid-backed hemisphere (R = 10 mm) pressed on a stout steel rod: the load follows
    d = (P/k)^(2/3) + C P with k within 2 % of (4/3) E* sqrt(R), and the contact radius
    follows (3 P R / (4 E*))^(1/3) to within one node spacing."""
    problem = AxiImpact(0.5, 1.0, 0.01, STEEL, "cap", 0.02, 0.04, STEEL, "fixed")
    displacements = np.linspace(0.25, 1.0, 5) * 7e-5
    result = static_indentation(problem, displacements, FEMAxiOptions(elements_across=8))
    force = result.force_N
    design = np.column_stack([force ** (2.0 / 3.0), force])
    coef, *_ = np.linalg.lstsq(design, displacements, rcond=None)
    k_hertz = hertz_constant(0.01, STEEL)
    assert coef[0] ** -1.5 == pytest.approx(k_hertz, rel=0.02)
    assert np.max(np.abs(design @ coef - displacements)) < 1e-3 * displacements.max()
    # the linear term is the finite bodies' correction, of the order of 1 / (pi E* R)
    assert abs(coef[1]) < 3.0 / (math.pi * effective_modulus(STEEL) * 0.01)
    radius = (3 * force * 0.01 / (4 * effective_modulus(STEEL))) ** (1 / 3)
    assert np.all(np.abs(result.contact_radius_m - radius) <= result.node_spacing_m + 0.03 * radius)


def test_pulse_travels_at_the_bar_speed_and_reflects_from_the_fixed_end():
    """A smooth end-load pulse on a slender rod: the cross-section mean displacement at
    three quarters of the length follows d'Alembert's 1D solution (wave speed sqrt(E/rho),
    displacement inverted by the fixed end's reflection) to 2 % of its maximum."""
    radius, length = 1e-3, 0.2
    body_mesh = rod_mesh(radius, length, 0.5e-3, 1e-3, coarse_size_m=1e-3)
    basis = Basis(body_mesh.mesh, ElementVector(ElementTriP2()))
    far = body_mesh.boundaries["far"]
    removed = np.union1d(axis_dofs(basis), np.union1d(dofs_of(basis, far, 0), dofs_of(basis, far, 1)))
    body = AxiBody(
        basis,
        axisym_stiffness(basis, STEEL.youngs_modulus_pa, STEEL.poisson_ratio),
        axisym_mass(basis, STEEL.density_kg_m3),
        removed,
    )
    load = body.T.T @ axisym_load(basis, lambda r, z: (0.0, 1.0), "end")  # 1 Pa towards +z
    h = 0.2e-6
    body.factorise(h)
    body.start(0.0)
    station = body.reduce_rows(cross_section_mean_uz(basis, 0.75 * length, radius))
    run = end_pulse_response(body, load, station, length, math.pi * radius**2, h, 20e-6)
    values, exact, history, rod = run.values, run.exact, run.history, run.rod
    assert np.max(np.abs(values - exact)) < 0.02 * np.max(np.abs(exact))
    # the incident wave lifts the section by Q/Z; the fixed end's inverted reflection brings
    # it back to rest (a free end would double it)
    impulse = history.Q[-1]
    assert values.max() == pytest.approx(impulse / rod.impedance, rel=0.02)
    assert abs(values[-1]) < 0.02 * values.max()


@pytest.fixture(scope="module")
def coarse_model():
    problem = AxiImpact(0.5, 1.0, 0.01, STEEL, "cap", math.sqrt(5e-5 / math.pi), 0.5, STEEL, "fixed")
    return solve_fem_axi(problem, FEMAxiOptions(elements_across=5, steps_per_contact=150), stations=[0.5, 0.999, 1.0])


def test_a_station_at_the_rods_end_has_its_whole_strain(coarse_model):
    """The fixed end's station and one just inside it: the same strain (the far bar's last
    element), not half of it (a one-sided difference over the whole span's divisor)."""
    strain = coarse_model.extra_series["station_strain"][0]
    inside, end = strain[:, 1], strain[:, 2]
    assert np.max(np.abs(end)) > 0
    np.testing.assert_allclose(end, inside, rtol=0, atol=1e-3 * np.max(np.abs(inside)))


def test_coarse_model_is_close_to_the_sem(coarse_model):
    sem = solve_sem(model_problem(), SEMOptions(steps_per_contact=1000))
    assert coarse_model.success and coarse_model.n_contacts == 1
    assert coarse_model.contact_time_s == pytest.approx(sem.contact_time_s, rel=0.03)
    assert len(coarse_model.peak_force_N) == 3
    np.testing.assert_allclose(coarse_model.peak_force_N, sem.peak_force_N, rtol=0.08)
    # the contact zone stays inside the Hertz estimate it was meshed for
    assert coarse_model.extra["max_contact_radius_m"] <= coarse_model.extra["estimated_contact_radius_m"]


def test_energy_and_momentum_balance(coarse_model):
    """Newmark's rule conserves energy up to the contact; the contact force's impulse is the
    impactor's loss of momentum."""
    assert abs(coarse_model.energy_error) < 2e-4
    t, force = coarse_model.time, coarse_model.contact_force
    impulse = np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(t))
    loss = 0.5 * (1.0 - coarse_model.rebound_velocity_m_s)
    assert impulse == pytest.approx(loss, rel=2e-3)


def test_a_cap_heavier_than_the_impactor_is_refused():
    problem = AxiImpact(0.01, 1.0, 0.01, STEEL, "cap", 0.004, 0.5, STEEL, "fixed")
    with pytest.raises(ValueError, match="cap_height"):
        solve_fem_axi(problem, FEMAxiOptions(elements_across=4, steps_per_contact=50))
