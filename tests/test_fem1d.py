"""fem1d against the SEM (same physics, independent discretisation) and against mathematics:
observed orders in element size and time step, energy, d'Alembert's wave field."""

import numpy as np
import pytest

from rodimpact.jobs.runner import run_case
from rodimpact.solvers.fem1d.bar import bar_model, row_blocks
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.fem1d.solver import solve_fem1d
from rodimpact.solvers.sem.history import ForceHistory
from rodimpact.solvers.sem.options import SEMOptions
from rodimpact.solvers.sem.solver import solve_sem

from helpers.paper import model_problem, two_contact_problem


def fem(problem, **options):
    result = solve_fem1d(problem, FEM1DOptions(**options))
    assert result.success, result.message
    return result


def order(steps, errors):
    return np.polyfit(np.log(1.0 / np.asarray(steps, float)), np.log(errors), 1)[0]


def errors(result, ref):
    """Relative errors of the largest force maximum and of the rebound velocity."""
    return (
        abs(result.peak_force_N.max() / ref.peak_force_N.max() - 1),
        abs(result.rebound_velocity_m_s / ref.rebound_velocity_m_s - 1),
    )


@pytest.fixture(scope="module")
def shipped_model(shipped_project):
    case = shipped_project.cases["model"]
    return run_case(case, "fem1d"), run_case(case, "sem")


def test_fem1d_agrees_with_sem_at_the_shipped_setting(shipped_model):
    """Issue 3: 1e-3 on contact time and every maximum (measured: about 1e-5)."""
    fem1d, sem = shipped_model
    assert fem1d.n_contacts == sem.n_contacts == 1
    assert fem1d.contact_time_s == pytest.approx(sem.contact_time_s, rel=1e-4)
    assert len(fem1d.peak_force_N) == len(sem.peak_force_N) == 3
    np.testing.assert_allclose(fem1d.peak_force_N, sem.peak_force_N, rtol=1e-4)
    np.testing.assert_allclose(fem1d.peak_time_s, sem.peak_time_s, rtol=1e-3)
    assert fem1d.rebound_velocity_m_s == pytest.approx(sem.rebound_velocity_m_s, rel=1e-4)


def test_midrod_displacement_is_dalembert_of_the_sem_force(shipped_model):
    """The FEM wave field at x = l/2 against the exact 1D solution driven by the SEM's force."""
    fem1d, sem = shipped_model
    history = ForceHistory(model_problem().rod, linear=True)
    for t, p in zip(sem.time[1:], sem.contact_force[1:]):
        history.append(float(t), float(p))
    x = fem1d.extra["station_x_m"][0]
    assert x == pytest.approx(0.25)
    inside = fem1d.time <= sem.time[-1]
    exact = history.displacement_at(x, fem1d.time[inside])
    computed = fem1d.extra_series["station_displacement"][0][inside, 0]
    assert np.max(np.abs(computed - exact)) < 1e-3 * np.max(np.abs(exact))
    # nothing moves at mid-rod before the wave arrives at l / (2a)
    arrival = x / model_problem().rod.wave_speed
    early = fem1d.time < 0.9 * arrival
    assert np.max(np.abs(fem1d.extra_series["station_displacement"][0][early, 0])) < 1e-3 * np.max(exact)


def test_second_order_in_time():
    """Coarse P1 mesh (all its modes resolved in time): order 2 in the step."""
    problem = model_problem()
    ref = fem(problem, element="P1", elements=20, steps_per_contact=3200)
    steps = [100, 200, 400, 800]
    errs = np.array([errors(fem(problem, element="P1", elements=20, steps_per_contact=n), ref) for n in steps])
    for column in errs.T:
        assert 1.7 < order(steps, column) < 2.5


def test_second_order_in_element_size_for_p1():
    problem = model_problem()
    ref = fem(problem, element="P1", elements=640, steps_per_contact=400)
    sizes = [20, 40, 80, 160]
    errs = np.array([errors(fem(problem, element="P1", elements=n, steps_per_contact=400), ref) for n in sizes])
    for column in errs.T:
        assert 1.7 < order(sizes, column) < 2.5


