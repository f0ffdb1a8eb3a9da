"""The SEM's constant-cost rod sum on a step commensurate with the wave round trip:
the recursion W(t) = Q(t) + s W(t - 2T) against the direct sum, the implicit step's inline
sum and history against the force history's own, and what the automatic step's check costs."""

import math
import time

import numpy as np
import pytest

from rodimpact.model.responses import Rod
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.sem.grid import CommensurateGrid, commensurate_step
from rodimpact.solvers.sem.history import ForceHistory
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.solver import solve_sem
from rodimpact.solvers.sem.stepper import SEMRun

from helpers.paper import STEEL, model_problem, two_contact_problem


def _direct_terms(history: ForceHistory, h: float) -> tuple[float, float]:
    """sum_j c_j Q(t_new - 2jT) term by term, the new force's part separated (reference)."""
    t_n, p_n, q_n = history.t[-1], history.P[-1], history.Q[-1]
    t_new = t_n + h
    known = coef = 0.0
    j = 0
    while t_new - j * history.period > 0.0:
        tau = t_new - j * history.period
        c = 1.0 if j == 0 else 2.0 * history.sign**j
        if tau > t_n:
            d = tau - t_n
            if history.linear:
                known += c * (q_n + d * p_n - 0.5 * d * d * p_n / h)
                coef += c * 0.5 * d * d / h
            else:
                known += c * (q_n + d * p_n)
        else:
            known += c * history.impulse(tau)
        j += 1
    return known / history.impedance, coef / history.impedance


@pytest.mark.parametrize("far_end", ["fixed", "free"])
@pytest.mark.parametrize("linear", [True, False])
@pytest.mark.parametrize("ratio", [7, 1, 1 / 3])  # 2T = 7 h, 2T = h, h = 3 (2T)
def test_grid_sum_is_the_direct_sum_over_every_reflection(far_end, linear, ratio):
    """Over at least 60 round trips and 200 steps of a random force, with event nodes off
    the grid, the O(1) grid terms equal the direct sum of every reflection to rounding."""
    rod = Rod(0.01, 5.0e-5, STEEL, far_end=far_end)
    period = rod.reflection_period
    h = period / ratio
    grid = CommensurateGrid.of(h, period, rod.reflection_sign, linear)
    assert grid is not None
    history = ForceHistory(rod, linear, grid)
    rng = np.random.default_rng(3)
    checked = 0
    while history.t[-1] < max(60 * period, 200 * h):
        if history.on_grid and len(history.W) % 37 == 5:  # an event node inside the next step
            t_event = history.t[-1] + 0.3 * h
            known, coef = history.rod_step_terms(0.3 * h)
            p = float(rng.uniform(0, 1e3))
            history.append(t_event, p, known + coef * p)
        step, t_new = history.next_step(h)
        on_grid = history.on_grid
        known, coef = history.rod_step_terms(step)
        ref_known, ref_coef = _direct_terms(history, step)
        assert known == pytest.approx(ref_known, rel=1e-11, abs=1e-11 * abs(ref_coef) * 1e3)
        assert coef == pytest.approx(ref_coef, rel=1e-12, abs=1e-30)
        checked += on_grid
        p = float(rng.uniform(0, 1e3))
        history.append(t_new, p, known + coef * p)
    assert checked >= 190


def test_commensurate_step_divides_or_spans_whole_round_trips():
    period = 2.0e-6
    for guess in (3.3e-8, 1.9e-6, 2.0e-6, 2.1e-6, 7.3e-6):
        step = commensurate_step(guess, period)
        assert step <= guess * (1 + 1e-12)
        assert CommensurateGrid.of(step, period, -1, True) is not None
    assert commensurate_step(7.3e-6, period) == pytest.approx(6.0e-6, rel=1e-14)
    assert commensurate_step(3.3e-8, period) == pytest.approx(period / 61, rel=1e-14)
    assert commensurate_step(1e-6, math.inf) == 1e-6
    assert CommensurateGrid.of(0.37e-6, period, -1, True) is None


#: A grid step (commensurate) and a step on no grid (just off it), in contact times on a rigid rod.
_STEPS = {"grid": 1.0, "no_grid": 1.0 + 1e-7}


def _run(problem, where: str) -> tuple[SEMRun, ImpactResult]:
    """An implicit run at about 3000 steps a contact, and its result."""
    h = commensurate_step(problem.rigid_contact.contact_time_s / 3000, problem.rod.reflection_period) * _STEPS[where]
    run = SEMRun(problem, SEMOptions(dt_s=h), h)
    return run, run.finish((), time.perf_counter(), {})


