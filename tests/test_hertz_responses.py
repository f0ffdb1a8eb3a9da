"""Hertz constant, closed-form Hertz impact, and the bodies' impulse responses."""

import math

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid, quad, solve_ivp

from rodimpact.contact.hertz import HERTZ_TIME_FACTOR, effective_modulus, hertz_constant, hertz_rigid_impact
from rodimpact.model.materials import Material
from rodimpact.model.responses import (
    Rod,
    impactor_impulse_response,
    impactor_ramp_response,
    paper_rod_ramp_response,
    rod_impulse_response,
    rod_ramp_response,
    rod_step_response,
)

from helpers.paper import ALUMINIUM as ALU
from helpers.paper import STEEL, model_problem


def test_hertz_constant_one_material_is_the_papers_formula():
    r = 0.01
    paper = 2.0 * STEEL.youngs_modulus_pa * math.sqrt(r) / (3.0 * (1.0 - STEEL.poisson_ratio**2))
    assert hertz_constant(r, STEEL) == pytest.approx(paper, rel=1e-14)
    assert hertz_constant(r, STEEL, STEEL) == pytest.approx(paper, rel=1e-14)


def test_effective_modulus_two_materials():
    expected = 1.0 / ((1 - 0.3**2) / 2.1e11 + (1 - 0.34**2) / 7.342e10)
    assert effective_modulus(STEEL, ALU) == pytest.approx(expected, rel=1e-14)
    assert effective_modulus(ALU, STEEL) == pytest.approx(expected, rel=1e-14)
    # a mixed pair lies between the two one-material pairs
    assert effective_modulus(ALU) < effective_modulus(STEEL, ALU) < effective_modulus(STEEL)


def test_hertz_time_factor():
    integral, _ = quad(lambda x: 1.0 / math.sqrt(1.0 - x**2.5), 0.0, 1.0, limit=200)
    assert HERTZ_TIME_FACTOR == pytest.approx(2.0 * integral, rel=1e-9)
    assert HERTZ_TIME_FACTOR == pytest.approx(2.94328, abs=5e-6)


def test_rigid_hertz_impact_against_ode():
    m, v0, k = 0.5, 1.0, hertz_constant(0.01, STEEL)
    closed = hertz_rigid_impact(m, v0, k)
    # energy: all kinetic energy stored at maximum approach
    assert 0.4 * k * closed.max_approach_m**2.5 == pytest.approx(0.5 * m * v0**2, rel=1e-12)

    def rhs(t, y):
        return [y[1], -k * max(y[0], 0.0) ** 1.5 / m]

    def separation(t, y):
        return y[0]

    def turning(t, y):
        return y[1]

    separation.terminal, separation.direction = True, -1
    sol = solve_ivp(rhs, (0, 1.0), [0.0, v0], events=(separation, turning), rtol=1e-12, atol=1e-20, method="DOP853")
    assert sol.t_events[0][0] == pytest.approx(closed.contact_time_s, rel=1e-8)
    alpha_max = sol.y_events[1][0][0]
    assert alpha_max == pytest.approx(closed.max_approach_m, rel=1e-8)
    assert sol.t_events[1][0] == pytest.approx(0.5 * closed.contact_time_s, rel=1e-8)


def test_hertz_rejects_bad_arguments():
    with pytest.raises(ValueError, match="radius_m"):
        hertz_constant(-1.0, STEEL)
    with pytest.raises(ValueError, match="mass_kg"):
        hertz_rigid_impact(0.0, 1.0, 1e9)
    with pytest.raises(ValueError, match="poisson_ratio"):
        Material(1e9, 0.5, 1000.0)


@pytest.fixture
def rod():
    """The Model problem's rod: 0.5 m of steel, 5e-5 m^2, fixed far end."""
    return model_problem().rod


def test_ramp_response_matches_papers_printed_formulas(rod):
    """docs/paper-notes.md, "Impulse responses": the printed 'unit impulse' reactions are unit-ramp responses."""
    period = rod.reflection_period  # 2T
    t = np.linspace(0.0, 3.0 * period, 3001)[1:]
    assert rod_ramp_response(t, rod) == pytest.approx(paper_rod_ramp_response(t, rod), rel=1e-12)
    assert impactor_ramp_response(t, 0.5) == pytest.approx(t**3 / 3.0, rel=1e-14)


def test_responses_integrate_into_each_other(rod):
    t = np.linspace(0.0, 5.0 * rod.reflection_period, 200_001)
    impulse = rod_impulse_response(t, rod)
    step = cumulative_trapezoid(impulse, t, initial=0.0)
    ramp = cumulative_trapezoid(step, t, initial=0.0)
    scale = rod.reflection_period / rod.impedance
    assert np.max(np.abs(step - rod_step_response(t, rod))) < 1e-4 * scale
    assert np.max(np.abs(ramp - rod_ramp_response(t, rod))) < 1e-4 * scale * rod.reflection_period


def test_impulse_response_units_and_shape(rod):
    z, period = rod.impedance, rod.reflection_period
    t = np.array([0.25, 0.75, 1.25, 1.75, 2.25]) * period
    # fixed far end: a square wave of height 1/Z, period 4T (= 2 * 2T)
    assert rod_impulse_response(t, rod) * z == pytest.approx([1, 1, -1, -1, 1], abs=1e-12)
    free = Rod(rod.length_m, rod.area_m2, rod.material, far_end="free")
    assert rod_impulse_response(t, free) * z == pytest.approx([1, 1, 3, 3, 5], abs=1e-12)
    assert impactor_impulse_response(t, 2.0) == pytest.approx(t / 2.0, rel=1e-14)


def test_mean_step_response_is_static_compliance(rod):
    """The fixed rod's step response oscillates about l/(E S)."""
    four_t = 2.0 * rod.reflection_period
    t = np.linspace(0.0, four_t, 400_001)
    mean = np.trapezoid(rod_step_response(t, rod), t) / four_t
    assert mean == pytest.approx(rod.static_compliance, rel=1e-9)


def test_free_rod_drifts_with_rigid_body_velocity(rod):
    """Free far end: the impulse response grows on average like t / M_rod."""
    free = Rod(rod.length_m, rod.area_m2, rod.material, far_end="free")
    t = 100.5 * free.reflection_period
    assert rod_impulse_response(t, free) == pytest.approx(t / free.mass_kg, rel=1e-2)
    assert free.impedance * free.reflection_period == pytest.approx(2.0 * free.mass_kg, rel=1e-14)
