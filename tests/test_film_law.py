"""The thin-film law (hertz_film) and the tabulated law, against mathematics.

- the law against its own closed forms (dP/dalpha, dE/dalpha, the inverse, the step root);
- a film of vanishing thickness is Hertz's law (the runs agree to 1e-9);
- on a rigid rod, the quadrature of the energy integral against sem;
- sem, sem_paper and fem1d agree on a film case as on Hertz, and sem keeps order 2;
- the energy balance with the film's stored energy closes;
- the tabulated law reproduces a power law exactly, and the film law to its measured
  interpolation error, and a run with it agrees with the run with the law it tabulates.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rodimpact.contact import film_impact
from rodimpact.contact.film import HertzFilmLaw, constrained_modulus, film_constant
from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.contact.law import ContactLaw
from rodimpact.contact.tabulated import TabulatedLaw, pchip_slopes
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.fem1d.solver import solve_fem1d
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions
from rodimpact.solvers.sem.solver import solve_sem

from helpers.paper import ALUMINIUM, STEEL

# Table 2, row 1 on the text's rod with the text's film (pvdf, nominal constants)
RADIUS, MASS, VELOCITY = 1.58e-3, 1.30e-4, 0.3225
THICKNESS, FILM_E, FILM_NU = 28e-6, 3.0e9, 0.35
TEXT_ROD = Rod(0.0301, math.pi * 0.01**2, ALUMINIUM)


def film_law(thickness: float = THICKNESS, modulus: float = FILM_E) -> HertzFilmLaw:
    k = hertz_constant(RADIUS, STEEL, ALUMINIUM)
    c = film_constant(RADIUS, thickness, constrained_modulus(modulus, FILM_NU))
    return HertzFilmLaw(k, c, RADIUS, thickness)


def film_problem(law=None, rod: Rod = TEXT_ROD) -> ImpactProblem:
    return ImpactProblem(MASS, VELOCITY, film_law() if law is None else law, rod)


def test_constrained_modulus_and_film_constant():
    """M = E (1-nu)/((1+nu)(1-2nu)) (M = E at nu = 0; M/E = 2.1429 at nu = 0.4) and c = pi M R / h."""
    assert constrained_modulus(3e9, 0.0) == 3e9
    assert constrained_modulus(1.0, 0.4) == pytest.approx(0.6 / (1.4 * 0.2), rel=1e-15)
    assert film_constant(2.0, 0.5, 3.0) == pytest.approx(math.pi * 12.0, rel=1e-15)


def test_film_law_is_consistent_with_itself():
    """dP/dalpha, dE/dalpha against central differences (error ~ (h/alpha)^2 = 1e-12), the
    inverse, the series sum alpha = (P/k)^(2/3) + (P/c)^(1/2), and the step's root."""
    law = film_law()
    for alpha in (1e-9, 1e-7, 2e-6, 2e-5):
        h = 1e-6 * alpha
        assert (law.force(alpha + h) - law.force(alpha - h)) / (2 * h) == pytest.approx(law.stiffness(alpha), rel=1e-7)
        assert (float(law.energy(alpha + h)) - float(law.energy(alpha - h))) / (2 * h) == pytest.approx(
            law.force(alpha), rel=1e-7
        )
        force = law.force(alpha)
        assert (force / law.k) ** (2 / 3) + math.sqrt(force / law.c) == pytest.approx(alpha, rel=1e-14)
        assert law.approach(force) == pytest.approx(alpha, rel=1e-14)
        for b in (0.0, 1e-9, 1e-6):
            root, _ = law.solve_step(alpha, b, 0.0)
            assert root + b * law.force(root) == pytest.approx(alpha, rel=1e-13)
    assert np.allclose(law.energy(np.array([1e-7, 2e-6])), [law.energy(1e-7), law.energy(2e-6)], rtol=1e-15)
    assert law.force(-1e-6) == 0.0 and law.stiffness(0.0) == 0.0 and float(law.energy(-1.0)) == 0.0


def test_energy_between_is_the_quadrature_without_cancellation():
    """The closed form of int P d alpha over [lower, upper] against adaptive quadrature of the
    force (ContactLaw's generic method) to 1e-12, and on an interval of 1e-13 relative width,
    where E(upper) - E(lower) loses 13 digits, against the midpoint rule P(mid) times the width
    to 1e-9 (its error is of the order of the squared relative width)."""
    from rodimpact.contact.law import ContactLaw

    law = film_law()
    for lower, upper in ((0.0, 1e-6), (-1e-7, 2e-6), (1e-7, 2e-5), (2e-6, 3e-6)):
        assert law.energy_between(lower, upper) == pytest.approx(
            ContactLaw.energy_between(law, lower, upper), rel=1e-12
        )
    assert law.energy_between(3e-6, 2e-6) == pytest.approx(-law.energy_between(2e-6, 3e-6), rel=1e-15)
    assert law.energy_between(1e-6, 1e-6) == 0.0
    alpha = 2e-6
    upper = alpha * (1 + 1e-13)
    width = upper - alpha  # exact (Sterbenz)
    narrow = law.energy_between(alpha, upper)
    assert narrow == pytest.approx(law.force(alpha + 0.5 * width) * width, rel=1e-9)
    difference = float(law.energy(upper)) - float(law.energy(alpha))
    assert abs(difference / narrow - 1) > 1e-6  # the naive difference has lost those digits


