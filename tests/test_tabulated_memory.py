"""The ``tabulated`` law with memory: a loading curve and unloading curves from several maxima,
interpolated between them. Checked against a law with memory known in closed form (Thornton's,
sampled as the continuum's indentation samples its curves)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from rodimpact.contact.hertz import effective_modulus
from rodimpact.contact.tabulated import TabulatedLaw, TabulatedMemoryLaw, unloading_shape
from rodimpact.contact.thornton import ThorntonLaw, yield_velocity
from rodimpact.model.materials import Material
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.registry import METHODS
from rodimpact.solvers.sem.solver import solve_sem

STEEL = Material(2.1e11, 0.3, 7800.0)
ALUMINIUM = Material(7.0e10, 0.33, 2700.0)
RADIUS = 0.00475 / 2.0


def sampled(law: ThorntonLaw, maxima: int = 9, points: int = 12) -> TabulatedMemoryLaw:
    """Thornton's law as the indentation rule gives a law with memory: 97 loading points up to 40
    yield approaches, and ``maxima`` unloading curves of ``points`` points from loading points
    (spaced in ratio from 1.5 to 40 yield approaches), each from its maximum down, above its dent."""
    ay = law.yield_approach_m
    alpha = ay * 40.0 * np.geomspace(1.5 / 40.0, 1.0, 65)
    alpha = np.concatenate([ay * np.geomspace(0.05, 1.4, 32), alpha])
    loading = TabulatedLaw(tuple(alpha), tuple(law.force(a) for a in alpha))
    index, approach, force = [], [], []
    for k, top in enumerate(alpha[32:][:: 64 // (maxima - 1)]):
        dent = law.residual_approach(top)
        down = dent + (top - dent) * np.linspace(1.0, 0.0, points + 1)[:-1]
        branch = law.branch(top)
        index += [k] * points
        approach += down.tolist()
        force += [branch.force(a) for a in down]
    curve = {"unloading": {"curve": index, "approach_m": approach, "force_N": force}, "elastic_limit_m": ay}
    return TabulatedMemoryLaw.from_curve(loading, curve)


@pytest.fixture(scope="module")
def thornton() -> ThorntonLaw:
    return ThorntonLaw(effective_modulus(STEEL, ALUMINIUM), RADIUS, 1.6 * 2.76e8)


@pytest.fixture(scope="module")
def memory(thornton: ThorntonLaw) -> TabulatedMemoryLaw:
    return sampled(thornton, maxima=17)


def test_a_curve_with_unloading_curves_builds_the_law_with_memory(thornton: ThorntonLaw) -> None:
    """``from_bodies`` gives the elastic table without unloading curves, the law with memory with."""
    ay = thornton.yield_approach_m
    alpha = ay * np.geomspace(0.05, 10.0, 20)
    curve = {"approach_m": alpha.tolist(), "force_N": [thornton.force(a) for a in alpha]}
    spec = {"law": "tabulated", "from": "fem_axi_indentation", "curve": curve}
    plain = TabulatedLaw.from_bodies(spec, RADIUS, STEEL, ALUMINIUM)
    assert type(plain) is TabulatedLaw and not plain.memory
    top = 5.0 * ay
    dent = thornton.residual_approach(top)
    down = dent + (top - dent) * np.linspace(1.0, 0.0, 9)[:-1]
    curve["unloading"] = {
        "curve": [0] * 8,
        "approach_m": down.tolist(),
        "force_N": [thornton.branch(top).force(a) for a in down],
    }
    curve["elastic_limit_m"] = ay
    law = TabulatedLaw.from_bodies(spec, RADIUS, STEEL, ALUMINIUM)
    assert isinstance(law, TabulatedMemoryLaw) and law.memory
    # a Hertzian unloading curve is straight in (alpha, P^(2/3)): its dent is found exactly
    assert law.residual_approach(top) == pytest.approx(dent, rel=1e-12)


def test_the_branch_of_a_stored_maximum_is_its_unloading_curve(thornton, memory) -> None:
    """At each stored maximum the branch goes through the stored points, meets the loading curve
    at the maximum, carries nothing below the dent, and is monotone."""
    for top in memory.max_approach_m:
        branch = memory.branch(top)
        exact = thornton.branch(top)
        dent = thornton.residual_approach(top)
        assert memory.residual_approach(top) == pytest.approx(dent, rel=1e-10)
        for a in dent + (top - dent) * np.linspace(0.05, 1.0, 7):
            assert branch.force(a) == pytest.approx(exact.force(a), rel=1e-9)
        assert branch.force(top) == memory.force(top)
        assert branch.force(0.999 * dent) == 0.0
        grid = np.linspace(0.0, 2.0 * top, 400)
        assert np.all(np.diff([branch.force(a) for a in grid]) >= 0.0)


def test_energies_add_up(memory) -> None:
    """Stored energy = the integral of the branch's force (1e-9); what loading did = what
    unloading returns + what was dissipated; the branch's stiffness is its force's slope."""
    ay = memory.elastic_limit_m
    for top in (0.8 * ay, 2.3 * ay, 7.7 * ay, 25.0 * ay, 50.0 * ay):
        branch = memory.branch(top)
        dent = float(memory.residual_approach(top))
        stored = float(memory.stored_energy(top, top))
        integral = quad(branch.force, dent, top, epsabs=0.0, epsrel=1e-12, limit=200)[0]
        assert stored == pytest.approx(integral, rel=1e-9)
        loaded = float(memory.loading.energy(top))
        assert loaded == pytest.approx(stored + float(memory.dissipated_energy(top)), rel=1e-12)
        a = dent + 0.4 * (top - dent)
        step = 1e-6 * (top - dent)
        slope = (branch.force(a + step) - branch.force(a - step)) / (2 * step)
        assert branch.stiffness(a) == pytest.approx(slope, rel=1e-6)
    assert memory.dissipated_energy(0.8 * ay) == 0.0


def test_interpolated_between_maxima_it_gives_thorntons_impact(thornton, memory) -> None:
    """Between the stored maxima (17 curves, ratio 1.23) the law is interpolated: the rigid impact's
    restitution and contact time are Thornton's closed form's to 2e-4 from 2 to 10 yield velocities
    (measured 1.2e-4, 3.7e-5, 1.8e-5, 1.1e-5 in restitution at 2, 3, 5, 10; with 9 curves
    1.6e-3, 6.9e-4, 4.0e-4, 4.8e-5), exactly elastic below, the dent and the dissipation to 1e-3."""
    mass = 4.0 / 3.0 * math.pi * RADIUS**3 * 7800.0
    v_y = yield_velocity(mass, thornton.k, thornton.yield_approach_m)
    elastic = memory.rigid_impact(mass, 0.5 * v_y)
    assert elastic.restitution == 1.0 and elastic.residual_approach_m == 0.0
    for ratio in (2.0, 3.0, 5.0, 10.0):
        closed = thornton.rigid_impact(mass, ratio * v_y)
        table = memory.rigid_impact(mass, ratio * v_y)
        assert table.restitution == pytest.approx(closed.restitution, rel=2e-4)
        assert table.contact_time_s == pytest.approx(closed.contact_time_s, rel=2e-4)
    ay = thornton.yield_approach_m
    for top in (5.0 * ay, 13.0 * ay, 30.0 * ay):
        assert memory.residual_approach(top) == pytest.approx(thornton.residual_approach(top), rel=1e-3)
        assert memory.dissipated_energy(top) == pytest.approx(thornton.dissipated_energy(top), rel=1e-3)


def test_fewer_unloading_curves_interpolate_worse(thornton) -> None:
    """The interpolation error falls as unloading curves are added: with 5 curves the dent between
    them is further from Thornton's than with 9 and with 17."""
    ay = thornton.yield_approach_m
    tops = ay * np.geomspace(1.7, 35.0, 23)
    errors = []
    mass = 4.0 / 3.0 * math.pi * RADIUS**3 * 7800.0
    v_y = yield_velocity(mass, thornton.k, thornton.yield_approach_m)
    for maxima in (5, 9, 17):
        law = sampled(thornton, maxima=maxima)
        errors.append(max(abs(law.residual_approach(m) / thornton.residual_approach(m) - 1.0) for m in tops))
        # what docs/contact-laws.md quotes (pytest -rP): the rigid impact's errors at 2, 3, 5, 10 V_y
        impacts = [(law.rigid_impact(mass, r * v_y), thornton.rigid_impact(mass, r * v_y)) for r in (2, 3, 5, 10)]
        print(
            f"{maxima} curves: restitution",
            " ".join(f"{t.restitution / c.restitution - 1:+.1e}" for t, c in impacts),
            "contact time",
            " ".join(f"{t.contact_time_s / c.contact_time_s - 1:+.1e}" for t, c in impacts),
        )
    assert errors[0] > errors[1] > errors[2]


