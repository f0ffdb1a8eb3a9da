"""The sensor stack (``hertz_stack``, :class:`~rodimpact.contact.stack.Stack`), against mathematics.

- a stack of one layer is the film: the same runs of sem, fem1d and fem_axi, and the same
  indentation curve of the calibrated law, to round-off;
- layers of vanishing thickness: the thin-layer law tends to Hertz's as sqrt(H) (its deficit
  is the series formula's first-order term), and the SEM run to the Hertz run;
- two layers of one material are one layer of their summed thickness: exactly in the
  thin-layer law; to round-off in the continuum's static indentation and in the calibrated
  law's contact time when the two meshes are the same, to their discretisation error when
  they are not;
- fem_axi converges through the sensor's 6 um electrodes (film_layers 1, 2, 4);
- the band's parameters of the sensor as built (jobs.sensor_band), and its corners by the
  analytic law's directions equal to those by the continuum's axes.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from typing import Any

import numpy as np
import pytest

from rodimpact.config.bodies import resolve_contact
from rodimpact.contact.film import FilmLayer, constrained_modulus
from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.contact.laws import build_law
from rodimpact.contact.stack import HertzStackLaw, Stack
from rodimpact.jobs.indentation import indentation_curve
from rodimpact.jobs.runner import run_case
from rodimpact.jobs.sensor_band import calibrated_time_us, sensor_band, stack_parameters, with_values
from rodimpact.model.materials import Material
from rodimpact.solvers.fem_axi.film_mesh import layer_elements
from rodimpact.solvers.fem_axi.indentation import static_indentation
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact

from helpers.paper import ALUMINIUM, STEEL

FILM = "ball_3.16mm-r10_l30_film"
FILM_CAL = "ball_3.16mm-r10_l30_film_cal"
SENSOR = "ball_3.16mm-r10_l30_sensor"
SENSOR_CAL = "ball_3.16mm-r10_l30_sensor_cal"

#: Table 2, row 1 (the shipped cases' ball): radius, mass, velocity.
RADIUS, MASS, VELOCITY = 1.58e-3, 1.30e-4, 0.3225


def _config_error(message: str, field: str | None = None) -> ValueError:
    return ValueError(f"{field}: {message}")


def stack_contact(law: str, layers: list[dict[str, Any]], area_m2: float | None, **more: Any) -> dict[str, Any]:
    """A ``contact`` block with a stack, resolved as the configuration resolves a case's."""
    given = {"law": law, **more, "stack": {"area_m2": area_m2, "source": "", "layers": layers}}
    return resolve_contact(given, {}, _config_error)["contact"]


def film_as_layer(film: dict[str, Any], name: str = "film", thickness_m: float | None = None) -> dict[str, Any]:
    """A case's resolved film as a stack's layer (its material resolved, ranges and all)."""
    h = film["thickness_m"] if thickness_m is None else thickness_m
    low, high = film["thickness_range_m"] if thickness_m is None else (0.5 * h, 1.5 * h)
    return {
        "name": name,
        "thickness_m": h,
        "thickness_range_m": [low, high],
        "material": film["material"],
        "source": "",
    }


def with_contact(case: dict[str, Any], contact: dict[str, Any] | None) -> dict[str, Any]:
    changed = copy.deepcopy(case)
    if contact is None:
        changed.pop("contact", None)
    else:
        changed["contact"] = contact
    return changed


def one_layer_stack_case(case: dict[str, Any]) -> dict[str, Any]:
    """The case with its film given as a stack of one layer (hertz_film -> hertz_stack; a
    tabulated law keeps its law and takes the stack instead of the film)."""
    contact = case["contact"]
    film = contact["film"]
    if contact["law"] == "tabulated":
        block = stack_contact("tabulated", [film_as_layer(film)], film["area_m2"], **{"from": contact["from"]})
    else:
        block = stack_contact("hertz_stack", [film_as_layer(film)], film["area_m2"])
    return with_contact(case, block)


# ------------------------------------------------------------------ 1. one layer is the film


@pytest.fixture(scope="module")
def film_and_one_layer(shipped_project):
    film = shipped_project.cases[FILM]
    return film, one_layer_stack_case(film)