def test_step_force_is_the_force_at_the_step_root():
    """solve_step_force's P is P(alpha) of its root to 1e-14: one root, not two."""
    law = film_law()
    for a in (1e-8, 2e-6):
        for b in (0.0, 1e-9, 1e-6):
            alpha, force, _ = law.solve_step_force(a, b, 0.0)
            assert alpha == law.solve_step(a, b, 0.0)[0]
            assert force == pytest.approx(law.force(alpha), rel=1e-14)
    assert law.solve_step_force(-1.0, 1e-6, 0.0) == (0.0, 0.0, 0)


def test_vanishing_film_is_hertz():
    """h -> 0: the film's share (P h / (pi M R))^(1/2) of the approach goes as sqrt(h); at
    h = 1e-30 m it is ~1e-14 of the approach, and the sem runs of the two laws agree to 1e-9."""
    hertz = HertzLaw(hertz_constant(RADIUS, STEEL, ALUMINIUM), RADIUS)
    options = SEMOptions(tolerance=1e-8)
    reference = solve_sem(film_problem(hertz), options)
    thin = solve_sem(film_problem(film_law(thickness=1e-30)), options)
    assert thin.contact_time_s == pytest.approx(reference.contact_time_s, rel=1e-9)
    assert thin.peak_force_N[0] == pytest.approx(reference.peak_force_N[0], rel=1e-9)
    # and the film's share falls as sqrt(h): the slope of log(share) against log(h) is 1/2
    thicknesses = np.geomspace(1e-12, 1e-6, 5)
    shares = [float(film_law(h).approach(5.0) - hertz.approach(5.0)) for h in thicknesses]
    assert np.polyfit(np.log(thicknesses), np.log(shares), 1)[0] == pytest.approx(0.5, abs=1e-9)


@pytest.mark.parametrize("thickness", [1e-30, 1e-9, THICKNESS, 1e-3])
@pytest.mark.parametrize(("mass", "velocity"), [(1e-6, 50.0), (MASS, VELOCITY), (10.0, 0.01)])
def test_rigid_impact_in_s_against_adaptive_quadrature(thickness, mass, velocity):
    """The film law's rigid impact (Gauss-Legendre in s, rodimpact.contact.film_impact) against
    the generic adaptive quadrature of the energy integral in alpha (epsrel 1e-12), from a film of
    1e-30 m (Hertz) to 1 mm, and against Gauss-Legendre on 4 times the nodes (converged)."""
    law = film_law(thickness)
    fast, generic = law.rigid_impact(mass, velocity), ContactLaw._rigid_impact(law, mass, velocity)
    assert fast.contact_time_s == pytest.approx(generic.contact_time_s, rel=1e-11)
    assert fast.max_approach_m == pytest.approx(generic.max_approach_m, rel=1e-14)
    assert fast.peak_force_N == pytest.approx(generic.peak_force_N, rel=1e-14)
    nodes, weights = np.polynomial.legendre.leggauss(4 * film_impact.NODES)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(film_impact, "_NODES", nodes)
        patch.setattr(film_impact, "_WEIGHTS", weights)
        finer = film_impact.thin_layer_rigid_impact(law._a, law._b, mass, velocity)
    assert fast.contact_time_s == pytest.approx(finer.contact_time_s, rel=1e-14)


def test_rigid_impact_in_s_is_hertz_without_a_film():
    """B = 0 is Hertz's law: t_c, alpha_max and P_max of the closed form to 1e-14."""
    k = hertz_constant(RADIUS, STEEL, ALUMINIUM)
    exact = HertzLaw(k, RADIUS).rigid_impact(MASS, VELOCITY)
    thin = film_impact.thin_layer_rigid_impact(k ** (-2.0 / 3.0), 0.0, MASS, VELOCITY)
    assert thin.contact_time_s == pytest.approx(exact.contact_time_s, rel=1e-14)
    assert thin.max_approach_m == pytest.approx(exact.max_approach_m, rel=1e-14)
    assert thin.peak_force_N == pytest.approx(exact.peak_force_N, rel=1e-14)
    with pytest.raises(ValueError, match="mass_kg"):
        film_impact.thin_layer_rigid_impact(1.0, 0.0, 0.0, VELOCITY)


def test_rigid_rod_closed_form_against_sem():
    """A rigid-like rod (E S / l = 4e16 N/m): the contact time and peak force of sem against the
    quadrature of the energy integral, 2 int_0^alpha_max d alpha / v(alpha), to 1e-6."""
    law = film_law()
    rigid = law.rigid_impact(MASS, VELOCITY)
    # the quadrature against its closed-form limits: peak force P(alpha_max), E(alpha_max) = m v0^2 / 2
    assert float(law.energy(rigid.max_approach_m)) == pytest.approx(0.5 * MASS * VELOCITY**2, rel=1e-12)
    stiff_rod = Rod(0.5, 1.0e5, STEEL)
    result = solve_sem(film_problem(law, stiff_rod), SEMOptions(tolerance=1e-10))
    assert result.contact_time_s == pytest.approx(rigid.contact_time_s, rel=1e-6)
    assert result.peak_force_N[0] == pytest.approx(rigid.peak_force_N, rel=1e-6)


