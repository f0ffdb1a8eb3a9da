"""fem_axi's end test and its step: the conserved quantities and compliances of the
separation bound (src/rodimpact/solvers/fem_axi/separation.py) checked against the normal
modes of small bodies; the bound along a long free flight; a run that stops by the bound
against the same run continued to its time horizon, with a re-contact and without; the
contact LCP's complementarity; the Newmark step through the state's images against the step
through products with M."""

import math

import numpy as np
import pytest
import scipy.linalg as la
import scipy.sparse as sp
from skfem import Basis, ElementTriP2, ElementVector

from rodimpact.solvers.fem_axi.axibody import AxiBody, dofs_of
from rodimpact.solvers.fem_axi.axisym import axis_dofs, axisym_mass, axisym_stiffness
from rodimpact.solvers.fem_axi.contact import ContactOperator
from rodimpact.solvers.fem_axi.meshes import ball_mesh, rod_mesh
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.separation import BodyBound, Flight
from rodimpact.solvers.fem_axi.solver import solve_fem_axi

from helpers.paper import ALUMINIUM, STEEL

STEP = 2e-7  # s: a few element transit times of the small bodies below, as in a run


def small_rod() -> tuple[AxiBody, sp.csr_matrix]:
    """A clamped steel rod (radius 1 mm, 4 mm long, P2) and the u_z rows of four end-face points."""
    mesh = rod_mesh(1e-3, 4e-3, 0.5e-3, 0.5e-3, coarse_size_m=1e-3)
    basis = Basis(mesh.mesh, ElementVector(ElementTriP2()))
    far = mesh.boundaries["far"]
    removed = np.union1d(axis_dofs(basis), np.union1d(dofs_of(basis, far, 0), dofs_of(basis, far, 1)))
    body = AxiBody(
        basis,
        axisym_stiffness(basis, STEEL.youngs_modulus_pa, STEEL.poisson_ratio),
        axisym_mass(basis, STEEL.density_kg_m3),
        removed,
    )
    return body, body.uz_probe_rows(np.array([[0.0, 0.2e-3, 0.5e-3, 0.9e-3], [0.0] * 4]))


def small_ball() -> tuple[AxiBody, sp.csr_matrix]:
    """A free steel ball (R = 1 mm, P2) and minus the u_z of three surface nodes near its pole."""
    mesh = ball_mesh(1e-3, 0.4e-3, 0.4e-3)
    basis = Basis(mesh.mesh, ElementVector(ElementTriP2()))
    body = AxiBody(
        basis,
        axisym_stiffness(basis, STEEL.youngs_modulus_pa, STEEL.poisson_ratio),
        axisym_mass(basis, STEEL.density_kg_m3),
        axis_dofs(basis),
    )
    surface = dofs_of(basis, mesh.boundaries["surface"], 1)
    near = surface[np.argsort(np.hypot(*basis.doflocs[:, surface]))[:3]]
    pick = sp.csr_matrix((-np.ones(3), (np.arange(3), near)), shape=(3, basis.N))
    return body, body.reduce_rows(pick)


def struck(body: AxiBody, rows: sp.csr_matrix, velocity: float = 0.0, pulse_steps: int = 40):
    """``body`` factorised for STEP, started at ``velocity``, loaded at the rows for
    ``pulse_steps`` steps (a half-sine), then one free step: its bound and its state."""
    body.factorise(STEP)
    body.start(velocity)
    GT = body.solve(np.asfortranarray(rows.T.toarray())).T
    weights = np.linspace(1.0, 0.5, rows.shape[0])
    load = rows.T @ weights
    unit = body.solve(load)
    for n in range(pulse_steps + 1):
        p = 0.05 * math.sin(math.pi * n / pulse_steps) ** 2 if n < pulse_steps else 0.0  # N per radian
        body.advance(body.predict() + p * unit, p * load)
    return BodyBound.of(body, rows, GT)