def test_one_layer_stack_resolves_to_the_films_law(film_and_one_layer):
    """The resolved block is a hertz_stack law whose Stack is the film's (one layer, the film's
    area and constants), and its thin-layer law is the film law (k and c to the last bit)."""
    film_case, stack_case = film_and_one_layer
    assert stack_case["contact"]["law"] == "hertz_stack" and stack_case["id"] == film_case["id"]
    # the film's layer carries its area, the stack's layers leave it to the stack
    as_layer = [
        dataclasses.replace(layer, area_m2=None)
        for case in (stack_case, film_case)
        for layer in Stack.of(case["contact"]).layers
    ]
    assert len(as_layer) == 2 and as_layer[0] == as_layer[1]
    assert Stack.of(stack_case["contact"]).area_m2 == film_case["contact"]["film"]["area_m2"]
    imp, rod = film_case["impactor"], film_case["rod"]
    args = (imp["radius_m"], Material.from_mapping(imp["material"]), Material.from_mapping(rod["material"]))
    film_law, stack_law = build_law(film_case["contact"], *args), build_law(stack_case["contact"], *args)
    assert isinstance(stack_law, HertzStackLaw)
    assert (stack_law.k, stack_law.c, stack_law.thickness_m) == (film_law.k, film_law.c, film_law.thickness_m)


@pytest.mark.parametrize("method", ["sem", "fem1d", "fem_axi"])
def test_one_layer_stack_runs_as_the_film(film_and_one_layer, method):
    """sem, fem1d and fem_axi (~3 s a run) on the film case and on the same case with the film
    given as a stack of one layer: the same time grid, contact time and force history.

    rtol 1e-9: the two cases are the same numbers (the law's c from the one layer's own
    thickness and modulus; the continuum's one region of the film's constants and disc), so
    the runs agree to round-off; 1e-9 leaves room for a different order of summation only
    (measured: bitwise equal for all three methods)."""
    film_case, stack_case = film_and_one_layer
    film, stack = run_case(film_case, method), run_case(stack_case, method)
    assert film.success and stack.success and film.n_contacts >= 1
    assert stack.time.shape == film.time.shape
    np.testing.assert_allclose(stack.time, film.time, rtol=1e-9, atol=0.0)
    assert stack.contact_time_s == pytest.approx(film.contact_time_s, rel=1e-9)
    np.testing.assert_allclose(
        stack.contact_force, film.contact_force, rtol=1e-9, atol=1e-9 * float(film.contact_force.max())
    )


def test_one_layer_stack_indents_as_the_film(shipped_project):
    """The calibrated law's curve (fem_axi's static indentation, ~1 s each) of the film _cal
    case and of the same case with a stack of one layer: the same approaches and forces,
    rtol 1e-9 (the same mesh and the same materials: round-off; measured bitwise equal)."""
    film_case = shipped_project.cases[FILM_CAL]
    stack_case = one_layer_stack_case(film_case)
    assert stack_case["contact"]["law"] == "tabulated" and stack_case["contact"]["film"] is None
    film, stack = indentation_curve(film_case), indentation_curve(stack_case)
    for key in ("displacement_m", "approach_m", "force_N", "contact_radius_m"):
        np.testing.assert_allclose(stack.data[key], film.data[key], rtol=1e-9, atol=0.0)
    assert stack.summary["analytic_law"] == "hertz_stack" and film.summary["analytic_law"] == "hertz_film"


# ------------------------------------------------------------- 2. vanishing layers are Hertz


def _sensor_with_thickness(case: dict[str, Any], thickness_m: float) -> dict[str, Any]:
    """The sensor case with every layer ``thickness_m`` thick (ranges around it)."""
    changed = copy.deepcopy(case)
    for layer in changed["contact"]["stack"]["layers"]:
        layer["thickness_m"], layer["thickness_range_m"] = thickness_m, [0.5 * thickness_m, 1.5 * thickness_m]
    return changed


