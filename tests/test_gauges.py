"""Strain gauges and the far end's velocity (outputs ``gauge_strain``, ``far_end_velocity``)
in every method: the SEM against d'Alembert's closed form, fem1d against the SEM within its
discretisation error (measured, with its observed order), fem_axi's surface strain against
its cross-section mean, the gauges' checks, and the outputs' way through the registry to a
stored run."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.model.gauges import Gauge, GaugeError
from rodimpact.model.problem import ImpactProblem
from rodimpact.model.responses import Rod
from rodimpact.solvers.fem1d.cost import fem1d_cost
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.fem1d.solver import solve_fem1d
from rodimpact.solvers.fem_axi.cost import fem_axi_dofs
from rodimpact.solvers.fem_axi.farbar import continuum_length
from rodimpact.solvers.fem_axi.gauges import STATION_HALF_SPAN
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import solve_fem_axi
from rodimpact.solvers.gauge_series import RECORD_CONTACT_MARGIN, RECORD_TRANSIT_MARGIN, record_until_s
from rodimpact.solvers.registry import METHODS
from rodimpact.solvers.sem.cost import sem_cost
from rodimpact.solvers.sem.history import ForceHistory
from rodimpact.solvers.sem.options import SEMOptions
from rodimpact.solvers.sem.solver import solve_sem
from rodimpact.storage.runs import read_run, write_run

from helpers.paper import STEEL, model_problem

#: The model problem's rod: 0.5 m, 5e-5 m^2 (radius 4 mm), steel.
LENGTH = 0.5
ROD_RADIUS = math.sqrt(5e-5 / math.pi)
#: The SEM's gauges: a point and a 20 mm gauge at L/10, and a point at the far end.
SEM_GAUGES = (Gauge(0.1 * LENGTH), Gauge(0.1 * LENGTH, 0.02), Gauge(LENGTH))


def _incident(result, delay: float) -> np.ndarray:
    """P(t - delay) at the run's nodes, from its stored force alone: np.interp on the stored
    time grid, which is the implicit scheme's own interpolation of its force (linear between
    nodes, ForceHistory.force_array); 0 before the impact."""
    tau = result.time - delay
    return np.where(tau > 0.0, np.interp(tau, result.time, result.contact_force), 0.0)


def _sem(far_end: str):
    problem = model_problem(far_end)
    result = solve_sem(problem, SEMOptions(), gauges=SEM_GAUGES, far_end_velocity=True)
    assert result.success, result.message
    return problem, result


@pytest.fixture(scope="module")
def sem_fixed():
    return _sem("fixed")


@pytest.fixture(scope="module")
def sem_free():
    return _sem("free")


# -- the SEM: d'Alembert's closed form -----------------------------------------------------


def test_sem_point_gauge_reads_the_incident_wave_before_the_first_reflection(sem_fixed):
    """eps(x, t) = -P(t - x/c) / (E A) until the far end's reflection arrives, (2L - x)/c."""
    problem, result = sem_fixed
    rod = problem.rod
    x, c, ea = SEM_GAUGES[0].station_m, rod.wave_speed, rod.material.youngs_modulus_pa * rod.area_m2
    before = result.time < (2 * LENGTH - x) / c
    expected = -_incident(result, x / c)[before] / ea
    assert before.sum() > 100 and np.max(np.abs(expected)) > 0
    strain = result.extra_series["gauge_strain"][0][before, 0]
    np.testing.assert_allclose(strain, expected, rtol=1e-9, atol=1e-9 * np.max(np.abs(expected)))
    np.testing.assert_array_equal(result.extra["gauge_x_m"], [g.station_m for g in SEM_GAUGES])
    np.testing.assert_array_equal(result.extra["gauge_length_m"], [g.gauge_length_m for g in SEM_GAUGES])


