"""Verification of the SEM solver against mathematics: closed-form limits, an ODE,
observed orders of convergence and the energy balance."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rodimpact.analysis.signals import local_maxima, peak_prominences
from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.solver import solve_sem

from helpers.paper import STEEL, model_problem, two_contact_problem


def solve(problem, n, scheme="implicit", **kw):
    options = (SEMOptions if scheme == "implicit" else PaperSEMOptions)(steps_per_contact=n, **kw)
    result = solve_sem(problem, options)
    assert result.success, result.message
    return result


def observed_order(steps, errors):
    slope, _ = np.polyfit(np.log(1.0 / np.asarray(steps, float)), np.log(errors), 1)
    return slope


def test_rigid_rod_limit_is_the_closed_form_hertz_impact():
    """A rod of enormous impedance does not move: the impact is Hertz's on a rigid wall."""
    problem = ImpactProblem(0.5, 1.0, HertzLaw(hertz_constant(0.01, STEEL)), Rod(0.5, 1.0e5, STEEL))
    closed = problem.rigid_contact
    result = solve(problem, 2000)
    assert result.n_contacts == 1
    assert result.contact_time_s == pytest.approx(closed.contact_time_s, rel=1e-6)
    assert result.contact_time_s == pytest.approx(2.94328 * closed.max_approach_m, rel=2e-6)
    assert len(result.peak_force_N) == 1
    assert result.peak_force_N[0] == pytest.approx(closed.peak_force_N, rel=1e-6)
    assert result.peak_time_s[0] == pytest.approx(0.5 * closed.contact_time_s, rel=1e-4)
    assert result.rebound_velocity_m_s == pytest.approx(-1.0, rel=1e-6)


def test_semi_infinite_rod_matches_the_equivalent_ode():
    """No reflection within the contact: u' = P/Z, m x'' = -P, P = k (x - u)^(3/2)."""
    rod = Rod(math.inf, 1e-6, STEEL)  # a thin wire: the rod's compliance dominates
    problem = ImpactProblem(0.01, 1.0, HertzLaw(hertz_constant(0.005, STEEL)), rod)
    m, k, z = problem.mass_kg, problem.contact.k, rod.impedance

    def rhs(t, y):
        p = k * max(y[0] - y[2], 0.0) ** 1.5
        return [y[1], -p / m, p / z]

    def separation(t, y):
        return y[0] - y[2] if t > 0 else 1.0

    separation.terminal, separation.direction = True, -1
    ode = solve_ivp(
        rhs, (0, 1.0), [0.0, 1.0, 0.0], events=separation, rtol=1e-12, atol=1e-22, method="DOP853", dense_output=True
    )
    t_end = ode.t_events[0][0]

    result = solve(problem, 1000)
    assert result.n_contacts == 1
    assert result.contact_time_s == pytest.approx(t_end, rel=1e-7)
    assert result.rebound_velocity_m_s == pytest.approx(ode.y_events[0][0][1], rel=1e-6)
    y = ode.sol(result.time[result.time < t_end])
    force_ode = k * np.maximum(y[0] - y[2], 0.0) ** 1.5
    force = result.contact_force[: len(force_ode)]
    assert np.max(np.abs(force - force_ode)) < 2e-5 * np.max(force_ode)
    # the rod matters here: the contact lasts far longer than on a rigid wall
    assert t_end > 3 * problem.rigid_contact.contact_time_s


@pytest.fixture(scope="module")
def reference():
    return solve(model_problem(), 16000)


def test_model_case_has_three_maxima(reference):
    """Fig. 2 of the paper: one contact, three force maxima."""
    assert reference.n_contacts == 1
    assert len(reference.peak_force_N) == 3
    assert reference.status == "completed"


def _errors(results, reference):
    tc = [abs(r.contact_time_s - reference.contact_time_s) / reference.contact_time_s for r in results]
    peaks = [np.max(np.abs(r.peak_force_N - reference.peak_force_N) / reference.peak_force_N) for r in results]
    return np.array(tc), np.array(peaks)