def test_vanishing_layers_are_hertz(shipped_project):
    """The sensor's four layers, each h thick (H = 4 h): with the approach alpha = (P/k)^(2/3)
    + (P/c)^(1/2), c = pi M_eff R / H, the force at a fixed approach falls short of Hertz's by
    eps = (3/2) (P/c)^(1/2) / alpha to first order, a deficit that goes as sqrt(H).

    At the rigid-impact approach of Hertz's law (alpha = 1.34 um, P = 5.0 N):
    - h = 1e-12 m: eps = 8.16e-4 (not 1e-6: the layers' share of the approach,
      (P H / (pi M_eff R))^(1/2) = 4.5e-10 m, is 3.4e-4 of alpha); the law's deficit is the
      first-order eps to rtol 5e-3 (the next term is O(eps) = 1e-3 of it; measured 5.4e-4);
    - h = 1e-20 m: Hertz's force to rtol 1e-6 (eps = 8.2e-8);
    - the deficit's slope in log H is 1/2 (abs 1e-3: the second-order term, eps <= 8e-4)."""
    sensor = shipped_project.cases[SENSOR]
    impactor = Material.from_mapping(sensor["impactor"]["material"])
    rod = Material.from_mapping(sensor["rod"]["material"])
    R = sensor["impactor"]["radius_m"]
    hertz = HertzLaw(hertz_constant(R, impactor, rod), R)
    alpha = hertz.rigid_impact(MASS, VELOCITY).max_approach_m
    p_hertz = hertz.force(alpha)

    def law(h: float) -> HertzStackLaw:
        return HertzStackLaw.from_bodies(_sensor_with_thickness(sensor, h)["contact"], R, impactor, rod)

    thin = law(1e-12)
    assert thin.k == hertz.k
    stack = Stack.of(_sensor_with_thickness(sensor, 1e-12)["contact"])
    m_eff = stack.thickness_m / sum(h.thickness_m / h.constrained_modulus_pa for h in stack.layers)
    first_order = 1.5 * math.sqrt(p_hertz * stack.thickness_m / (math.pi * m_eff * R)) / alpha
    deficit = 1.0 - thin.force(alpha) / p_hertz
    assert deficit == pytest.approx(first_order, rel=5e-3)
    assert deficit > 1e-4  # 1e-12 m layers are still far from Hertz at 1e-6
    assert law(1e-20).force(alpha) == pytest.approx(p_hertz, rel=1e-6)
    thicknesses = np.geomspace(1e-14, 1e-12, 3)
    deficits = [1.0 - law(h).force(alpha) / p_hertz for h in thicknesses]
    assert np.polyfit(np.log(thicknesses), np.log(deficits), 1)[0] == pytest.approx(0.5, abs=1e-3)


def test_vanishing_layers_run_as_hertz(shipped_project):
    """sem on the sensor case with four layers of 1e-20 m against the same case without a
    contact block (Hertz): the same step, and the contact time and peak force to rtol 1e-7.

    The tolerance: on a rigid rod the closed form lengthens the contact by 3.4e-8 (asserted
    below 1e-7 here); both runs take the same step (the step comes from that rigid contact
    time), so the runs differ by the law's effect, which the rod's compliance only dilutes
    (measured 3.4e-8 in contact time, 2.7e-8 in peak force)."""
    sensor = shipped_project.cases[SENSOR]
    thin_case = _sensor_with_thickness(sensor, 1e-20)
    hertz_case = with_contact(sensor, None)
    impactor = Material.from_mapping(sensor["impactor"]["material"])
    rod = Material.from_mapping(sensor["rod"]["material"])
    laws = [build_law(c.get("contact"), RADIUS, impactor, rod) for c in (thin_case, hertz_case)]
    rigid = [law.rigid_impact(MASS, VELOCITY).contact_time_s for law in laws]
    assert 0.0 < rigid[0] / rigid[1] - 1.0 < 1e-7
    thin, hertz = run_case(thin_case, "sem"), run_case(hertz_case, "sem")
    assert thin.dt_s == pytest.approx(hertz.dt_s, rel=1e-12)
    assert thin.contact_time_s == pytest.approx(hertz.contact_time_s, rel=1e-7)
    assert thin.peak_force_N[0] == pytest.approx(hertz.peak_force_N[0], rel=1e-7)


# --------------------------------------------------- 3. two layers of one material are one


def pvdf(thickness_m: float, name: str = "pvdf") -> FilmLayer:
    return FilmLayer(thickness_m, 3.0e9, 0.35, 1780.0, name=name)


