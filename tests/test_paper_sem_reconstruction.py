"""Why our SEM differs from the paper's SEM column of Table 2 (docs/results.md, "Our SEM and the paper's SEM").

With the shipped physics (two-material Hertz constant, sphere radius = diameter / 2) our SEM
is 11-16 % longer than the paper's SEM on the 10 mm rods. Reading the printed diameter as the
sphere's radius (k larger by sqrt(2)) reproduces the paper's SEM column within 3 %, for both
10 mm rod lengths: the most likely source of the paper's short SEM times.
"""

import math

import numpy as np
import pytest

from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.model.materials import Material
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.sem.options import SEMOptions
from rodimpact.solvers.sem.solver import solve_sem


def contact_times(project, variant: str, radius_factor: float) -> tuple[np.ndarray, np.ndarray]:
    ours, paper = [], []
    for case in project.cases_in("table2", variant):
        ball = Material.from_mapping(case["impactor"]["material"])
        rod_mat = Material.from_mapping(case["rod"]["material"])
        rod = Rod(case["rod"]["length_m"], case["rod"]["area_m2"], rod_mat)
        k = hertz_constant(radius_factor * case["impactor"]["radius_m"], ball, rod_mat)
        problem = ImpactProblem(case["impactor"]["mass_kg"], case["impactor"]["velocity_m_s"], HertzLaw(k), rod)
        ours.append(1e6 * solve_sem(problem, SEMOptions(steps_per_contact=400)).contact_time_s)
        paper.append(case["published"]["sem"]["contact_time_us"])
    return np.array(ours), np.array(paper)


@pytest.mark.parametrize("variant", ["r10_l30", "r10_l301"])
def test_shipped_physics_is_longer_than_the_papers_sem(shipped_project, variant):
    ours, paper = contact_times(shipped_project, variant, 1.0)
    deviation = ours / paper - 1.0
    assert np.all(deviation > 0.10) and np.all(deviation < 0.17)


@pytest.mark.parametrize("variant", ["r10_l30", "r10_l301"])
def test_diameter_read_as_radius_reproduces_the_papers_sem(shipped_project, variant):
    ours, paper = contact_times(shipped_project, variant, 2.0)
    assert np.max(np.abs(ours / paper - 1.0)) < 0.03


def test_thin_rods_cannot_explain_the_papers_sem(shipped_project):
    for variant in ("r1_l30", "r1_l301"):
        for factor in (1.0, 2.0):
            ours, paper = contact_times(shipped_project, variant, factor)
            assert np.max(np.abs(ours / paper - 1.0)) > 0.5
    assert math.isfinite(ours.sum())
