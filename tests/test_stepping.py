"""What the time-stepping solvers share (rodimpact.solvers.stepping): the energy balance of the
bodies' energies, and the result a run's histories make, with its failure on a balance that is
not finite. The solvers' own tests check the runs; these check the shared rules on histories
written by hand."""

import math

import numpy as np
import pytest

from rodimpact.solvers.stepping import NON_FINITE_ENERGY, Outcome, StepHistory, energy_error


def _history(force: list[float], ends: list[float], starts: list[float]) -> StepHistory:
    n = len(force)
    return StepHistory(
        t=[1e-6 * i for i in range(n)],
        force=force,
        x=[0.0] * n,
        w=[1.0] * (n - 1) + [-0.5],
        u_end=[0.0] * n,
        alpha=[0.0] * n,
        starts=starts,
        ends=ends,
        n_newton=7,
    )


def _result(history: StepHistory, outcome: Outcome, error: float, **more):
    return history.result(
        history.nodes(),
        outcome,
        scheme="test",
        dt_s=1e-6,
        energy_error=error,
        rod_energy_J=0.25,
        n_events=3,
        extra={"a": 1},
        extra_series={},
        **more,
    )


def test_energy_error_is_the_loss_of_the_total_over_its_start():
    impactor = np.array([1.0, 0.25, 0.5])
    contact = np.array([0.0, 0.5, 0.0])
    rod = np.array([0.0, 0.25, 0.375])
    assert energy_error(impactor, contact, rod) == pytest.approx((1.0 - 0.875) / 1.0)
    assert energy_error(impactor) == pytest.approx(0.5)
    assert math.isnan(energy_error(impactor, np.array([0.0, 0.0, np.nan])))


def test_a_run_with_a_finite_balance_keeps_its_outcome():
    history = _history([0.0, 2.0, 5.0, 1.0, 0.0, 0.0], ends=[4e-6], starts=[0.0])
    result = _result(history, Outcome("completed", "1 contact(s)", 0.5), 1e-9)
    assert result.success and result.status == "completed" and result.message == "1 contact(s)"
    assert result.energy_error == 1e-9 and result.rod_energy_J == 0.25 and result.wall_time_s == 0.5
    assert result.n_steps == 5 and result.n_newton_iterations == 7 and result.n_events == 3
    assert result.rebound_velocity_m_s == -0.5
    np.testing.assert_array_equal(result.contact_force, [0.0, 2.0, 5.0, 1.0, 0.0, 0.0])
    np.testing.assert_array_equal(result.contact_end_s, [4e-6])
    np.testing.assert_array_equal(result.contact_start_s, [0.0])
    assert len(result.peak_force_N) == 1 and result.peak_force_N[0] >= 5.0
    assert result.field == {} and result.extra == {"a": 1}


@pytest.mark.parametrize("error", [math.nan, math.inf])
def test_a_run_whose_balance_is_not_finite_fails(error):
    history = _history([0.0, 2.0, 5.0, 1.0, 0.0], ends=[4e-6], starts=[0.0])
    result = _result(history, Outcome("completed", "1 contact(s)", 0.5), error)
    assert not result.success and result.status == "failed" and result.message == NON_FINITE_ENERGY


def test_a_failed_run_keeps_its_own_reason():
    history = _history([0.0, 2.0, 5.0], ends=[], starts=[0.0])
    result = _result(history, Outcome("failed", "time horizon reached", 0.5), math.nan)
    assert result.status == "failed" and result.message == "time horizon reached"


def test_only_complete_contacts_are_reported_and_small_maxima_can_be_dropped():
    """A contact still open at the end has no interval; a maximum below the prominence is dropped."""
    force = [0.0, 4.0, 10.0, 4.0, 0.0, 0.0, 3.0, 3.1, 3.0]
    history = _history(force, ends=[4e-6], starts=[0.0, 5e-6])
    every = _result(history, Outcome("truncated", "limit", 0.5), 0.0)
    np.testing.assert_array_equal(every.contact_start_s, [0.0])
    assert len(every.peak_force_N) == 2
    prominent = _result(history, Outcome("truncated", "limit", 0.5), 0.0, min_prominence=0.5)
    assert len(prominent.peak_force_N) == 1 and prominent.peak_force_N[0] >= 10.0
