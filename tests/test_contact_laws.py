"""The contact-law interface: Hertz against its closed forms, the generic parts of the interface
against Hertz, and a second law, defined in this file only, run by every one-dimensional method.

The second law is a linear spring P = c alpha. On a rigid rod the impactor is a mass on a
spring for half a period: the contact lasts pi sqrt(m/c) and the force peaks at v0 sqrt(m c).
No module outside this file knows the law: if the solvers assumed P = k alpha^(3/2) anywhere,
they would miss these closed forms.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.contact.law import ContactLaw, RigidImpact, check_positive
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.fem1d.solver import solve_fem1d
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.solver import solve_sem
from rodimpact.solvers.sem.stability import paper_step_limit

from helpers.laws import LinearSpring
from helpers.paper import STEEL

MASS, VELOCITY, SPRING = 0.5, 1.0, 1.0e7  # kg, m/s, N/m
HALF_PERIOD = math.pi * math.sqrt(MASS / SPRING)
PEAK = VELOCITY * math.sqrt(MASS * SPRING)


def rigid_like_problem(law: ContactLaw) -> ImpactProblem:
    """A rod so stiff (E S / l = 4e16 N/m against the contact's 1e7) that it barely moves."""
    return ImpactProblem(MASS, VELOCITY, law, Rod(0.5, 1.0e5, STEEL))


# --------------------------------------------------------------------------- Hertz


def hertz() -> HertzLaw:
    return HertzLaw(hertz_constant(0.01, STEEL), 0.01)


def test_hertz_law_is_consistent_with_itself():
    """dP/dalpha is the stiffness, dE/dalpha is the force, approach inverts P (central
    differences, error ~ (h/alpha)^2 = 1e-12, against the closed forms)."""
    law = hertz()
    for alpha in (1e-7, 3e-6, 2e-5):
        h = 1e-6 * alpha
        assert (law.force(alpha + h) - law.force(alpha - h)) / (2 * h) == pytest.approx(law.stiffness(alpha), rel=1e-8)
        assert (float(law.energy(alpha + h)) - float(law.energy(alpha - h))) / (2 * h) == pytest.approx(
            law.force(alpha), rel=1e-8
        )
        assert law.approach(law.force(alpha)) == pytest.approx(alpha, rel=1e-13)
        assert law.contact_radius(alpha) == pytest.approx(math.sqrt(0.01 * alpha), rel=1e-14)
    assert law.force(-1e-6) == 0.0 and float(law.energy(-1e-6)) == 0.0


def test_generic_rigid_impact_reproduces_hertz_closed_form():
    """The interface's quadrature of the energy integral against Hertz's closed form."""
    law = hertz()
    closed = law.rigid_impact(MASS, VELOCITY)
    generic = ContactLaw.rigid_impact(law, MASS, VELOCITY)
    assert generic.max_approach_m == pytest.approx(closed.max_approach_m, rel=1e-12)
    assert generic.contact_time_s == pytest.approx(closed.contact_time_s, rel=1e-9)
    assert generic.peak_force_N == pytest.approx(closed.peak_force_N, rel=1e-12)


@pytest.mark.parametrize("a, b", [(1e-5, 1e-12), (1e-5, 1e-9), (3e-4, 1e-6), (1e-6, 0.0)])
def test_generic_step_solve_matches_hertz(a, b):
    law = hertz()
    exact, _ = law.solve_step(a, b, a)
    generic, iterations = ContactLaw.solve_step(law, a, b, 0.5 * a)
    assert generic == pytest.approx(exact, rel=1e-13)
    assert generic + b * law.force(generic) == pytest.approx(a, rel=1e-13)
    assert iterations < 60


# --------------------------------------------------------------------------- a second law


def test_linear_spring_rigid_impact_is_half_a_period():
    rigid = LinearSpring(SPRING).rigid_impact(MASS, VELOCITY)
    assert isinstance(rigid, RigidImpact)
    assert rigid.contact_time_s == pytest.approx(HALF_PERIOD, rel=1e-10)
    assert rigid.peak_force_N == pytest.approx(PEAK, rel=1e-10)
    assert rigid.max_approach_m == pytest.approx(PEAK / SPRING, rel=1e-10)


def test_the_step_limit_uses_the_laws_own_stiffness():
    """2 Z / k_c with k_c = dP/dalpha = c (a constant), whatever the approach."""
    problem = ImpactProblem(MASS, VELOCITY, LinearSpring(SPRING), Rod(0.5, 5e-5, STEEL))
    assert paper_step_limit(problem) == pytest.approx(2.0 * problem.rod.impedance / SPRING, rel=1e-14)


@pytest.fixture(scope="module")
def spring_runs():
    problem = rigid_like_problem(LinearSpring(SPRING))
    runs = {
        "sem": solve_sem(problem, SEMOptions(tolerance=1e-8)),
        "sem_paper": solve_sem(problem, PaperSEMOptions(steps_per_contact=20000)),
        "fem1d": solve_fem1d(problem, FEM1DOptions(steps_per_contact=2000)),
    }
    for name, result in runs.items():
        assert result.success, f"{name}: {result.message}"
    return runs


#: Relative tolerances against the closed form: twice the implicit scheme's own (automatic
#: step for 1e-8; measured 4e-9), the paper scheme's first-order error at 20000 steps per
#: contact (a few 1/20000; measured 6e-5 on the peak), and Newmark's period error at 2000
#: steps per contact, (pi/2000)^2 / 12 = 2.06e-7 (measured 2.06e-7); the rod's compliance adds
#: 2.5e-10 (c l / (E S)).
RTOL = {"sem": 2e-8, "sem_paper": 2e-4, "fem1d": 3e-7}


@pytest.mark.parametrize("method", ["sem", "sem_paper", "fem1d"])
def test_each_method_gives_the_springs_closed_form(spring_runs, method):
    result = spring_runs[method]
    assert result.n_contacts == 1
    assert result.contact_time_s == pytest.approx(HALF_PERIOD, rel=RTOL[method])
    assert result.peak_force_N.max() == pytest.approx(PEAK, rel=RTOL[method])
    assert result.rebound_velocity_m_s == pytest.approx(-VELOCITY, rel=10 * RTOL[method])
    assert abs(result.energy_error) < 10 * RTOL[method]
    assert "contact_radius" not in result.extra_series  # the law has no geometry


def test_the_methods_agree_with_each_other(spring_runs):
    sem = spring_runs["sem"]
    assert spring_runs["fem1d"].contact_time_s == pytest.approx(sem.contact_time_s, rel=1e-6)
    assert spring_runs["sem_paper"].contact_time_s == pytest.approx(sem.contact_time_s, rel=2e-4)


def test_the_stored_contact_energy_is_the_laws(spring_runs):
    """The energy series of every method is the law's own stored energy c alpha^2 / 2."""
    for result in spring_runs.values():
        alpha = np.maximum(result.approach, 0.0)
        np.testing.assert_allclose(result.extra_series["contact_energy"][0], 0.5 * SPRING * alpha**2, rtol=1e-14)


@pytest.mark.parametrize("value", [0.0, -1.0, math.inf, math.nan])
def test_check_positive_names_the_first_value_that_is_not_positive_and_finite(value):
    check_positive(mass_kg=1.0, velocity_m_s=1e-3)  # positive and finite: passes
    with pytest.raises(ValueError, match=r"^velocity_m_s must be > 0, got"):
        check_positive(mass_kg=1.0, velocity_m_s=value, c=-1.0)
