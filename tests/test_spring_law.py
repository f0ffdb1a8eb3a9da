"""The linear contact spring (rodimpact.contact.spring): its closed forms against the contact-law
interface's generic parts and against an ODE solve, and the methods on the shipped smooth case
(config/cases/smooth.yaml) against the closed form of a rod whose reflection comes after the
contact."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rodimpact.contact.law import ContactLaw
from rodimpact.contact.spring import SpringLaw, semi_infinite_rod_contact
from rodimpact.jobs.runner import run_case
from rodimpact.model.materials import Material, wave_speed

SPRING, MASS, VELOCITY = 8.0e7, 0.05, 1.0  # N/m, kg, m/s


def test_the_closed_forms_are_the_interfaces_generic_parts() -> None:
    law = SpringLaw(SPRING)
    generic = ContactLaw._rigid_impact(law, MASS, VELOCITY)  # quadrature of the energy integral
    closed = law.rigid_impact(MASS, VELOCITY)
    assert closed.contact_time_s == pytest.approx(math.pi * math.sqrt(MASS / SPRING), rel=1e-15)
    for name in ("contact_time_s", "max_approach_m", "peak_force_N"):
        assert getattr(closed, name) == pytest.approx(getattr(generic, name), rel=1e-10), name
    for a, b in [(1e-5, 1e-12), (1e-5, 1e-7), (3e-4, 1e-6), (1e-6, 0.0)]:
        alpha, iterations = law.solve_step(a, b, 0.0)
        assert alpha == pytest.approx(ContactLaw.solve_step(law, a, b, 0.5 * a)[0], rel=1e-14)
        assert alpha + b * law.force(alpha) == pytest.approx(a, rel=1e-15) and iterations == 1
    assert law.energy_between(1e-6, 3e-6) == pytest.approx(ContactLaw.energy_between(law, 1e-6, 3e-6), rel=1e-13)
    assert law.approach(law.force(2e-6)) == pytest.approx(2e-6, rel=1e-15)
    assert law.force(-1e-6) == 0.0 and law.stiffness(-1e-6) == 0.0 and float(law.energy(-1e-6)) == 0.0
    assert law.contact_radius(1e-6) is None  # no body's law: no geometry


@pytest.mark.parametrize("value", [0.0, -1.0, math.inf, math.nan])
def test_a_stiffness_that_is_not_positive_and_finite_is_refused(value: float) -> None:
    with pytest.raises(ValueError, match="c must be > 0"):
        SpringLaw(value)


def test_the_damped_oscillator_closed_form_is_the_ode_solution() -> None:
    """m alpha'' + (m c / Z) alpha' + c alpha = 0, alpha(0) = 0, alpha'(0) = v0, solved to 1e-12:
    the first return of alpha to zero and the largest c alpha."""
    impedance = 2023.6
    exact = semi_infinite_rod_contact(SPRING, MASS, VELOCITY, impedance)

    def rhs(t, y):
        return [y[1], -SPRING / MASS * y[0] - SPRING / impedance * y[1]]

    def separation(t, y):
        return y[0] if t > 0 else 1.0

    separation.terminal, separation.direction = True, -1
    dense = solve_ivp(
        rhs, (0.0, 1e-3), [0.0, VELOCITY], method="DOP853", rtol=1e-12, atol=1e-18, events=separation, dense_output=True
    )
    t_end = dense.t_events[0][0]
    assert exact.contact_time_s == pytest.approx(t_end, rel=1e-9)
    t = np.linspace(0.0, t_end, 200_001)
    force = SPRING * dense.sol(t)[0]
    assert exact.peak_force_N == pytest.approx(force.max(), rel=1e-9)
    assert exact.peak_time_s == pytest.approx(t[np.argmax(force)], abs=2 * t_end / 200_000)
    assert exact.damping_ratio == pytest.approx(math.sqrt(MASS * SPRING) / (2 * impedance), rel=1e-15)
    with pytest.raises(ValueError, match="never ends"):
        semi_infinite_rod_contact(SPRING, MASS, VELOCITY, 0.1 * impedance)  # overdamped


@pytest.fixture(scope="module")
def smooth_case(shipped_project):
    return shipped_project.cases["linear_spring"]


@pytest.fixture(scope="module")
def smooth_exact(smooth_case):
    rod = smooth_case["rod"]
    material = Material.from_mapping(rod["material"])
    impedance = material.density_kg_m3 * wave_speed(material) * rod["area_m2"]
    impactor = smooth_case["impactor"]
    return semi_infinite_rod_contact(
        smooth_case["contact"]["stiffness_n_per_m"], impactor["mass_kg"], impactor["velocity_m_s"], impedance
    )


def test_the_smooth_case_ends_its_contact_before_the_reflection_returns(smooth_case, smooth_exact) -> None:
    rod = smooth_case["rod"]
    round_trip = 2.0 * rod["length_m"] / wave_speed(Material.from_mapping(rod["material"]))
    assert smooth_exact.contact_time_s < 0.5 * round_trip  # 90.3 us against 192.7 us
    assert 0.3 < smooth_exact.damping_ratio < 0.7  # the rod takes a good part of the impact


#: Against the closed form, at the case's own numerics: sem's automatic step for 1e-6 (measured
#: 2.6e-7 on the contact time), fem1d at 2000 steps per contact (5.7e-9; its Hermite-located end).
RTOL = {"sem": 1e-6, "fem1d": 1e-6}


@pytest.mark.parametrize("method", ["sem", "fem1d"])
def test_the_methods_give_the_closed_form_on_the_smooth_case(smooth_case, smooth_exact, method) -> None:
    result = run_case(smooth_case, method)
    assert result.success, result.message
    assert result.contact_end_s[0] - result.contact_start_s[0] == pytest.approx(
        smooth_exact.contact_time_s, rel=RTOL[method]
    )
    first = result.peak_time_s <= result.contact_end_s[0]
    assert first.sum() == 1  # one force maximum in the first contact
    assert result.peak_force_N[first][0] == pytest.approx(smooth_exact.peak_force_N, rel=10 * RTOL[method])
