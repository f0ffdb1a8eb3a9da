"""Thornton's elastic-perfectly-plastic contact (rodimpact.contact.thornton), a law with memory:
its rigid impact against Thornton's closed-form restitution and against the interface's
quadrature, its curves against their definitions, and every method that carries a law's memory
(sem, sem_paper, fem1d) against the rigid impact on a nearly rigid rod, against its own energy
balance with the dissipation counted, and on a second strike that meets the dent of the first."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rodimpact.contact.hertz import HertzLaw, effective_modulus
from rodimpact.contact.law import ContactLaw, MemoryLaw, contact_energies
from rodimpact.contact.thornton import ThorntonLaw, thornton_restitution, yield_velocity
from rodimpact.model.materials import Material
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.registry import METHODS

#: A 5 mm steel sphere on steel with a limiting pressure of 1 GPa.
E_STAR, RADIUS, P_Y = 1.15e11, 0.0025, 1.0e9
MASS = 4.0 / 3.0 * math.pi * RADIUS**3 * 7800.0
#: The rigid impact's ratios V / V_y the issue names, and more.
RATIOS = [1.5, 2.0, 3.0, 5.0, 10.0, 30.0, 100.0]


@pytest.fixture(scope="module")
def law() -> ThorntonLaw:
    return ThorntonLaw(E_STAR, RADIUS, P_Y)


def _v_y(law: ThorntonLaw) -> float:
    return yield_velocity(MASS, law.k, law.yield_approach_m)


def test_the_yield_point_is_where_hertz_reaches_the_limiting_pressure(law: ThorntonLaw) -> None:
    # Hertz's peak pressure p0 = 2 E* a / (pi R) with a = sqrt(R alpha) equals p_y at alpha_y
    a_y = math.sqrt(RADIUS * law.yield_approach_m)
    assert 2.0 * E_STAR * a_y / (math.pi * RADIUS) == pytest.approx(P_Y, rel=1e-14)
    hertz = HertzLaw(law.k)
    for alpha in (0.1 * law.yield_approach_m, law.yield_approach_m):
        assert law.force(alpha) == hertz.force(alpha) and float(law.energy(alpha)) == pytest.approx(
            float(hertz.energy(alpha)), rel=1e-15
        )
    # beyond it the force grows linearly with Thornton's slope pi p_y R
    d = 3.0 * law.yield_approach_m
    assert law.force(law.yield_approach_m + d) == pytest.approx(
        law.yield_force_N + math.pi * P_Y * RADIUS * d, rel=1e-15
    )


@pytest.mark.parametrize("ratio", RATIOS)
def test_the_rigid_impact_restitution_is_thorntons_closed_form(law: ThorntonLaw, ratio: float) -> None:
    """The acceptance test: a rigid sphere on a rigid flat rebounds with Thornton's (1997) e,
    to 1e-6 relative from 1.5 to 100 times the yield velocity."""
    impact = law.rigid_impact(MASS, ratio * _v_y(law))
    assert impact.restitution == pytest.approx(thornton_restitution(1.0 / ratio), rel=1e-6)
    assert 0.0 < impact.residual_approach_m < impact.max_approach_m


@pytest.mark.parametrize("ratio", [0.3, 1.0, 1.5, 10.0, 100.0])
def test_the_closed_form_impact_is_the_interfaces_quadrature(law: ThorntonLaw, ratio: float) -> None:
    """The closed form (incomplete beta, a quarter oscillation, half a Hertz impact) against the
    generic impact of a law with memory (quadrature of loading, then of unloading on its branch)."""
    velocity = ratio * _v_y(law)
    closed = law.rigid_impact(MASS, velocity)
    generic = MemoryLaw.rigid_impact(law, MASS, velocity)
    assert closed.contact_time_s == pytest.approx(generic.contact_time_s, rel=1e-9)
    for name in ("max_approach_m", "peak_force_N", "restitution"):
        assert getattr(closed, name) == pytest.approx(getattr(generic, name), rel=1e-12), name
    assert closed.residual_approach_m == pytest.approx(generic.residual_approach_m, rel=1e-12, abs=1e-30)
    if ratio <= 1.0:  # no yield: Hertz's impact
        hertz = HertzLaw(law.k).rigid_impact(MASS, velocity)
        assert closed.restitution == 1.0 and closed.contact_time_s == pytest.approx(hertz.contact_time_s, rel=1e-14)


def test_the_restitution_falls_as_v_to_the_minus_quarter_far_past_yield() -> None:
    # Thornton's e ~ 1.185 (V_y/V)^(1/4) when V >> V_y (his eq. 28 as r -> 0)
    r = 1e-6
    limit = math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * (r / (2.0 * math.sqrt(6.0 / 5.0))) ** 0.25
    assert thornton_restitution(r) == pytest.approx(limit, rel=1e-6)
    assert thornton_restitution(1.0) == 1.0 and thornton_restitution(2.0) == 1.0


def test_the_branch_unloads_on_hertz_about_the_dent_and_reloads_on_the_virgin_curve(law: ThorntonLaw) -> None:
    peak = 8.0 * law.yield_approach_m
    branch = law.branch(peak)
    state = law.state(peak)
    residual = state.residual_approach_m
    assert branch.force(peak) == pytest.approx(law.force(peak), rel=1e-14)  # continuous at alpha_m
    assert branch.force(residual) == 0.0 and branch.force(0.5 * residual) == 0.0  # the dent carries nothing
    assert branch.force(1.5 * peak) == law.force(1.5 * peak)  # past alpha_m: the virgin curve
    # the contact radius at alpha_m is Thornton's a_m on both curves
    a_m2 = (2.0 * law.force(peak) + law.yield_force_N) / (2.0 * math.pi * P_Y)
    assert float(branch.contact_radius(peak)) ** 2 == pytest.approx(a_m2, rel=1e-13)
    assert float(law.contact_radius(peak)) ** 2 == pytest.approx(a_m2, rel=1e-13)
    # energies: the branch's is int_0^alpha P (finite differences give its force); the loading
    # work is what unloading returns plus what was dissipated
    for alpha in (0.5 * (residual + peak), 0.99 * peak, 1.2 * peak):
        h = 1e-6 * alpha
        slope = (float(branch.energy(alpha + h)) - float(branch.energy(alpha - h))) / (2.0 * h)
        assert slope == pytest.approx(branch.force(alpha), rel=1e-7)
        assert branch.approach(branch.force(alpha)) == pytest.approx(alpha, rel=1e-12)
    returned = float(law.stored_energy(peak, peak))
    assert returned + state.dissipated_energy_J == pytest.approx(float(law.energy(peak)), rel=1e-14)
    assert 0.0 < state.dissipated_energy_J < float(law.energy(peak))
    below = law.state(0.5 * law.yield_approach_m)  # below yield: elastic
    assert below.residual_approach_m == 0.0 and below.dissipated_energy_J == 0.0


@pytest.mark.parametrize("peak_factor", [0.0, 0.5, 4.0])
def test_the_branchs_step_solves_its_equation_on_every_piece(law: ThorntonLaw, peak_factor: float) -> None:
    branch = law.branch(peak_factor * law.yield_approach_m)
    for a in np.geomspace(1e-3, 30.0, 23) * law.yield_approach_m:
        for b in (1e-12, 1e-9, 1e-6):
            alpha, _ = branch.solve_step(float(a), b, 0.3 * float(a))
            generic, _ = ContactLaw.solve_step(branch, float(a), b, 0.3 * float(a))
            assert alpha + b * branch.force(alpha) == pytest.approx(a, rel=1e-13)
            assert alpha == pytest.approx(generic, rel=1e-10)


def test_contact_energies_follow_the_largest_approach(law: ThorntonLaw) -> None:
    alpha = np.array([0.0, 2.0, 6.0, 4.0, 6.0, 8.0, 1.0]) * law.yield_approach_m
    stored, dissipated = contact_energies(law, alpha)
    assert np.all(np.diff(dissipated) >= 0.0)  # dissipation never returns
    assert dissipated[2] == dissipated[3] == dissipated[4]  # unloading and reloading to alpha_m: elastic
    assert stored[4] == pytest.approx(float(law.stored_energy(alpha[2], alpha[2])), rel=1e-15)
    assert stored[-1] == pytest.approx(float(law.stored_energy(alpha[-1], alpha[5])), rel=1e-15, abs=1e-300)
    hertz = HertzLaw(law.k)  # an elastic law stores int_0^alpha P and dissipates nothing
    h_stored, h_dissipated = contact_energies(hertz, alpha)
    assert np.array_equal(h_stored, hertz.energy(alpha)) and not h_dissipated.any()


@pytest.mark.parametrize("method", ["sem", "sem_paper", "fem1d"])
def test_on_a_nearly_rigid_rod_every_method_gives_thorntons_restitution(law: ThorntonLaw, method: str) -> None:
    """A rod a thousand times stiffer and denser than steel (its impedance 1e6 times steel's):
    the run's restitution approaches the rigid impact's, and its energy balance, which counts
    the contact's dissipation, closes."""
    rod = Rod(length_m=0.3, area_m2=math.pi * 0.01**2, material=Material(2.1e14, 0.3, 7.8e6), far_end="fixed")
    for ratio in (3.0, 20.0):
        velocity = ratio * _v_y(law)
        problem = ImpactProblem(MASS, velocity, law, rod)
        driver = _driver(method)
        result = driver(problem, METHODS[method].options())
        assert result.success and result.n_contacts == 1, result.message
        rigid = law.rigid_impact(MASS, velocity)
        # the rod's compliance takes 1e-5 of the restitution; sem_paper is a first-order scheme
        assert result.restitution == pytest.approx(rigid.restitution, rel=2e-4 if method == "sem_paper" else 2e-5)
        assert result.contact_time_s == pytest.approx(rigid.contact_time_s, rel=2e-5)
        assert abs(result.energy_error) < (5e-4 if method == "sem_paper" else 1e-7)
        dissipated = law.state(float(np.max(result.approach))).dissipated_energy_J
        lost = problem.kinetic_energy_J * (1.0 - result.restitution**2)
        assert dissipated == pytest.approx(lost, rel=1e-3)  # the rod keeps almost nothing


def _driver(method: str):
    from rodimpact.solvers.fem1d.solver import solve_fem1d
    from rodimpact.solvers.sem.solver import solve_sem

    return solve_fem1d if method == "fem1d" else solve_sem


@pytest.mark.parametrize("method", ["sem", "sem_paper", "fem1d"])
def test_a_second_strike_meets_the_dent_of_the_first(aluminium: Material, method: str) -> None:
    """A 4.75 mm ball on the long thin rod of Table 2 strikes twice; with Thornton's law its
    second contact starts where the approach reaches the residual approach the first left, not
    at zero."""
    radius = 0.00475 / 2.0
    steel = Material(2.1e11, 0.3, 7800.0)
    law = ThorntonLaw(effective_modulus(steel, aluminium), radius, 1.6 * 2.76e8)
    rod = Rod(length_m=0.301, area_m2=math.pi * 0.001**2, material=aluminium, far_end="fixed")
    problem = ImpactProblem(4.0 / 3.0 * math.pi * radius**3 * 7800.0, 0.3225, law, rod)
    result = _driver(method)(problem, METHODS[method].options())
    assert result.success and result.n_contacts == 2, result.message
    first_end = np.searchsorted(result.time, result.contact_end_s[0])
    residual = law.state(float(np.max(result.approach[: first_end + 1]))).residual_approach_m
    assert residual > 0.0
    second = np.searchsorted(result.time, result.contact_start_s[1])
    # the approach at the second start is the dent's, within the approach one step moves
    step_move = abs(result.approach[second + 1] - result.approach[second - 1])
    assert abs(result.approach[second] - residual) <= step_move
    between = slice(first_end + 1, second)
    assert not result.contact_force[between].any()
    # between the contacts the approach was positive with no force: an elastic law would have
    # carried a force there
    assert np.any(result.approach[between] > 0.0)
