"""fem_axi's far bar: the rod beyond z_c as a 1-D bar joined to the continuum's last section.

Verified against mathematics (a uniform stress state is exact through the joint, d'Alembert's
waves cross it) and against the full continuum (contact time, maxima, mid-rod displacement)."""

import math

import numpy as np
import pytest
from scipy.sparse.linalg import spsolve
from skfem import Basis, ElementTriP2, ElementVector

from rodimpact.solvers.fem_axi.axibody import AxiBody, dofs_of
from rodimpact.solvers.fem_axi.axisym import axis_dofs, axisym_load, axisym_mass, axisym_stiffness
from rodimpact.solvers.fem_axi.farbar import FarBar, continuum_length
from rodimpact.solvers.fem_axi.meshes import rod_mesh
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import solve_fem_axi

from helpers.paper import STEEL, end_pulse_response

RADIUS = 1e-3


def _rod_with_bar(length: float, z_c: float, fixed: bool = True) -> AxiBody:
    mesh = rod_mesh(RADIUS, z_c, 0.5e-3, 1e-3, coarse_size_m=1e-3)
    basis = Basis(mesh.mesh, ElementVector(ElementTriP2()))
    bar = FarBar(
        start_m=z_c,
        length_m=length,
        radius_m=RADIUS,
        youngs_modulus_pa=STEEL.youngs_modulus_pa,
        density_kg_m3=STEEL.density_kg_m3,
        fixed=fixed,
    )
    return AxiBody(
        basis,
        axisym_stiffness(basis, STEEL.youngs_modulus_pa, STEEL.poisson_ratio),
        axisym_mass(basis, STEEL.density_kg_m3),
        axis_dofs(basis),
        bar=bar,
        joint=dofs_of(basis, mesh.boundaries["far"], 1),
    )


def test_the_continuum_ends_after_its_diameters_on_a_rod_ten_continua_long():
    assert continuum_length(1e-3, 0.301, 5.0) == pytest.approx(0.010)
    assert continuum_length(0.01, 0.030, 5.0) is None  # the rod is shorter than 5 diameters
    assert continuum_length(1e-3, 0.0301, 5.0) is None  # 3 continua: the 1 mm rods of 30.1 mm
    assert continuum_length(0.01, 0.301, 5.0) is None  # 3 continua: the 10 mm rods of 301 mm
    assert continuum_length(1e-3, 0.100, 5.0) == pytest.approx(0.010)  # exactly 10
    assert continuum_length(1e-3, 0.0999, 5.0) is None
    assert continuum_length(1e-3, 0.301, None) is None


def test_bar_matrices_carry_the_bars_mass_and_stiffness():
    bar = FarBar(0.01, 0.3, RADIUS, STEEL.youngs_modulus_pa, STEEL.density_kg_m3, fixed=True)
    K, M = bar.matrices()
    area = math.pi * RADIUS**2
    assert 2 * math.pi * M.sum() == pytest.approx(STEEL.density_kg_m3 * area * 0.29, rel=1e-12)
    # an end force F on the bar fixed at z = L: the free end moves F (L - z_c) / (E A)
    keep = np.arange(bar.elements)  # the held node z = L is the last
    load = np.zeros(bar.elements)
    load[0] = 1.0 / (2 * math.pi)
    u = np.linalg.solve(K.toarray()[np.ix_(keep, keep)], load)
    assert u[0] == pytest.approx(0.29 / (STEEL.youngs_modulus_pa * area), rel=1e-12)
    assert bar.interpolation_row(0.3).toarray()[0, -1] == 1.0
    with pytest.raises(ValueError, match="bar"):
        bar.interpolation_row(0.005)


def test_uniform_stress_crosses_the_joint_exactly():
    """A uniform pressure p on the struck end of a fixed rod: u_z(z) = p (L - z) / E in the
    continuum and in the bar (the joint ties u_z and leaves u_r free, as uniaxial stress does)."""
    length, z_c, p = 0.05, 0.01, 1e6
    body = _rod_with_bar(length, z_c)
    load = body.T.T @ axisym_load(body.basis, lambda r, z: (0.0, p), "end")
    u = spsolve(body.K.tocsc(), load)
    for z in (0.0, 0.005, z_c, 0.02, 0.049):
        assert float((body.section_mean_uz_row(z, RADIUS) @ u)[0]) == pytest.approx(
            p * (length - z) / STEEL.youngs_modulus_pa, rel=1e-9
        )


def test_a_pulse_crosses_the_joint_and_reflects_as_dalembert_says():
    """A smooth end-load pulse: the mean displacement at 3/4 of the length, in the bar, follows
    d'Alembert's 1-D solution to 2 % of its maximum, and the energy is conserved once the load
    has ended."""
    length, z_c = 0.2, 0.01
    body = _rod_with_bar(length, z_c)
    load = body.T.T @ axisym_load(body.basis, lambda r, z: (0.0, 1.0), "end")
    h = 0.2e-6
    body.factorise(h)
    body.start(0.0)
    station = body.section_mean_uz_row(0.75 * length, RADIUS)
    run = end_pulse_response(body, load, station, length, math.pi * RADIUS**2, h, 20e-6)
    values, exact, energies = run.values, run.exact, run.energies
    assert np.max(np.abs(values - exact)) < 0.02 * np.max(np.abs(exact))
    assert abs(values[-1]) < 0.02 * values.max()
    assert np.ptp(energies) < 1e-9 * max(energies)


@pytest.fixture(scope="module")
def coarse_pair():
    problem = AxiImpact(0.5, 1.0, 0.01, STEEL, "cap", math.sqrt(5e-5 / math.pi), 0.5, STEEL, "fixed")
    runs = {}
    for label, diameters in (("bar", 5.0), ("full", None)):
        options = FEMAxiOptions(elements_across=5, steps_per_contact=150, continuum_diameters=diameters)
        runs[label] = solve_fem_axi(problem, options, stations=[0.5])
    return runs


def test_far_bar_keeps_the_full_continuums_contact(coarse_pair):
    """``model`` at coarse settings: the same contact time and maxima within 0.1 %, and the
    mid-rod displacement within 0.5 % of its largest value, with far fewer rod DOFs."""
    bar, full = coarse_pair["bar"], coarse_pair["full"]
    assert bar.success and full.success
    assert bar.extra["bar_elements"] > 0 and full.extra["bar_elements"] == 0
    assert bar.extra["rod_dofs"] < 0.7 * full.extra["rod_dofs"]
    assert bar.contact_time_s == pytest.approx(full.contact_time_s, rel=1e-3)
    assert len(bar.peak_force_N) == len(full.peak_force_N) == 3
    np.testing.assert_allclose(bar.peak_force_N, full.peak_force_N, rtol=1e-3)
    u_bar = bar.extra_series["station_displacement"][0][:, 0]
    u_full = full.extra_series["station_displacement"][0][:, 0]
    n = min(len(u_bar), len(u_full))
    assert np.max(np.abs(u_bar[:n] - u_full[:n])) < 5e-3 * np.max(np.abs(u_full))
    assert abs(bar.energy_error) < 2e-4