def test_sem_gauge_of_length_g_is_the_mean_of_the_incident_wave_over_it(sem_fixed):
    """Before the reflection reaches its far end, t < (2L - x - g/2)/c, a gauge of length g
    reads the mean of -P(t - s/c)/(E A) over s in [x - g/2, x + g/2]:

        eps_g(t) = -(c / (E A g)) int_{t - (x + g/2)/c}^{t - (x - g/2)/c} P(tau) d tau,

    the integral taken here by quadrature (scipy's quad, with the force nodes as break points,
    relative accuracy 1e-12) of the stored force interpolated linearly; agreement to 1e-9 of
    the largest strain."""
    problem, result = sem_fixed
    rod = problem.rod
    gauge = SEM_GAUGES[1]
    low, high = gauge.ends()
    c, ea, g = rod.wave_speed, rod.material.youngs_modulus_pa * rod.area_m2, gauge.gauge_length_m
    t, force = result.time, result.contact_force

    def p(tau: float) -> float:
        return float(np.interp(tau, t, force)) if tau > 0.0 else 0.0

    inside = np.flatnonzero((t > low / c) & (t < (2 * LENGTH - high) / c))
    samples = inside[:: max(1, len(inside) // 60)]
    expected = []
    for i in samples:
        a, b = t[i] - high / c, t[i] - low / c
        nodes = t[(t > a) & (t < b)]
        integral, _ = quad(p, a, b, points=nodes, limit=len(nodes) + 50, epsabs=0.0, epsrel=1e-12)
        expected.append(-c * integral / (ea * g))
    expected = np.asarray(expected)
    strain = result.extra_series["gauge_strain"][0][samples, 1]
    np.testing.assert_allclose(strain, expected, rtol=0, atol=1e-9 * np.max(np.abs(expected)))


def test_sem_strain_at_a_fixed_end_is_twice_the_incident_wave(sem_fixed):
    """At x = L, fixed, the incident and its reflection add: eps(L, t) = -2 P(t - L/c)/(E A)
    during the first transit there, L/c <= t < 3L/c."""
    problem, result = sem_fixed
    rod = problem.rod
    c, ea = rod.wave_speed, rod.material.youngs_modulus_pa * rod.area_m2
    first = result.time < 3 * LENGTH / c
    expected = -2.0 * _incident(result, LENGTH / c)[first] / ea
    assert np.max(np.abs(expected)) > 0
    strain = result.extra_series["gauge_strain"][0][first, 2]
    np.testing.assert_allclose(strain, expected, rtol=1e-9, atol=1e-9 * np.max(np.abs(expected)))


def test_sem_free_far_end_moves_at_twice_the_incident_particle_velocity(sem_free, sem_fixed):
    """v(L, t) = 2 P(t - L/c) / Z during the first arrival (t < 3L/c) at a free far end; a
    fixed one does not move."""
    problem, result = sem_free
    rod = problem.rod
    first = result.time < 3 * LENGTH / rod.wave_speed
    expected = 2.0 * _incident(result, LENGTH / rod.wave_speed)[first] / rod.impedance
    assert np.max(expected) > 0
    velocity, units, _ = result.extra_series["far_end_velocity"]
    assert units == "m/s"
    np.testing.assert_allclose(velocity[first], expected, rtol=1e-9, atol=1e-9 * np.max(expected))
    assert np.all(sem_fixed[1].extra_series["far_end_velocity"][0] == 0.0)


# -- fem1d against the SEM --------------------------------------------------------------------


def _sem_reference(problem, sem, gauge: Gauge, times: np.ndarray) -> np.ndarray:
    """The SEM's gauge strain at ``times``: d'Alembert of its force, exact at any time."""
    history = ForceHistory.of_nodes(problem.rod, True, sem.time, sem.contact_force)
    if gauge.gauge_length_m == 0.0:
        return history.strain_at(gauge.station_m, times)
    low, high = gauge.ends()
    return (history.displacement_at(high, times) - history.displacement_at(low, times)) / gauge.gauge_length_m


def _differences(computed: np.ndarray, reference: np.ndarray) -> tuple[float, float]:
    """Relative L2 and max-norm differences of two histories on the same times."""
    difference = computed - reference
    return (
        float(np.linalg.norm(difference) / np.linalg.norm(reference)),
        float(np.max(np.abs(difference)) / np.max(np.abs(reference))),
    )


def test_fem1d_gauges_agree_with_the_sem_within_the_discretisation_error(sem_fixed):
    """A point gauge at L/2 and a 20 mm gauge at 0.3 L on the fixed model rod, fem1d at its
    default settings (P2, 200 nodes per wavelength: 47 elements, 2000 steps per contact) and
    refined twice (nodes per wavelength and steps per contact x2, x4), against the SEM over
    fem1d's nodes up to the SEM run's end.

    Measured (relative L2 / max-norm): point gauge 6.8e-4 / 2.3e-3, 2.7e-4 / 1.2e-3,
    8.4e-5 / 4.7e-4 (observed order of the L2 difference 1.5: the strain is a derivative and
    its front disperses); 20 mm gauge 4.1e-4 / 1.5e-3, 4.6e-5 / 1.9e-4, 1.2e-5 / 6.0e-5 (order
    2.5). The SEM's own error is far below (its tolerance 1e-8 changes none of these figures by
    more than 1 %)."""
    problem, _ = sem_fixed
    sem = solve_sem(problem, SEMOptions())
    gauges = (Gauge(0.5 * LENGTH), Gauge(0.3 * LENGTH, 0.02))
    levels = (1, 2, 4)
    table = []  # per level: (l2, max) per gauge
    for level in levels:
        fem = solve_fem1d(
            problem,
            FEM1DOptions(points_per_wavelength=200.0 * level, steps_per_contact=2000 * level),
            gauges=gauges,
        )
        assert fem.success, fem.message
        inside = fem.time <= sem.time[-1]
        table.append(
            [
                _differences(
                    fem.extra_series["gauge_strain"][0][inside, k], _sem_reference(problem, sem, g, fem.time[inside])
                )
                for k, g in enumerate(gauges)
            ]
        )
    table = np.asarray(table)  # (level, gauge, norm)
    (point_l2, point_max), (long_l2, long_max) = table[0]
    assert point_l2 < 1.5e-3 and point_max < 5e-3
    assert long_l2 < 1e-3 and long_max < 4e-3
    assert np.all(np.diff(table, axis=0) < 0)  # every refinement reduces every difference
    orders = [np.polyfit(np.log(levels), -np.log(table[:, k, 0]), 1)[0] for k in range(len(gauges))]
    assert orders[0] > 1.2 and orders[1] > 1.5


def test_fem1d_far_end_velocity_agrees_with_the_sem(sem_free):
    """Free far end, fem1d's default settings against the SEM: measured 5.9e-4 (relative L2)
    and 2.9e-3 (max norm); its fixed far end does not move."""
    problem, sem = sem_free
    fem = solve_fem1d(problem, FEM1DOptions(), far_end_velocity=True)
    assert fem.success, fem.message
    history = ForceHistory.of_nodes(problem.rod, True, sem.time, sem.contact_force)
    inside = fem.time <= sem.time[-1]
    l2, largest = _differences(
        fem.extra_series["far_end_velocity"][0][inside], history.velocity_at(LENGTH, fem.time[inside])
    )
    assert l2 < 1.5e-3 and largest < 6e-3
    fixed = solve_fem1d(model_problem("fixed"), FEM1DOptions(points_per_wavelength=50.0), far_end_velocity=True)
    assert np.all(fixed.extra_series["far_end_velocity"][0] == 0.0)


# -- fem_axi: the surface against the cross-section's mean ----------------------------------


def _relative_max(surface: np.ndarray, mean: np.ndarray) -> float:
    return float(np.max(np.abs(surface - mean)) / np.max(np.abs(mean)))


def test_fem_axi_surface_and_mean_agree_for_a_long_pulse():
    """The heavy cap (0.5 kg, contact ~0.5 ms: a pulse ~300 diameters long) on the 0.5 m rod,
    a point gauge and a 10 mm gauge at 50 mm (6 diameters, beyond the contact's near field):
    surface and mean strain agree within 1 % of the largest (measured 9.7e-4 and 1.5e-4). The
    continuum (5 diameters, 40 mm, without gauges) reaches one diameter beyond the 10 mm
    gauge's far end; the fixed far end does not move."""
    problem = AxiImpact(0.5, 1.0, 0.01, STEEL, "cap", ROD_RADIUS, LENGTH, STEEL, "fixed")
    gauges = (Gauge(0.05), Gauge(0.05, 0.01))
    result = solve_fem_axi(
        problem, FEMAxiOptions(elements_across=5, steps_per_contact=150), gauges=gauges, far_end_velocity=True
    )
    assert result.success, result.message
    surface, mean = result.extra_series["gauge_strain"][0], result.extra_series["gauge_mean_strain"][0]
    for k in range(len(gauges)):
        assert _relative_max(surface[:, k], mean[:, k]) < 1e-2
    assert result.extra["continuum_length_m"] == pytest.approx(0.055 + 2 * ROD_RADIUS)
    assert np.all(np.abs(result.extra_series["far_end_velocity"][0]) < 1e-12)


def test_fem_axi_surface_strain_differs_from_the_mean_for_a_short_pulse():
    """A 2 mm steel ball at 1 m/s on a steel rod of radius 5 mm (contact 6.9 us: a pulse 3.6
    radii long), a point gauge at 10 mm (one diameter): the section does not stay plane, and
    the surface strain departs from the mean by 10 % of the largest (measured 0.104, 0.102,
    0.101 at elements_across 5, 8, 12, steps_per_contact 100, 200, 300): more than 5 %."""
    mass = 4.0 / 3.0 * math.pi * 1e-3**3 * STEEL.density_kg_m3
    problem = AxiImpact(mass, 1.0, 1e-3, STEEL, "sphere", 5e-3, 0.05, STEEL, "fixed")
    result = solve_fem_axi(problem, FEMAxiOptions(elements_across=5, steps_per_contact=100), gauges=(Gauge(0.01),))
    assert result.success, result.message
    surface, mean = result.extra_series["gauge_strain"][0][:, 0], result.extra_series["gauge_mean_strain"][0][:, 0]
    assert _relative_max(surface, mean) > 0.05


def test_fem_axi_gauges_at_either_end_of_the_rod_are_whole():
    """Point gauges at z = 0 and z = L read a one-sided difference divided by its own span:
    the same strain as the gauges just inside (2 STATION_HALF_SPAN L in), not half of it.
    Measured on the 0.2 m rod: the mean strain at the struck end within 1.4 % of the largest,
    surface and mean at the fixed end within 0.5 % and 1.0 % (the surface at the free struck
    face carries almost no axial strain, so only its mean is compared there)."""
    length = 0.2
    delta = STATION_HALF_SPAN * length
    problem = AxiImpact(0.5, 1.0, 0.01, STEEL, "cap", ROD_RADIUS, length, STEEL, "fixed")
    gauges = (Gauge(0.0), Gauge(2 * delta), Gauge(length), Gauge(length - 2 * delta))
    result = solve_fem_axi(problem, FEMAxiOptions(elements_across=5, steps_per_contact=150), gauges=gauges)
    surface, mean = result.extra_series["gauge_strain"][0], result.extra_series["gauge_mean_strain"][0]
    assert _relative_max(mean[:, 0], mean[:, 1]) < 0.05
    assert _relative_max(surface[:, 2], surface[:, 3]) < 0.05
    assert _relative_max(mean[:, 2], mean[:, 3]) < 0.05


def test_fem_axi_free_far_end_velocity_is_close_to_the_sem(sem_free):
    """The section-mean axial velocity at z = L (the far bar's last node) on the coarse model
    against the SEM: measured 2.2 % (relative L2)."""
    problem, sem = sem_free
    axi = AxiImpact(0.5, 1.0, 0.01, STEEL, "cap", ROD_RADIUS, LENGTH, STEEL, "free")
    result = solve_fem_axi(axi, FEMAxiOptions(elements_across=5, steps_per_contact=150), far_end_velocity=True)
    history = ForceHistory.of_nodes(problem.rod, True, sem.time, sem.contact_force)
    inside = result.time <= sem.time[-1]
    l2, _ = _differences(
        result.extra_series["far_end_velocity"][0][inside], history.velocity_at(LENGTH, result.time[inside])
    )
    assert l2 < 0.05


def test_the_continuum_covers_the_gauges():
    """A gauge's reach moves the joint beyond the default 5 diameters; a bar shorter than a
    diameter is none; no cover, or a cover within the default, changes nothing."""
    assert continuum_length(1e-3, 0.301, 5.0) == pytest.approx(0.010)
    assert continuum_length(1e-3, 0.301, 5.0, cover_m=0.005) == pytest.approx(0.010)
    assert continuum_length(1e-3, 0.301, 5.0, cover_m=0.05) == pytest.approx(0.05)
    assert continuum_length(1e-3, 0.301, 5.0, cover_m=0.3) is None  # less than a diameter of bar
    assert continuum_length(1e-3, 0.0301, 5.0, cover_m=0.02) is None  # no bar anyway
    assert continuum_length(1e-3, 0.301, None, cover_m=0.05) is None


# -- the record goes on until the contact's waves have passed the gauges ------------------

#: A 10 mm steel ball (radius 5 mm, 4.084 g) at 1 m/s on a fixed 0.5 m steel rod of radius 5 mm,
#: a point gauge half-way: the contact lasts 35 us and ends before its wave reaches the gauge
#: (x/c = 48 us); the fixed end's reflection reaches it at (2L - x)/c = 145 us.
BALL_MASS = 4.0 / 3.0 * math.pi * 5e-3**3 * STEEL.density_kg_m3
BALL_ROD_RADIUS = 5e-3
BALL_GAUGE = Gauge(0.25)


def _ball_problem(far_end: str = "fixed") -> ImpactProblem:
    rod = Rod(LENGTH, math.pi * BALL_ROD_RADIUS**2, STEEL, far_end)
    return ImpactProblem(BALL_MASS, 1.0, HertzLaw(hertz_constant(5e-3, STEEL)), rod)


#: The contact results a run with records must share with the same run without.
CONTACT_RESULTS = (
    "success",
    "status",
    "message",
    "contact_start_s",
    "contact_end_s",
    "peak_time_s",
    "peak_force_N",
    "rebound_velocity_m_s",
    "rod_energy_J",
    "energy_error",
)


def _solve_ball(method: str, **records):
    problem = _ball_problem()
    if method == "sem":
        return problem, solve_sem(problem, SEMOptions(), **records)
    return problem, solve_fem1d(problem, FEM1DOptions(), **records)


@pytest.mark.parametrize(("method", "rtol"), [("sem", 1e-3), ("fem1d", 1e-2)])
def test_a_far_gauge_records_the_whole_first_pulse(method, rtol):
    """The run goes on after the contact (35 us) until its wave has passed the gauge at 0.25 m,
    t >= t_end + (1 + RECORD_TRANSIT_MARGIN) x/c + RECORD_CONTACT_MARGIN t_end (87 us, before
    the reflection's 145 us): the strain is back below 1 % of its peak at the end (measured: 0
    for the SEM, 1.8e-5 for fem1d), and its time integral is the impulse the contact
    transferred, int eps dt = -(1/(E A)) int P dt = -m (V0 - V_rebound)/(E A), V_rebound the
    reported rebound velocity (negative: away from the rod): measured within 4e-9 (SEM) and 1.1e-7
    (fem1d) relative. Every history has the length of ``time``."""
    problem, result = _solve_ball(method, stations=(0.5,), gauges=(BALL_GAUGE,))
    assert result.success and result.status == "completed", result.message
    rod = problem.rod
    c, ea, x = rod.wave_speed, rod.material.youngs_modulus_pa * rod.area_m2, BALL_GAUGE.station_m
    end = result.contact_end_s[-1]
    until = (1 + RECORD_CONTACT_MARGIN) * end + (1 + RECORD_TRANSIT_MARGIN) * x / c
    assert result.extra["recorded_until_s"] == pytest.approx(until, rel=1e-12)
    assert until <= result.time[-1] < until + 2 * result.dt_s
    assert end + x / c < until < (2 * LENGTH - x) / c  # the pulse has passed; its reflection has not come
    strain = result.extra_series["gauge_strain"][0][:, 0]
    peak = np.max(np.abs(strain))
    assert peak > 0 and abs(strain[-1]) < 1e-2 * peak
    impulse = problem.mass_kg * (problem.velocity_m_s - result.rebound_velocity_m_s)
    assert result.rebound_velocity_m_s < 0
    assert np.trapezoid(strain, result.time) == pytest.approx(-impulse / ea, rel=rtol)
    n = len(result.time)
    for name in ("contact_force", "approach", "impactor_displacement", "impactor_velocity", "rod_end_displacement"):
        assert len(getattr(result, name)) == n, name
    for name, (values, _, _) in result.extra_series.items():
        assert len(values) == n, name
    # after the contact: no force, the impactor in free flight, the approach as the solver defines it
    after = result.time > end
    assert np.all(result.contact_force[after] == 0.0)
    np.testing.assert_allclose(result.impactor_velocity[after], result.rebound_velocity_m_s, rtol=1e-12)
    np.testing.assert_allclose(
        result.approach, result.impactor_displacement - result.rod_end_displacement, rtol=0, atol=1e-15
    )


@pytest.mark.parametrize("method", ["sem", "fem1d"])
def test_recording_leaves_the_contact_results_unchanged(method):
    """The same run with a gauge and the far end's velocity and without: the same contact
    results, bit for bit, and the same histories up to where the run without ends; only the
    recording run goes on, and says to when (``recorded_until_s``, the far end's transit)."""
    problem, plain = _solve_ball(method)
    _, recorded = _solve_ball(method, gauges=(BALL_GAUGE,), far_end_velocity=True)
    for name in CONTACT_RESULTS:
        np.testing.assert_array_equal(getattr(recorded, name), getattr(plain, name), err_msg=name)
    n = len(plain.time)
    assert len(recorded.time) > n and "recorded_until_s" not in plain.extra
    np.testing.assert_array_equal(recorded.time[:n], plain.time)
    np.testing.assert_array_equal(recorded.contact_force[:n], plain.contact_force)
    np.testing.assert_array_equal(recorded.rod_end_displacement[:n], plain.rod_end_displacement)
    until = record_until_s(plain.contact_end_s[-1], LENGTH, problem.rod.wave_speed)
    assert recorded.extra["recorded_until_s"] == until <= recorded.time[-1]


def test_the_time_limit_does_not_cut_the_record_short(monkeypatch):
    """fem1d on the fixed model rod with its time limit just beyond where the plain run ends
    (the contact estimate made 0.62 ms, max_time_factor 1.01: 0.626 ms, the plain run ends at
    0.60 ms): recording the far end's velocity, it goes on past the limit to
    1.02 t_end + 1.05 L/c (0.677 ms), still completed."""
    monkeypatch.setattr(ImpactProblem, "contact_time_estimate", lambda self: 6.2e-4)
    problem, options = model_problem("fixed"), FEM1DOptions(points_per_wavelength=50.0, max_time_factor=1.01)
    t_max = 1.01 * 6.2e-4
    plain = solve_fem1d(problem, options)
    assert plain.status == "completed" and plain.time[-1] < t_max
    recorded = solve_fem1d(problem, options, far_end_velocity=True)
    assert recorded.status == "completed", recorded.message
    assert recorded.extra["recorded_until_s"] > t_max
    assert recorded.time[-1] >= recorded.extra["recorded_until_s"]


def test_fem_axi_records_until_the_waves_have_passed_the_gauge():
    """The 10 mm ball on a fixed 0.2 m rod of radius 5 mm, coarse (4 elements across, 60 steps
    per contact), a point gauge at 0.1 m: the run goes on to 1.02 t_end + 1.05 x/c at the rod's
    bar speed (the continuum's slowest front that matters for the pulse's end), its contact
    results close to the run without (here the same continuum: equal but for the rebound, 1e-12);
    the mean strain's integral is the impulse over E A within 1e-3 (measured 3.8e-4) and the
    surface strain is back below 1 % of its peak (measured 0.64 %)."""
    problem = AxiImpact(BALL_MASS, 1.0, 5e-3, STEEL, "sphere", BALL_ROD_RADIUS, 0.2, STEEL, "fixed")
    options = FEMAxiOptions(elements_across=4, steps_per_contact=60)
    plain = solve_fem_axi(problem, options)
    gauge = Gauge(0.1)
    result = solve_fem_axi(problem, options, gauges=(gauge,))
    assert result.success and result.status == "completed", result.message
    c = math.sqrt(STEEL.youngs_modulus_pa / STEEL.density_kg_m3)
    until = record_until_s(result.contact_end_s[-1], gauge.station_m, c)
    assert result.extra["recorded_until_s"] == until
    assert until <= result.time[-1] < until + result.dt_s
    assert result.time[-1] > plain.time[-1] and "recorded_until_s" not in plain.extra
    assert result.contact_time_s == pytest.approx(plain.contact_time_s, rel=1e-3)
    assert np.max(result.peak_force_N) == pytest.approx(np.max(plain.peak_force_N), rel=1e-3)
    assert result.rebound_velocity_m_s == pytest.approx(plain.rebound_velocity_m_s, rel=1e-3)
    surface, mean = result.extra_series["gauge_strain"][0][:, 0], result.extra_series["gauge_mean_strain"][0][:, 0]
    assert abs(surface[-1]) < 1e-2 * np.max(np.abs(surface))
    ea = STEEL.youngs_modulus_pa * math.pi * BALL_ROD_RADIUS**2
    impulse = BALL_MASS * (1.0 - result.rebound_velocity_m_s)
    assert np.trapezoid(mean, result.time) == pytest.approx(-impulse / ea, rel=1e-3)


def test_the_cost_models_count_the_record_after_the_contact():
    """A 2 mm ball on the fixed 0.5 m rod recording the far end's velocity: the SEM stores the
    nodes to 1.02 t_c + 1.05 L/c (not stepped: the step budget's count is the same), fem1d
    steps there (beyond its end test, 3 t_c); a run that records nothing costs as before."""
    steel = {"youngs_modulus_pa": 2.1e11, "poisson_ratio": 0.3, "density_kg_m3": 7800.0}
    mass = 4.0 / 3.0 * math.pi * 1e-3**3 * STEEL.density_kg_m3

    def case(outputs):
        return {
            "id": "ball",
            "impactor": {"material": steel, "mass_kg": mass, "velocity_m_s": 1.0, "radius_m": 1e-3, "body": "sphere"},
            "rod": {"length_m": LENGTH, "area_m2": math.pi * 25e-6, "material": steel, "far_end": "fixed"},
            "outputs": outputs,
        }

    plain, recorded = case(["contact_force"]), case(["contact_force", "far_end_velocity"])
    transit = LENGTH / math.sqrt(steel["youngs_modulus_pa"] / steel["density_kg_m3"])
    sem_plain, sem_recorded = sem_cost(plain, SEMOptions()), sem_cost(recorded, SEMOptions())
    assert sem_recorded.steps_needed == sem_plain.steps_needed
    assert sem_recorded.steps - sem_plain.steps > transit / sem_plain.time_step_s
    fem_plain, fem_recorded = fem1d_cost(plain, FEM1DOptions()), fem1d_cost(recorded, FEM1DOptions())
    assert fem_recorded.steps - fem_plain.steps > 0.5 * transit / fem_plain.time_step_s
    assert fem_recorded.solve_s > fem_plain.solve_s


# -- the gauges' checks ----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("gauge", "field"),
    [
        (Gauge(-0.01), "station_m"),
        (Gauge(0.6), "station_m"),
        (Gauge(math.nan), "station_m"),
        (Gauge(0.25, -0.01), "gauge_length_m"),
        (Gauge(0.25, 0.6), "gauge_length_m"),  # longer than the rod
        (Gauge(0.01, 0.04), "gauge_length_m"),  # over the struck end
        (Gauge(0.49, 0.04), "gauge_length_m"),  # over the far end
    ],
)
def test_a_gauge_off_the_rod_is_refused_naming_its_field(gauge, field):
    with pytest.raises(GaugeError) as caught:
        gauge.check(LENGTH)
    assert caught.value.field == field
    with pytest.raises(GaugeError) as caught:  # the drivers check before any step
        solve_sem(model_problem(), SEMOptions(), gauges=[gauge])
    assert caught.value.field == field


def test_gauges_on_the_rod_and_their_settings():
    for gauge in (Gauge(0.0), Gauge(LENGTH), Gauge(0.02, 0.04), Gauge(0.48, 0.04), Gauge(0.25, LENGTH)):
        assert gauge.check(LENGTH) is gauge
    gauge = Gauge.from_settings({"station_m": 1, "gauge_length_m": 0.01, "file": "ignored.csv"})
    assert gauge == Gauge(1.0, 0.01) and gauge.ends() == pytest.approx((0.995, 1.005))
    assert Gauge.from_settings(gauge.as_settings()) == gauge
    assert Gauge.from_settings({"station_m": 0.1}).gauge_length_m == 0.0
    with pytest.raises(GaugeError) as caught:
        Gauge.from_settings({"gauge_length_m": 0.01})
    assert caught.value.field == "station_m"
    with pytest.raises(GaugeError) as caught:
        Gauge.from_settings({"station_m": 0.1, "gauge_length_m": "long"})
    assert caught.value.field == "gauge_length_m"
    with pytest.raises(GaugeError) as caught:
        solve_fem1d(model_problem(), FEM1DOptions(), gauges=[Gauge(0.6)])
    assert caught.value.field == "station_m"


# -- the outputs through the registry, the cost models and the store -------------------------


def _case(outputs: list[str]) -> dict:
    steel = {"youngs_modulus_pa": 2.1e11, "poisson_ratio": 0.3, "density_kg_m3": 7800.0}
    return {
        "id": "gauged",
        "impactor": {"material": steel, "mass_kg": 0.5, "velocity_m_s": 1.0, "radius_m": 0.01, "body": "cap"},
        "rod": {"length_m": LENGTH, "area_m2": 5e-5, "material": steel, "far_end": "free"},
        "gauges": [{"station_m": 0.05, "gauge_length_m": 0.0}, {"station_m": 0.1, "gauge_length_m": 0.01}],
        "outputs": outputs,
        "numerics": {"sem": {}, "fem_axi": {}},
    }


def test_the_registry_asks_for_gauges_only_when_the_outputs_list_them(tmp_path):
    plain, asked = _case(["contact_force"]), _case(["contact_force", "gauge_strain", "far_end_velocity"])
    sem = METHODS["sem"]
    result = sem.solve(plain, {})
    assert "gauge_strain" not in result.extra_series and "far_end_velocity" not in result.extra_series
    result = sem.solve(asked, {})
    series = result.series(asked["outputs"])
    assert series["gauge_strain"][0].shape == (len(result.time), 2)
    path = write_run(
        tmp_path / "run.h5",
        config={"id": "gauged"},
        method="sem",
        series=series,
        summary=result.summary(),
        wall_time_s=0.0,
        code_version="test",
    )
    stored = read_run(path)
    np.testing.assert_array_equal(stored.series["gauge_strain"], series["gauge_strain"][0])
    np.testing.assert_array_equal(stored.series["far_end_velocity"], series["far_end_velocity"][0])
    np.testing.assert_array_equal(stored.summary["gauge_x_m"], [0.05, 0.1])
    np.testing.assert_array_equal(stored.summary["gauge_length_m"], [0.0, 0.01])
    # the cost models count what is asked: the SEM's stored histories, fem_axi's longer continuum
    assert sem_cost(asked, SEMOptions()).mem_mib > sem_cost(plain, SEMOptions()).mem_mib
    assert fem_axi_dofs(asked) > fem_axi_dofs(plain)