def test_implicit_scheme_is_second_order(reference):
    steps = [250, 500, 1000, 2000]
    tc, peaks = _errors([solve(model_problem(), n) for n in steps], reference)
    assert 1.8 < observed_order(steps, tc) < 2.4
    assert 1.8 < observed_order(steps, peaks) < 2.4
    assert tc[-1] < 1e-7 and peaks[-1] < 1e-6


def test_paper_scheme_is_first_order(reference):
    steps = [1000, 2000, 4000, 8000]
    results = [solve(model_problem(), n, scheme="paper") for n in steps]
    tc, peaks = _errors(results, reference)
    assert 0.8 < observed_order(steps, tc) < 1.2
    assert 0.8 < observed_order(steps, peaks) < 1.2
    energy = [abs(r.energy_error) for r in results]
    assert 0.8 < observed_order(steps, energy) < 1.2


def test_energy_balance_converges(reference):
    """KE in = KE out + work done on the rod; the discrete balance closes at O(h^2)."""
    steps = [250, 500, 1000, 2000]
    errors = [abs(solve(model_problem(), n).energy_error) for n in steps]
    assert 1.8 < observed_order(steps, errors) < 2.2
    assert abs(reference.energy_error) < 1e-8
    assert reference.rod_energy_J == pytest.approx(0.5 * 0.5 * (1 - reference.rebound_velocity_m_s**2), rel=1e-7)


def test_contact_end_is_located_between_steps(reference):
    """A coarse step does not round the contact time to the grid."""
    coarse = solve(model_problem(), 100)
    assert coarse.dt_s > 1e-3 * reference.contact_time_s
    assert abs(coarse.contact_time_s - reference.contact_time_s) < 1e-2 * coarse.dt_s
    # the separation is a node of its own, off the uniform grid
    assert (coarse.contact_end_s[0] / coarse.dt_s) % 1.0 > 1e-6
    end = np.searchsorted(coarse.time, coarse.contact_end_s[0])
    assert coarse.time[end] == coarse.contact_end_s[0]
    assert coarse.contact_force[end] == 0.0 and coarse.contact_force[end - 1] > 0.0


def test_implicit_scheme_stable_where_the_papers_scheme_is_not():
    """A thin wire (small impedance Z, stiff contact k_c = dP/dalpha): the lagged force is
    unstable for steps beyond about 2 Z / k_c (docs/paper-notes.md, "The paper's scheme"); the
    implicit scheme is not."""
    problem = ImpactProblem(0.01, 1.0, HertzLaw(hertz_constant(0.005, STEEL)), Rod(1.0, 1e-6, STEEL))
    fine = solve(problem, 1000)
    alpha_peak = (fine.peak_force_N.max() / problem.contact.k) ** (2.0 / 3.0)
    contact_stiffness = 1.5 * problem.contact.k * math.sqrt(alpha_peak)
    dt = 4.0 * problem.rod.impedance / contact_stiffness
    implicit = solve_sem(problem, SEMOptions(dt_s=dt))
    assert implicit.success and implicit.n_contacts == fine.n_contacts
    assert abs(implicit.contact_time_s / fine.contact_time_s - 1) < 1e-2
    assert np.all(implicit.contact_force >= 0) and np.all(np.isfinite(implicit.contact_force))
    assert abs(implicit.energy_error) < 1e-2
    paper = solve_sem(problem, PaperSEMOptions(dt_s=dt, allow_unstable=True))
    assert paper.energy_error < -1.0  # the explicit scheme creates energy...
    assert paper.contact_force.max() > 10 * fine.contact_force.max()
    assert not paper.success and "unstable" in paper.message  # ...and says so