def test_sem_with_the_table_strikes_twice_as_with_thorntons_law(thornton, memory) -> None:
    """The 4.75 mm ball on Table 2's long thin rod strikes twice: by the SEM, the sampled law with
    memory gives Thornton's contact times and restitution to 1e-3 (measured 2e-6 and 2e-5)."""
    rod = Rod(length_m=0.301, area_m2=math.pi * 0.001**2, material=ALUMINIUM, far_end="fixed")
    mass = 4.0 / 3.0 * math.pi * RADIUS**3 * 7800.0
    runs = [solve_sem(ImpactProblem(mass, 0.3225, law, rod), METHODS["sem"].options()) for law in (thornton, memory)]
    exact, table = runs
    assert exact.success and table.success and table.n_contacts == exact.n_contacts == 2
    np.testing.assert_allclose(table.contact_end_s, exact.contact_end_s, rtol=1e-3)
    np.testing.assert_allclose(table.contact_start_s[1], exact.contact_start_s[1], rtol=1e-3)
    assert table.restitution == pytest.approx(exact.restitution, rel=1e-3)
    # the energy balance counts the table's dissipation: it closes as with Thornton's law (the
    # scheme's own 2.5e-6 on this run)
    assert table.energy_error == pytest.approx(exact.energy_error, rel=0.05)


def test_a_bad_unloading_curve_is_refused() -> None:
    """An unloading curve that rises, or has fewer than three points with force, is refused."""
    with pytest.raises(ValueError, match="must fall"):
        unloading_shape([3.0, 2.0, 2.5, 1.0], [9.0, 5.0, 6.0, 1.0])
    with pytest.raises(ValueError, match="at least two more"):
        unloading_shape([3.0, 2.0, 1.0], [9.0, 5.0, 0.0])