def test_energy_is_conserved_up_to_the_contact_quadrature():
    problem = model_problem()
    steps = [200, 400, 800]
    errs = [abs(fem(problem, element="P1", elements=20, steps_per_contact=n).energy_error) for n in steps]
    assert 1.8 < order(steps, errs) < 2.2
    assert errs[-1] < 1e-5


def test_second_contact_matches_the_sem():
    """Steel ball of 0.71 g on the thin 301 mm aluminium rod strikes twice."""
    problem = two_contact_problem()
    sem = solve_sem(problem, SEMOptions(steps_per_contact=2000))
    result = fem(problem)
    assert result.n_contacts == sem.n_contacts == 2
    np.testing.assert_allclose(result.contact_start_s, sem.contact_start_s, rtol=1e-4, atol=1e-9)
    np.testing.assert_allclose(result.contact_end_s, sem.contact_end_s, rtol=1e-4)


def test_free_far_end():
    problem = model_problem("free")
    sem = solve_sem(problem, SEMOptions(steps_per_contact=2000))
    result = fem(problem, element="P2", elements=60)
    assert result.contact_time_s == pytest.approx(sem.contact_time_s, rel=1e-4)
    assert result.rebound_velocity_m_s == pytest.approx(sem.rebound_velocity_m_s, rel=1e-3)


def test_too_coarse_settings_are_refused_with_the_value_needed(caplog):
    problem = model_problem()
    with pytest.raises(ValueError, match=r"elements=1\b.*needs elements >= \d+"):
        solve_fem1d(problem, FEM1DOptions(element="P1", elements=1))
    t_contact = problem.rigid_contact.contact_time_s
    with pytest.raises(ValueError, match=r"dt_s=.* needs dt_s <= .*steps_per_contact >= 20"):
        solve_fem1d(problem, FEM1DOptions(dt_s=t_contact / 10))
    with pytest.raises(ValueError, match=r"^steps_per_contact must be >= 20, got 10$"):
        FEM1DOptions(steps_per_contact=10)
    with caplog.at_level("WARNING"):
        result = solve_fem1d(problem, FEM1DOptions(element="P1", elements=3, steps_per_contact=100))
    assert "elements=3 gives only" in caplog.text and "recommended" in result.extra["warnings"]


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("far_end", ["fixed", "free"])
def test_banded_solver_is_the_sparse_solve(element, far_end):
    """The banded Cholesky solve (reverse Cuthill-McKee order) equals a direct sparse solve."""
    from scipy.sparse.linalg import spsolve

    from rodimpact.solvers.fem1d.bar import banded_solver

    rod = model_problem(far_end).rod
    bar = bar_model(rod, element, 40)
    matrix = (bar.stiffness + 1e12 * bar.mass).tocsc()
    rhs = np.random.default_rng(0).normal(size=matrix.shape[0])
    np.testing.assert_allclose(banded_solver(matrix)(rhs), spsolve(matrix, rhs), rtol=1e-10, atol=0)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_row_blocks_give_each_product_to_the_last_bit(element):
    """A step's products taken as one stacked product (row_blocks) are each block's own product,
    bit for bit (the same sum in the same order per row), on vectors of very different scales;
    an absent block has no rows."""
    rod = model_problem().rod
    length = rod.length_m
    bar = bar_model(
        rod, element, 60, stations_m=(0.0, 0.3 * length, length), gauges_m=((0.5 * length, 0.01),), far_end=True
    )
    rng = np.random.default_rng(7)
    blocks = (bar.station_probes, bar.strain_probes, bar.gauge_probes, None, bar.stiffness)
    stacked, rows = row_blocks(*blocks)
    assert rows[3] is None and stacked.shape[0] == sum(b.shape[0] for b in blocks if b is not None)
    of_v, (at_m, at_far) = row_blocks(bar.mass, bar.far_probe)
    for scale in (1e-15, 1e-6, 1.0, 1e6):
        u = scale * rng.standard_normal(bar.stiffness.shape[0])
        together = stacked @ u
        for block, at in zip(blocks, rows):
            if block is not None:
                assert np.array_equal(together[at], block @ u)
        assert np.array_equal((of_v @ u)[at_m], bar.mass @ u)
        assert np.array_equal((of_v @ u)[at_far], bar.far_probe @ u)