def modes(body: AxiBody) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies squared and M-orthonormal modes of the body (dense)."""
    w2, phi = la.eigh(body.K.toarray(), body.M.toarray())
    return np.maximum(w2, 0.0), phi


@pytest.mark.parametrize("make", [small_rod, small_ball])
def test_compliances_and_fast_energy_are_the_modal_sums(make):
    """c_s = sum beta^2 / w^2 and the dynamic remainder sum beta^2 mu / (w^2 (w^2 + mu)) over
    the modes without rigid motion, E_1 / mu = sum (w^2 / mu) E_j: to 1e-6 (the bound's own
    margins are 1e-6)."""
    body, rows = make()
    bound = struck(body, rows)
    w2, phi = modes(body)
    elastic = w2 > 1e-6 * w2.max()
    assert bound.free == (not elastic.all())
    beta = rows.toarray() @ phi[:, elastic]
    mu = 4.0 / STEP**2
    static = (beta**2 / w2[elastic]).sum(axis=1)
    np.testing.assert_allclose(bound.static, static, rtol=2e-6)
    np.testing.assert_allclose(
        bound.dynamic,
        (beta**2 * mu / (w2[elastic] * (w2[elastic] + mu))).sum(axis=1),
        rtol=1e-6,
        atol=2e-6 * static.max(),
    )
    alpha, rate = phi.T @ body.Mq, phi.T @ body.Mv  # modal displacements and velocities
    modal_energy = 0.5 * (rate**2 + w2 * alpha**2)
    assert bound.fast_energy(body) == pytest.approx(float((w2 / mu * modal_energy).sum()), rel=1e-7)


@pytest.mark.parametrize("make", [small_rod, small_ball])
def test_the_bound_holds_along_a_free_flight(make):
    """After the pulse, 1500 free steps: the energy, E_1 and the axial momentum are conserved
    (to 1e-9: differences of displacements carry the solves' rounding), X moves at V, and every
    candidate's closing by d stays within the reach."""
    body, rows = make()
    bound = struck(body, rows, velocity=-0.3)
    x0, v0, internal, energy = bound.motion(body)
    fast = bound.fast_energy(body)
    reach = bound.reach(internal, fast, energy)
    dense = rows.toarray()
    ones = body.uniform_axial(1.0)
    closing = []
    for n in range(1, 1501):
        body.advance(body.predict(), 0.0)
        x, v, e_int, e = bound.motion(body)
        closing.append(dense @ (body.q - x * ones))
        assert e == pytest.approx(energy, rel=1e-9)
        assert e_int == pytest.approx(internal, rel=1e-4)
        assert v == pytest.approx(v0, rel=1e-7, abs=1e-15)
        assert x == pytest.approx(x0 + n * STEP * v0, rel=1e-7, abs=1e-18)
    assert bound.fast_energy(body) == pytest.approx(fast, rel=1e-8)
    peak = np.max(np.abs(closing), axis=0)
    assert np.all(peak <= reach)


def test_the_dynamic_bound_drops_the_local_compliance():
    """On a fine mesh a node's static compliance is mostly local (one step's): the dynamic
    remainder of the rod's axis node is a small part of it."""
    body, rows = small_rod()
    bound = struck(body, rows)
    assert bound.dynamic[0] < 0.5 * bound.static[0]


def thin_rod_impact(length: float) -> AxiImpact:
    """Table 2's 4.75 mm steel ball at 0.3225 m/s on the 1 mm aluminium rod of ``length``."""
    return AxiImpact(4.40e-4, 0.3225, 2.375e-3, STEEL, "sphere", 1e-3, length, ALUMINIUM, "fixed")


COARSE = FEMAxiOptions(elements_across=4, steps_per_contact=60, max_time_factor=1.6)


def _continued_to_horizon(problem):
    """The same run with the end test switched off: it continues to its time horizon."""
    original = Flight.holds
    Flight.holds = lambda self, rod, impactor: False
    try:
        return solve_fem_axi(problem, COARSE)
    finally:
        Flight.holds = original


@pytest.fixture(scope="module")
def recontact():
    """The 301 mm rod (the ball strikes twice), stopped by the bound and continued to the horizon."""
    problem = thin_rod_impact(0.301)
    stopped = solve_fem_axi(problem, COARSE)
    continued = _continued_to_horizon(problem)
    return stopped, continued


def test_a_re_contact_is_simulated(recontact):
    """The wave's round trip (2 L / c = 118 us) brings the rod's end back onto the ball: the
    run follows it to a second contact, and stops by the bound after it."""
    stopped, _ = recontact
    assert stopped.status == "completed" and "energy bound" in stopped.message
    assert stopped.n_contacts == 2
    assert stopped.contact_start_s[1] > 2 * 0.301 / math.sqrt(ALUMINIUM.youngs_modulus_pa / ALUMINIUM.density_kg_m3)


def test_nothing_happens_after_the_bound_stops_a_run(recontact):
    """Continued to its horizon, the same run finds the same contacts and maxima (to rounding)
    and no other: the bound stopped it where nothing was left to compute."""
    stopped, continued = recontact
    assert continued.status == "truncated" and continued.n_steps > stopped.n_steps
    assert continued.n_contacts == stopped.n_contacts
    np.testing.assert_allclose(continued.contact_end_s, stopped.contact_end_s, rtol=1e-12)
    np.testing.assert_allclose(continued.peak_force_N, stopped.peak_force_N, rtol=1e-12)
    assert np.all(continued.contact_force[stopped.n_steps + 1 :] == 0.0)
    # the ball's translation in q meets the rounding of K 1 = 0: its velocity drifts by ~1e-8
    assert continued.rebound_velocity_m_s == pytest.approx(stopped.rebound_velocity_m_s, rel=1e-7)


def test_a_short_rod_stops_soon_after_the_contact():
    """On the 30 mm rod the ball rebounds once: the run ends within a few percent of the
    contact's steps after the contact, with the same contact time as a run continued to its
    horizon."""
    problem = thin_rod_impact(0.0301)
    stopped = solve_fem_axi(problem, COARSE)
    steps_in_contact = stopped.contact_end_s[-1] / stopped.dt_s
    assert stopped.n_contacts == 1 and "energy bound" in stopped.message
    assert stopped.n_steps < 1.1 * steps_in_contact + 5
    continued = _continued_to_horizon(problem)
    assert continued.n_contacts == 1 and continued.n_steps > 2 * stopped.n_steps
    assert continued.contact_time_s == pytest.approx(stopped.contact_time_s, rel=1e-12)


def test_lcp_solution_is_complementary():
    """On random positive definite operators and gaps: lambda >= 0, w = g + A lambda >= 0 and
    lambda . w = 0, to 1e-10 of the scales."""
    rng = np.random.default_rng(7)
    c = 30
    root = rng.normal(size=(c, c))
    delassus = root @ root.T / c + np.eye(c)
    operator = ContactOperator(
        sp.csr_matrix((c, 5)), sp.csr_matrix((c, 5)), np.zeros(c), np.zeros((c, 5)), np.zeros((c, 5)), delassus
    )
    for _ in range(20):
        gap = rng.normal(size=c)
        lam = operator.multipliers(gap)
        w = gap + delassus @ lam
        scale = np.abs(gap).max()
        assert lam.min() >= 0.0 and w.min() >= -1e-10 * scale
        assert abs(lam @ w) <= 1e-10 * scale * np.abs(lam).sum()


def test_step_through_the_images_equals_the_step_through_products():
    """Newmark with the loads given (M q from the equation of motion) and without (M q by a
    product): after 200 loaded steps the same displacements to 1e-11 of their largest, and
    velocities (differences of displacements over h) and momenta M v to 1e-9."""
    states = []
    for given in (True, False):
        body, rows = small_rod()
        body.factorise(STEP)
        body.start(0.0)
        load = rows.T @ np.ones(rows.shape[0])
        unit = body.solve(load)
        for n in range(200):
            p = math.sin(0.05 * n) ** 2
            body.advance(body.predict() + p * unit, p * load if given else None)
        states.append((body.q.copy(), body.v.copy(), body.Mv.copy()))
    for ours, reference, tol in zip(*states, (1e-11, 1e-9, 1e-9)):
        np.testing.assert_allclose(ours, reference, rtol=0, atol=tol * np.abs(reference).max())