def test_methods_agree_on_the_film_case():
    """At the shipped settings sem, sem_paper and fem1d give the film case's contact time to
    1e-4 of each other (as on Hertz), and sem's observed order in the step is 2."""
    problem = film_problem()
    sem = solve_sem(problem, SEMOptions())
    paper = solve_sem(problem, PaperSEMOptions())
    fem = solve_fem1d(problem, FEM1DOptions())
    for other in (paper, fem):
        assert other.contact_time_s == pytest.approx(sem.contact_time_s, rel=1e-4)
    reference = solve_sem(problem, SEMOptions(steps_per_contact=16000))
    steps = np.array([250, 500, 1000, 2000])
    runs = [solve_sem(problem, SEMOptions(steps_per_contact=int(n))) for n in steps]
    for quantity in (lambda r: r.contact_time_s, lambda r: r.peak_force_N[0]):
        errors = [abs(quantity(run) - quantity(reference)) for run in runs]
        order = -np.polyfit(np.log(steps), np.log(errors), 1)[0]
        assert 1.8 < order < 2.4  # the bounds of test_sem's order test on Hertz
    assert sem.contact_time_s == pytest.approx(reference.contact_time_s, rel=1e-5)


def test_energy_balance_includes_the_film():
    """KE_in = KE_out + rod energy + the law's stored energy (which holds the film's): the
    balance of each 1-D method closes to its stated tolerance."""
    problem = film_problem()
    assert abs(solve_sem(problem, SEMOptions(tolerance=1e-8)).energy_error) < 1e-6
    assert abs(solve_fem1d(problem, FEM1DOptions()).energy_error) < 1e-6


# --------------------------------------------------------------------------- tabulated


def test_pchip_slopes_are_scipys():
    """The slopes are scipy's PchipInterpolator's (the same Fritsch-Carlson rule) to 1e-12."""
    from scipy.interpolate import PchipInterpolator

    x = np.array([0.0, 0.3, 1.0, 1.1, 2.5, 4.0])
    y = np.array([0.0, 0.2, 1.5, 1.6, 1.61, 3.0])
    assert np.allclose(pchip_slopes(x, y), PchipInterpolator(x, y).derivative()(x), rtol=1e-12, atol=1e-14)


def test_tabulated_law_is_exact_on_a_power_law():
    """A table of Hertz's law, straight in (ln alpha, ln P), is reproduced to round-off
    everywhere, outside the table too (its end slopes continue as the power law)."""
    hertz = HertzLaw(hertz_constant(RADIUS, STEEL, ALUMINIUM), RADIUS)
    alphas = np.geomspace(1e-8, 1e-5, 7)
    table = TabulatedLaw(tuple(alphas), tuple(hertz.force(a) for a in alphas))
    for alpha in np.geomspace(1e-9, 3e-5, 23):
        assert table.force(alpha) == pytest.approx(hertz.force(alpha), rel=1e-12)
        assert table.stiffness(alpha) == pytest.approx(hertz.stiffness(alpha), rel=1e-10)
        assert float(table.energy(alpha)) == pytest.approx(float(hertz.energy(alpha)), rel=1e-12)
    assert table.approach(3.0) == pytest.approx(hertz.approach(3.0), rel=1e-12)
    rigid, exact = table.rigid_impact(MASS, VELOCITY), hertz.rigid_impact(MASS, VELOCITY)
    assert rigid.contact_time_s == pytest.approx(exact.contact_time_s, rel=1e-9)


def test_tabulated_film_law_and_its_run():
    """The film law tabulated at 17 points spaced in ratio over the impact's range: the
    interpolation error in P is below 2e-4 between the points (measured 4e-5), and the sem
    run with the table agrees with the run with the law to 1e-4 in contact time and peak force."""
    law = film_law()
    peak = 1.5 * law.rigid_impact(MASS, VELOCITY).peak_force_N
    alphas = law.approach(peak) * np.geomspace(0.01, 1.0, 17)
    table = TabulatedLaw(tuple(alphas), tuple(law.force(a) for a in alphas))
    between = np.sqrt(alphas[1:] * alphas[:-1])
    error = max(abs(table.force(a) / law.force(a) - 1.0) for a in between)
    assert error < 2e-4
    exact = solve_sem(film_problem(law), SEMOptions())
    tabulated = solve_sem(film_problem(table), SEMOptions())
    assert tabulated.contact_time_s == pytest.approx(exact.contact_time_s, rel=1e-4)
    assert tabulated.peak_force_N[0] == pytest.approx(exact.peak_force_N[0], rel=1e-4)


def test_tabulated_law_refuses_a_non_monotone_curve():
    with pytest.raises(ValueError, match="strictly increasing"):
        TabulatedLaw((1e-6, 2e-6, 3e-6), (1.0, 0.5, 2.0))