@pytest.mark.parametrize("where", list(_STEPS))
@pytest.mark.parametrize(
    "problem",
    [model_problem(), two_contact_problem(), model_problem("free")],
    ids=["model", "two_contacts", "free_end"],
)
def test_the_step_sums_and_records_as_the_force_history_does(problem, where):
    """The implicit step sums the rod on the grid and appends its nodes inline (for speed):
    the run's nodes replayed through ForceHistory.rod_step_terms and append give its rod end
    displacement at every node that is not an event, and its impulse and W, to the last bit."""
    st = _run(problem, where)[0].st
    assert (st.hist.grid is not None) == (where == "grid")
    assert len(st.ends) >= 1 and st.n_events >= 1
    replay = ForceHistory(problem.rod, linear=True, grid=st.hist.grid)
    checked = 0
    for t, p, u in zip(st.t[1:], st.force[1:], st.u_end[1:]):
        step, t_next = replay.next_step(st.h)
        if t == t_next:  # not an event inside the step
            known, coef = replay.rod_step_terms(step)
            assert known + coef * p == u
            checked += 1
        replay.append(t, p, u)
    assert checked == len(st.t) - 1 - st.n_events
    assert replay.t == st.hist.t and replay.Q == st.hist.Q and replay.W == st.hist.W


@pytest.mark.parametrize("where", list(_STEPS))
@pytest.mark.parametrize(
    "problem",
    [model_problem(), two_contact_problem(), model_problem("free")],
    ids=["model", "two_contacts", "free_end"],
)
def test_returning_after_every_node_changes_no_bit(problem, where):
    """The implicit step goes on from node to node inside a contact, carrying the last node in
    local variables; returned to the driver after every node (its time limit already reached),
    it gives the same run to the last bit: contacts, events, Newton iterations and histories."""
    whole, result = _run(problem, where)
    h = whole.st.h
    run = SEMRun(problem, SEMOptions(dt_s=h), h)
    stepper_step = type(run.st).step
    run.st.step = lambda t_max, force_bound, max_nodes: stepper_step(run.st, -math.inf, force_bound, max_nodes)
    by_node = run.finish((), time.perf_counter(), {})
    assert by_node.n_contacts == result.n_contacts >= 1
    assert (by_node.n_events, by_node.n_newton_iterations) == (result.n_events, result.n_newton_iterations)
    for name in ("time", "contact_force", "approach", "impactor_velocity", "rod_end_displacement", "contact_end_s"):
        assert np.array_equal(getattr(by_node, name), getattr(result, name)), name


def test_grid_and_general_sums_agree_on_a_whole_run():
    """A step just off the commensurate one runs the general sum; the same case on the
    grid agrees with it to the scheme's own step sensitivity."""
    problem = model_problem()
    h = commensurate_step(problem.rigid_contact.contact_time_s / 4000, problem.rod.reflection_period)
    on_grid = solve_sem(problem, SEMOptions(dt_s=h))
    off_grid = solve_sem(problem, SEMOptions(dt_s=h * (1 + 1e-7)))
    assert off_grid.contact_time_s == pytest.approx(on_grid.contact_time_s, rel=1e-9)
    np.testing.assert_allclose(off_grid.peak_force_N, on_grid.peak_force_N, rtol=1e-9)


@pytest.mark.parametrize("problem", [model_problem(), two_contact_problem()], ids=["model", "two_contacts"])
def test_automatic_step_checks_on_first_contacts_only(problem):
    """The automatic step's check runs stop at their first contact's end: they cost fewer
    steps than the run kept, whose step is commensurate with the round trip."""
    auto = solve_sem(problem, SEMOptions(tolerance=1e-6))
    assert auto.success, auto.message
    assert auto.extra["error_estimate"] <= 1e-6
    assert auto.extra["n_steps_error_check"] <= auto.n_steps
    assert CommensurateGrid.of(auto.dt_s, problem.rod.reflection_period, -1, True) is not None
    fixed = solve_sem(problem, SEMOptions(dt_s=auto.dt_s))
    assert np.array_equal(fixed.contact_force, auto.contact_force)


def test_paper_scheme_on_a_commensurate_step_is_its_direct_sum():
    """The paper scheme (force held) on the grid equals the same scheme with the direct sum."""
    problem = model_problem()
    h = commensurate_step(problem.rigid_contact.contact_time_s / 20000, problem.rod.reflection_period)
    on_grid = solve_sem(problem, PaperSEMOptions(dt_s=h))
    off_grid = solve_sem(problem, PaperSEMOptions(dt_s=h * (1 + 1e-9)))
    assert on_grid.contact_time_s == pytest.approx(off_grid.contact_time_s, rel=1e-7)
    np.testing.assert_allclose(on_grid.peak_force_N, off_grid.peak_force_N, rtol=1e-7)