def test_thin_layer_law_of_two_halves_is_the_one_layer_law():
    """14 + 14 um of PVDF against 28 um: the same H, M_eff and law (rtol 1e-12: the series
    sum H / (h/M + h/M) = M in two roundings). And the sensor's M_eff against the series sum
    by hand; the order of the layers does not matter (springs in series)."""
    two = Stack((pvdf(14e-6, "top"), pvdf(14e-6, "bottom")), 2.1e-5)
    one = Stack((pvdf(28e-6),), 2.1e-5)
    assert two.thickness_m == pytest.approx(one.thickness_m, rel=1e-12)
    assert two.constrained_modulus_pa == pytest.approx(one.constrained_modulus_pa, rel=1e-12)
    law_two, law_one = (s.thin_layer_law(RADIUS, STEEL, ALUMINIUM) for s in (two, one))
    assert law_two.k == law_one.k and law_two.c == pytest.approx(law_one.c, rel=1e-12)
    for alpha in (1e-8, 3e-7, 2e-6):
        assert law_two.force(alpha) == pytest.approx(law_one.force(alpha), rel=1e-12)
    # four layers of three materials: M_eff = H / sum(h_i / M_i)
    ink, glue = FilmLayer(6e-6, 1e10, 0.37, 4000.0), FilmLayer(15e-6, 2e9, 0.35, 1100.0)
    sensor = Stack((ink, pvdf(28e-6), ink, glue))
    compliance = (
        2 * 6e-6 / constrained_modulus(1e10, 0.37)
        + 28e-6 / constrained_modulus(3e9, 0.35)
        + 15e-6 / constrained_modulus(2e9, 0.35)
    )
    assert sensor.constrained_modulus_pa == pytest.approx(55e-6 / compliance, rel=1e-12)
    reversed_law = Stack(tuple(reversed(sensor.layers))).thin_layer_law(RADIUS, STEEL, ALUMINIUM)
    assert reversed_law.c == pytest.approx(sensor.thin_layer_law(RADIUS, STEEL, ALUMINIUM).c, rel=1e-12)


def test_continuum_indents_two_halves_as_one_layer():
    """fem_axi's static indentation (the Table-2 ball as a cap on the 30.1 mm rod, six
    displacements up to 1.5 times the rigid-impact approach; ~9 s in all):

    - 14 + 14 um at film_layers=2 and 28 um at film_layers=4 are the same mesh (4 elements of
      7 um, the interface one of the 28 um layer's element boundaries) and the same materials:
      the same forces to rtol 1e-9 (round-off; measured 2e-15);
    - 14 + 14 um and 28 um both at film_layers=4 differ by their discretisation (8 elements of
      3.5 um against 4 of 7 um): rtol 5e-3. Measured 2.1e-3 (largest at the smallest load);
      the 28 um layer itself moves by 2.1e-3 from 4 to 8 elements and by 7.5e-4 from 8 to 16
      (a converging sequence whose 4-element error is ~3e-3 of its limit)."""

    def problem(stack: Stack) -> AxiImpact:
        return AxiImpact(MASS, VELOCITY, RADIUS, STEEL, "cap", 0.01, 0.0301, ALUMINIUM, "fixed", stack=stack)

    two = Stack((pvdf(14e-6, "top half"), pvdf(14e-6, "bottom half")), 2.1e-5)
    one = Stack((pvdf(28e-6),), 2.1e-5)
    assert problem(two).law.c == pytest.approx(problem(one).law.c, rel=1e-12)  # the same mesh scales
    d = problem(one).rigid_contact.max_approach_m * np.geomspace(0.05, 1.5, 6)
    one_4 = static_indentation(problem(one), d, FEMAxiOptions(film_layers=4))
    two_2 = static_indentation(problem(two), d, FEMAxiOptions(film_layers=2))
    two_4 = static_indentation(problem(two), d, FEMAxiOptions(film_layers=4))
    assert np.all(one_4.force_N > 0) and np.all(np.diff(one_4.force_N) > 0)
    np.testing.assert_allclose(two_2.force_N, one_4.force_N, rtol=1e-9, atol=0.0)
    np.testing.assert_allclose(two_4.force_N, one_4.force_N, rtol=5e-3, atol=0.0)
    assert not np.allclose(two_4.force_N, one_4.force_N, rtol=1e-6, atol=0.0)  # the meshes do differ