def test_second_contact_is_detected_and_resolution_independent():
    """Steel ball of 0.71 g on a thin aluminium rod 301 mm long: the ball strikes twice."""
    problem = two_contact_problem()
    results = [solve(problem, n) for n in (1000, 4000)]
    for r in results:
        assert r.n_contacts == 2
        assert np.all(np.diff(np.ravel(np.column_stack([r.contact_start_s, r.contact_end_s]))) > 0)
        gap = (r.time > r.contact_end_s[0]) & (r.time < r.contact_start_s[1])
        assert np.all(r.contact_force[gap] == 0.0) and np.all(r.approach[gap] <= 1e-15)
    assert results[0].contact_start_s[1] == pytest.approx(results[1].contact_start_s[1], rel=1e-5)


def test_free_far_end_rod_carries_the_momentum():
    problem = model_problem("free")
    result = solve(problem, 2000)
    rod_mass = problem.rod.mass_kg
    # momentum: the impulse given to the rod equals the impactor's loss
    impulse = problem.mass_kg * (1.0 - result.rebound_velocity_m_s)
    assert abs(result.energy_error) < 1e-6
    assert impulse > 0 and impulse / rod_mass > result.rebound_velocity_m_s


def test_local_maxima_refines_a_parabola_exactly():
    t = np.array([0.0, 0.9, 2.1, 3.0, 4.4])
    p = 5.0 - (t - 1.7) ** 2
    peak_t, peak_p = local_maxima(t, p)
    assert peak_t == pytest.approx([1.7], rel=1e-12)
    assert peak_p == pytest.approx([5.0], rel=1e-12)


def test_peak_prominences_are_scipys_and_filter_the_ripples():
    from scipy.signal import peak_prominences as scipy_prominences

    rng = np.random.default_rng(3)
    for _ in range(20):
        x = np.cumsum(rng.standard_normal(500))
        peaks = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
        assert np.array_equal(peak_prominences(x, peaks), scipy_prominences(x, peaks)[0])
    # a ripple of height 0.01 on a hump of height 1: only the hump stands out at prominence 0.1
    t = np.linspace(0.0, 1.0, 2001)
    p = np.sin(np.pi * t) + 0.01 * np.sin(60 * np.pi * t)
    assert len(local_maxima(t, p)[0]) > 10
    assert len(local_maxima(t, p, min_prominence=0.1)[0]) == 1


def test_options_are_validated():
    with pytest.raises(ValueError, match="steps_per_contact must be given"):
        PaperSEMOptions(steps_per_contact=None)
    with pytest.raises(ValueError, match="dt_s"):
        SEMOptions(dt_s=-1e-6)
    with pytest.raises(ValueError, match="steps_per_contact"):
        SEMOptions(steps_per_contact=3)


def test_automatic_step_judges_whole_runs_when_the_first_contact_end_is_ill_conditioned(shipped_project) -> None:
    """A 10 g impactor on a rod of impedance 1 kg/s (the stability map's corner): two contacts, the
    first ending in a near-grazing separation whose time does not converge at order 2. The
    automatic step then compares whole runs, and its result agrees with a run at half its step
    within the tolerance."""
    from rodimpact.analysis.studies import map_point_case

    config = shipped_project.config
    spec = config["stability"]["map"]
    case = map_point_case(shipped_project.cases[spec["base_case"]], spec, "m2_z0", "reference", config["numerics"])
    problem = ImpactProblem.from_case(case)
    assert (problem.mass_kg, problem.rod.impedance) == pytest.approx((1e-2, 1.0))
    options = SEMOptions(tolerance=1e-5, max_steps=400_000)
    auto = solve_sem(problem, options)
    assert auto.success, auto.message
    assert "whole-run" in auto.extra["error_estimate_basis"]
    assert auto.extra["error_estimate"] <= 1e-5
    half = solve_sem(problem, SEMOptions(dt_s=0.5 * auto.dt_s, max_steps=400_000))
    assert auto.contact_time_s == pytest.approx(half.contact_time_s, rel=1e-5)
