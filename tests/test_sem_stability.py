"""The SEM's step: the paper scheme's stability limit (derived in rodimpact.solvers.sem.stability,
verified here), its refusal of unstable steps, and the implicit scheme's automatic step."""

import math

import numpy as np
import pytest

from rodimpact.analysis.signals import sawtooth_amplitude
from rodimpact.config.load import load_global_config, load_project
from rodimpact.config.project import ConfigError
from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.solver import solve_sem
from rodimpact.solvers.sem.stability import UnstableStepError, paper_step_limit

from helpers.paper import STEEL, model_problem


def _jury_stable(h, kc, z, m):
    """Spectral radius < 1 of the linearised paper scheme (the module docstring's matrix)."""
    a, b = h * kc / z, h * h * kc / m
    matrix = np.array([[1 - a - b / 2, h], [-b / h, 1.0]])
    return np.max(np.abs(np.linalg.eigvals(matrix))) < 1.0


@pytest.mark.parametrize("z, m", [(40.0, 0.2), (2024.0, 0.5), (121.0, 1e-2)])
def test_linearised_paper_scheme_loses_stability_at_two_z_over_kc(z, m):
    """The eigenvalues of the linearised step cross -1 at h = 2 Z / k_c (when 2 Z / k_c < 2 m / Z)."""
    kc = 1.0e7
    limit = 2 * z / kc
    assert limit < 2 * m / z
    assert _jury_stable(0.99 * limit, kc, z, m)
    assert not _jury_stable(1.01 * limit, kc, z, m)


@pytest.fixture(scope="module")
def heavy_on_thin_wire():
    """0.2 kg on a semi-infinite steel wire of 1 mm^2: a long plateau of nearly constant
    approach, where a sawtooth grows or decays cleanly."""
    problem = ImpactProblem(0.2, 1.0, HertzLaw(hertz_constant(0.005, STEEL)), Rod(math.inf, 1e-6, STEEL))
    reference = solve_sem(problem, SEMOptions(steps_per_contact=320))
    return problem, reference


def test_paper_scheme_stable_just_below_its_limit_unstable_just_above(heavy_on_thin_wire):
    problem, reference = heavy_on_thin_wire
    limit = paper_step_limit(problem, approach_m=float(np.max(reference.approach)))
    late = {}
    for factor in (0.9, 1.1):
        result = solve_sem(problem, PaperSEMOptions(dt_s=factor * limit, allow_unstable=True))
        window = (result.time > 50 * limit) & (result.time < 1000 * limit)
        late[factor] = sawtooth_amplitude(result.contact_force[window])
        assert np.all(np.isfinite(result.contact_force)) and np.all(result.contact_force >= 0)
        if factor < 1:
            assert result.success and abs(result.energy_error) < 2e-3
            assert result.contact_time_s == pytest.approx(reference.contact_time_s, rel=1e-3)
        else:
            assert not result.success and result.energy_error < -0.01
            assert "energy balance off" in result.message and "unstable step" in result.message
    assert late[0.9] < 1e-5  # the start-up zig-zag has died out
    assert late[1.1] > 0.3  # the force alternates between ~0 and ~2 P


def test_limit_at_the_hertz_approach_is_safe(heavy_on_thin_wire):
    """The limit the method enforces (k_c at the rigid-rod approach) is below the sharp one."""
    problem, reference = heavy_on_thin_wire
    assert paper_step_limit(problem) < paper_step_limit(problem, float(np.max(reference.approach)))


def test_paper_scheme_refuses_an_unstable_step():
    problem = model_problem()
    limit = paper_step_limit(problem)
    with pytest.raises(UnstableStepError, match=r"stability limit 2 Z / k_c = .*allow_unstable"):
        solve_sem(problem, PaperSEMOptions(dt_s=1.01 * limit))
    assert solve_sem(problem, PaperSEMOptions(dt_s=0.2 * limit)).n_steps > 0


def test_config_refuses_an_unstable_paper_step_before_any_job(tmp_path):
    (tmp_path / "cases").mkdir()
    (tmp_path / "config.yaml").write_text(
        "cases_dir: cases\nmaterials: materials.yaml\ntargets: {sets: [thin]}\n"
        "numerics:\n  sem_paper: {steps_per_contact: 20}\n"
    )
    (tmp_path / "materials.yaml").write_text(
        "materials:\n  steel: {youngs_modulus_pa: 2.1e+11, poisson_ratio: 0.3, density_kg_m3: 7800.0}\n"
    )
    (tmp_path / "cases" / "thin.yaml").write_text(
        "cases:\n  - id: wire\n    impactor: {mass_kg: 0.2, radius_m: 0.005, velocity_m_s: 1.0, material: steel}\n"
        "    rod: {length_m: 10.0, area_m2: 1.0e-6, material: steel}\n    methods: [sem_paper]\n"
    )
    config = load_global_config(tmp_path / "config.yaml", schema_dir="workflow/schemas")
    with pytest.raises(ConfigError) as error:
        load_project(config, root=tmp_path, schema_dir="workflow/schemas")
    assert error.value.case == "wire" and error.value.field == "numerics.sem_paper.steps_per_contact"
    assert "stability limit" in error.value.reason and "thin.yaml" in str(error.value)


@pytest.mark.parametrize("tolerance", [1e-4, 1e-6])
def test_automatic_step_meets_its_tolerance(tolerance):
    """No step given: the result is within the tolerance of a converged run, and says so."""
    problem = model_problem()
    reference = solve_sem(problem, SEMOptions(steps_per_contact=32000))
    result = solve_sem(problem, SEMOptions(tolerance=tolerance))
    assert result.success and result.extra["step_choice"] == "auto"
    assert result.extra["tolerance"] == tolerance
    error = max(
        abs(result.contact_time_s / reference.contact_time_s - 1),
        abs(result.peak_force_N.max() / reference.peak_force_N.max() - 1),
    )
    assert error < tolerance
    # the step-doubling estimate is the error's size, not a gross over- or under-estimate
    assert error / 5 < result.extra["error_estimate"] < 5 * error
    assert "chosen for tolerance" in result.message


def test_automatic_step_fails_clearly_where_it_cannot_meet_the_tolerance(heavy_on_thin_wire):
    """The end of a contact that decays like exp(-t Z/m) is ill-conditioned: the first
    contact's duration does not settle to 1e-6, and the run says so instead of guessing."""
    problem, _ = heavy_on_thin_wire
    result = solve_sem(problem, SEMOptions(tolerance=1e-6, max_steps=200_000))
    assert not result.success
    assert "tolerance" in result.message or "max_steps" in result.message
