"""The continuum's dynamic run where a material yields: J2 in the plastic regions, the plastic load
iterated with the elastic Newmark factorisation; checked against the elastic run, by its energy
balance with the dissipation counted, and against the SEM with the continuum's law with memory."""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
import pytest

from rodimpact.contact.tabulated import TabulatedLaw, TabulatedMemoryLaw
from rodimpact.jobs.indentation import indentation_curve
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import solve_fem_axi
from rodimpact.solvers.registry import METHODS
from rodimpact.solvers.sem.solver import solve_sem

#: A coarse continuum: 4 elements across the contact, 60 steps per Hertz time, a horizon of 1.5
#: estimated contact times (a yielding run has no proof of its end: it runs to its horizon).
SETTINGS = {
    "elements_across": 4,
    "steps_per_contact": 60,
    "contact_extent": 2.5,
    "plastic_extent": 4.0,
    "max_time_factor": 1.5,
}


@pytest.fixture(scope="module")
def yielding_case(shipped_project):
    """The heaviest Table 2 ball on the 10 mm, 30.1 mm rod, ball and rod of their yielding
    variants' yield stresses (2.03 GPa, 276 MPa)."""
    case = copy.deepcopy(shipped_project.cases["ball_12.73mm-r10_l30"])
    case["impactor"]["material"]["yield_stress_pa"] = 2.03e9
    case["rod"]["material"]["yield_stress_pa"] = 2.76e8
    return case


@pytest.fixture(scope="module")
def dynamic(yielding_case):
    problem = dataclasses.replace(AxiImpact.from_case(yielding_case), body="cap")
    return problem, solve_fem_axi(problem, FEMAxiOptions.from_settings(SETTINGS))


def test_a_yield_stress_never_reached_steps_as_the_elastic_run(yielding_case) -> None:
    """With yield stresses far above the stresses, the run with plastic regions (the iteration on
    the plastic load) gives the elastic run's force history to 1e-9 of its largest force."""
    problem = dataclasses.replace(AxiImpact.from_case(yielding_case), body="cap")
    strong = dataclasses.replace(
        problem,
        rod_material=dataclasses.replace(problem.rod_material, yield_stress_pa=1e15),
        impactor_material=dataclasses.replace(problem.impactor_material, yield_stress_pa=1e15),
    )
    elastic = dataclasses.replace(
        problem,
        rod_material=dataclasses.replace(problem.rod_material, yield_stress_pa=None),
        impactor_material=dataclasses.replace(problem.impactor_material, yield_stress_pa=None),
    )
    options = FEMAxiOptions.from_settings(SETTINGS)
    plastic_run, elastic_run = solve_fem_axi(strong, options), solve_fem_axi(elastic, options)
    n = min(len(plastic_run.time), len(elastic_run.time))
    assert n > 50
    scale = float(np.max(elastic_run.contact_force))
    np.testing.assert_allclose(plastic_run.contact_force[:n], elastic_run.contact_force[:n], rtol=0, atol=1e-9 * scale)
    assert plastic_run.summary()["dissipated_energy_J"] == 0.0


def test_a_yielding_run_dissipates_and_its_energy_balance_closes(dynamic) -> None:
    """Past yield the run dissipates (its plastic work), leaves a dent, and its energy balance,
    with the stored energy of the elastic strain only and the plastic work counted, closes to
    1e-3 (measured 3.4e-5 at 5 elements across and 100 steps)."""
    problem, run = dynamic
    summary = run.summary()
    assert run.n_contacts >= 1, run.message
    kinetic = 0.5 * problem.mass_kg * problem.velocity_m_s**2
    assert 0.05 * kinetic < summary["dissipated_energy_J"] < kinetic
    assert summary["residual_approach_m"] > 0.0
    assert abs(run.energy_error) < 1e-3
    assert summary["plastic_guard"] < 1.0


def test_the_continuum_and_the_sem_with_its_law_with_memory_agree(yielding_case, dynamic) -> None:
    """The SEM with the law the continuum's elastic-plastic indentation gives (its unloading curves:
    the law with memory), on the same mesh, against the dynamic continuum: contact time within
    1 % and restitution within 2 %."""
    _, run = dynamic
    curve = indentation_curve(yielding_case, SETTINGS)
    law = TabulatedLaw.from_bodies(
        {"from": "fem_axi_indentation", "curve": curve.law_curve()}, yielding_case["impactor"]["radius_m"], None, None
    )
    assert isinstance(law, TabulatedMemoryLaw)
    one_d = copy.deepcopy(yielding_case)
    one_d["contact"] = {"law": "hertz"}
    problem = dataclasses.replace(ImpactProblem.from_case(one_d), contact=law)
    sem = solve_sem(problem, METHODS["sem"].options())
    assert sem.success, sem.message
    assert sem.contact_time_s == pytest.approx(run.contact_time_s, rel=0.01)
    assert sem.restitution == pytest.approx(run.restitution, rel=0.02)