def test_calibrated_time_of_two_halves_is_the_films(shipped_project):
    """The calibrated SEM's contact time (jobs.sensor_band.calibrated_time_us, ~2-5 s each) of
    the film _cal case, and of it with the film as two 14 um layers of its PVDF:

    - at film_layers=2 for the halves (the film's mesh at the default 4): rtol 1e-9, the same
      curve to round-off (measured 1e-16);
    - both at the default film_layers=4: rtol 1e-3. The curves' forces differ by at most
      2.1e-3 (the previous test), and the contact time goes as a stiffness to the power -2/5
      (Hertz's T ~ k^(-2/5)), so by at most 8.5e-4; measured 1.1e-5 (28.5886 us)."""
    film_case = shipped_project.cases[FILM_CAL]
    film = film_case["contact"]["film"]
    halves = [film_as_layer(film, "top half", 14e-6), film_as_layer(film, "bottom half", 14e-6)]
    two_case = with_contact(
        film_case, stack_contact("tabulated", halves, film["area_m2"], **{"from": film_case["contact"]["from"]})
    )
    reference = calibrated_time_us(film_case)
    assert 20.0 < reference < 40.0
    assert calibrated_time_us(two_case, {"film_layers": 2}) == pytest.approx(reference, rel=1e-9)
    assert calibrated_time_us(two_case) == pytest.approx(reference, rel=1e-3)


# ------------------------------------------------ 4. fem_axi converges through the electrodes


@pytest.fixture(scope="module")
def sensor_runs(shipped_project):
    """fem_axi on the sensor as built at film_layers 1, 2 and 4 (the default): ~4-10 s each."""
    runs = {}
    for layers in (1, 2, 4):
        case = copy.deepcopy(shipped_project.cases[SENSOR])
        case["numerics"]["fem_axi"]["film_layers"] = layers
        runs[layers] = run_case(case, "fem_axi")
    return runs


def test_fem_axi_converges_through_the_sensors_layers(shipped_project, sensor_runs):
    """The sensor's stack (6 um electrodes, 28 um PVDF, 15 um bond line) at film_layers 1, 2
    and 4: 4, 6 and 9 elements through its 55 um (the layering rule: n through the thickest,
    every other layer as many as make its elements at most 28/n um high, at least one).
    Contact time and peak force agree within 1 % of the default's (the brief's tolerance).

    Observed: the contact time is 33.904 us at all three (bitwise: the end falls in the same
    step, 264 steps of 0.128 us; a step is 0.38 % of it, so this comparison resolves two
    steps); peak force 5.04479, 5.04471, 5.04470 N (1.8e-5 and 2.5e-6 from the default).
    The force histories, on one time grid (the step comes from the law, not the mesh), agree
    to 1 % of the peak at every step too (measured 7.1e-4 and 1.0e-4 of the peak)."""
    thicknesses = [layer["thickness_m"] for layer in shipped_project.cases[SENSOR]["contact"]["stack"]["layers"]]
    reference = sensor_runs[4]
    for layers, run in sensor_runs.items():
        assert run.success and run.n_contacts == 1
        assert run.extra["film_elements_through_thickness"] == sum(layer_elements(thicknesses, layers))
        assert run.contact_time_s == pytest.approx(reference.contact_time_s, rel=1e-2)
        assert run.contact_force.max() == pytest.approx(reference.contact_force.max(), rel=1e-2)
        assert run.time.shape == reference.time.shape and run.dt_s == reference.dt_s
        assert np.abs(run.contact_force - reference.contact_force).max() < 1e-2 * reference.contact_force.max()
    assert [sum(layer_elements(thicknesses, n)) for n in (1, 2, 4)] == [4, 6, 9]


# ------------------------------------------------------------ 5. the band's parameters


def test_stack_parameters_of_the_sensor(shipped_project):
    """The sensor as built: one thickness for the two electrodes (one print), one for the film,
    one for the bond line, then each range of each material once (silver_ink is two layers'),
    each with its nominal value and range from the case."""
    case = shipped_project.cases[SENSOR_CAL]
    layers = case["contact"]["stack"]["layers"]
    parameters = stack_parameters(case)
    names = [p.name for p in parameters]
    assert len(names) == len(set(names))
    assert names[:3] == [
        "silver-ink electrode: thickness_m",
        "piezo film (PVDF): thickness_m",
        "bond line (cyanoacrylate): thickness_m",
    ]
    by_name = {p.name: p for p in parameters}
    for layer in layers:
        p = by_name[f"{layer['name']}: thickness_m"]
        assert (p.nominal, [p.low, p.high]) == (layer["thickness_m"], layer["thickness_range_m"])
    materials = {layer["material"]["name"]: layer["material"] for layer in layers}
    expected = {
        f"{name}: {constant}": (material[constant], *bounds)
        for name, material in materials.items()
        for constant, bounds in material.get("ranges", {}).items()
    }
    assert {
        "silver_ink: youngs_modulus_pa",
        "pvdf: youngs_modulus_pa",
        "pvdf: poisson_ratio",
        "cyanoacrylate: youngs_modulus_pa",
    } <= set(expected)
    assert {n: (p.nominal, p.low, p.high) for n, p in by_name.items() if not n.endswith("thickness_m")} == expected
    for p in parameters:
        assert p.low < p.high and p.low <= p.nominal <= p.high


def test_with_values_changes_both_electrodes_and_not_the_case(shipped_project):
    """with_values: the electrodes' thickness and the ink's modulus change in both electrode
    layers (and nothing else); the source case is untouched; the stack's total thickness and
    M_eff follow (series sum by hand, rtol 1e-12); an unknown name is a KeyError; electrodes
    of different thicknesses cannot share a parameter."""
    case = shipped_project.cases[SENSOR_CAL]
    pristine = copy.deepcopy(case)
    changed = with_values(case, {"silver-ink electrode: thickness_m": 1.0e-5, "silver_ink: youngs_modulus_pa": 2.0e10})
    assert case == pristine
    old, new = case["contact"]["stack"]["layers"], changed["contact"]["stack"]["layers"]
    for before, after in zip(old, new):
        if before["name"] == "silver-ink electrode":
            assert after["thickness_m"] == 1.0e-5 and after["material"]["youngs_modulus_pa"] == 2.0e10
            assert after["thickness_range_m"] == before["thickness_range_m"]
        else:
            assert after == before
    assert sum(layer["name"] == "silver-ink electrode" for layer in new) == 2
    stack = Stack.of(changed["contact"])
    assert stack.thickness_m == pytest.approx(2 * 1e-5 + 28e-6 + 15e-6, rel=1e-12)
    compliance = sum(
        layer["thickness_m"]
        / constrained_modulus(layer["material"]["youngs_modulus_pa"], layer["material"]["poisson_ratio"])
        for layer in new
    )
    assert stack.constrained_modulus_pa == pytest.approx(stack.thickness_m / compliance, rel=1e-12)
    # the changed case's parameters read the new nominal values
    assert {p.name: p.nominal for p in stack_parameters(changed)}["silver-ink electrode: thickness_m"] == 1.0e-5
    with pytest.raises(KeyError, match="no constant"):
        with_values(case, {"gold electrode: thickness_m": 1e-6})
    uneven = copy.deepcopy(case)
    uneven["contact"]["stack"]["layers"][2]["thickness_m"] = 8e-6
    with pytest.raises(ValueError, match="differ in thickness or range"):
        stack_parameters(uneven)


def test_the_bands_corners_by_the_analytic_law_are_the_continuums(shipped_project, tmp_path):
    """The default band takes each constant's lengthening end from the stack's analytic law
    (jobs.sensor_band.law_longer_high); make sensor-axes reads it from the continuum's own axis.
    On the heaviest ball, on a coarse continuum (elements_across 4, ~11 s for both), the time is
    monotone along every range, the two give the same end for every constant, so the same corners
    and the same band to the bit; the band file keeps the axes only when computed, and the axes'
    table says the same."""
    from rodimpact.present.sensor_tables import band_axes_frame
    from rodimpact.storage.bands import read_band, write_band

    case = shipped_project.cases["ball_12.73mm-r10_l30_sensor_cal"]
    coarse = {**shipped_project.config["numerics"]["fem_axi"], "elements_across": 4}
    with_axes, by_law = sensor_band(case, coarse, axes=True), sensor_band(case, coarse)
    continuum = tuple(bool(with_axes.axis_us[n][-1] >= with_axes.axis_us[n][0]) for n in with_axes.parameters)
    assert with_axes.monotone and by_law.monotone is None and not by_law.axis_us
    assert with_axes.law_longer_high == by_law.law_longer_high == continuum
    np.testing.assert_array_equal(with_axes.corner_parameters, by_law.corner_parameters)
    np.testing.assert_array_equal(with_axes.corner_us, by_law.corner_us)
    for band in (with_axes, by_law):
        write_band(tmp_path / "band.h5", [band], variant="v", method="sem", config={})
        (read,) = read_band(tmp_path / "band.h5")[1]
        assert read.monotone == band.monotone and read.law_longer_high == band.law_longer_high
        (tmp_path / "band.h5").unlink()
    frame = band_axes_frame([("v", with_axes), ("v", by_law)], {})
    assert len(frame) == len(with_axes.parameters) and frame["monotone"].all() and frame["agree"].all()
