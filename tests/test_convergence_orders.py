"""The orders of convergence: the solvers at the shipped levels against their expected orders,
and the columns of the orders table on synthetic frames (rodimpact.analysis.work_precision)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from rodimpact.analysis.signals import first_contact_maxima
from rodimpact.analysis.studies import level_case
from rodimpact.analysis.work_precision import (
    ORDER_TOLERANCE,
    _history,
    expected_order,
    levels_in,
    observed_orders,
    work_precision_frame,
)
from rodimpact.contact.spring import semi_infinite_rod_contact
from rodimpact.jobs.runner import run_case, run_to_file
from rodimpact.model.materials import Material, wave_speed
from rodimpact.storage.runs import read_run

WINDOW = 0.02


# ------------------------------------------------------------------ the solvers at the shipped levels

#: fem1d's levels run on model: the four the table fits its contact time on (400 to 3200 steps
#: per contact; at 6400 the contact time's error falls below 10 times the reference's).
FEM1D_LEVELS = slice(2, 6)


def _level_runs(project, config, case_id: str, fem1d_levels: slice, folder) -> list:
    """The stored runs of sem at every shipped level and of fem1d at ``fem1d_levels`` on a case."""
    records = []
    for method in ("sem", "fem1d"):
        levels = list(enumerate(config["work_precision"]["methods"][method]["levels"]))
        for level, overrides in levels[fem1d_levels] if method == "fem1d" else levels:
            case = level_case(project.cases[case_id], method, config["numerics"], overrides)
            records.append(read_run(run_to_file(case, method, folder / f"{method}_{level}.h5", level=level)))
    return records


def assert_stated_orders(stated, method: str) -> None:
    """Every stated order of ``stated`` (rows by quantity) fitted on at least three levels above the
    reference's floor, observed within ORDER_TOLERANCE of it, on monotone errors."""
    for quantity, row in stated.iterrows():
        assert row["fitted_levels"], (method, quantity)
        assert abs(row["observed_order"] - row["expected_order"]) <= ORDER_TOLERANCE, (
            method,
            quantity,
            row["observed_order"],
            row["expected_order"],
        )
        assert row["monotone"], (method, quantity)


@pytest.fixture(scope="module")
def model_orders(shipped_project, shipped_config, tmp_path_factory):
    """sem at every shipped level and fem1d at four, on model, fitted as the table fits them."""
    study = shipped_config["work_precision"]
    methods = {name: dict(study["methods"][name]) for name in ("sem", "fem1d")}
    records = _level_runs(shipped_project, shipped_config, "model", FEM1D_LEVELS, tmp_path_factory.mktemp("orders"))
    frame = work_precision_frame(records, methods)
    return observed_orders(frame, methods, study["fit_levels"], arrival_window=study["arrival_window"])


@pytest.mark.parametrize("method", ["sem", "fem1d"])
def test_every_stated_order_is_observed_within_its_tolerance(model_orders, method) -> None:
    rows = model_orders[model_orders["method"] == method].set_index("quantity")
    stated = rows[rows["expected_order"].notna()]
    # on model no maximum lies at a wave arrival: every quantity has its order, none is left out
    assert set(stated.index) == {"contact_time", "max_1", "max_2", "max_3", "history_l2", "history_max"}
    assert_stated_orders(stated, method)


def test_fem1d_errors_keep_one_sign_at_the_shipped_levels(model_orders) -> None:
    # mesh and step refined together at Courant number 1: the step's error dominates, no zero crossing
    rows = model_orders[(model_orders["method"] == "fem1d") & model_orders["sign_change"].notna()]
    assert len(rows) == 4 and not rows["sign_change"].astype(bool).any(), rows


#: fem1d's levels run on the smooth case: levels 1 to 5 (the table fits its maximum and its
#: history norms on 2-5; level 6 alone takes 14 s).
SMOOTH_FEM1D_LEVELS = slice(1, 6)


@pytest.fixture(scope="module")
def smooth_orders(shipped_project, shipped_config, tmp_path_factory):
    """sem at every shipped level and fem1d at five on the smooth case (config/cases/smooth.yaml),
    fitted as the table fits them, with the case's own expected orders."""
    study = shipped_config["work_precision"]
    records = _level_runs(
        shipped_project, shipped_config, "linear_spring", SMOOTH_FEM1D_LEVELS, tmp_path_factory.mktemp("smooth")
    )
    # every swept method's settings, as the workflow passes them: the case runs two of them
    frame = work_precision_frame(records, study["methods"])
    orders = observed_orders(
        frame, study["methods"], study["fit_levels"], arrival_window=study["arrival_window"], per_case=study["per_case"]
    )
    return SimpleNamespace(records=records, frame=frame, orders=orders)


def test_the_smooth_cases_reference_is_its_closed_form(smooth_orders, shipped_project) -> None:
    """The Richardson extrapolation of sem's finest two levels against the damped oscillator's
    closed form (rodimpact.contact.spring): measured 6e-14 in contact time, 3e-12 in the peak,
    far inside the reference's own estimate (the finest level's error, 1.6e-9)."""
    case = shipped_project.cases["linear_spring"]
    rod = Material.from_mapping(case["rod"]["material"])
    exact = semi_infinite_rod_contact(
        case["contact"]["stiffness_n_per_m"],
        case["impactor"]["mass_kg"],
        case["impactor"]["velocity_m_s"],
        rod.density_kg_m3 * wave_speed(rod) * case["rod"]["area_m2"],
    )
    sem = [r for r in smooth_orders.records if r.method == "sem"]
    coarse, fine = (r.summary for r in sem[-2:])
    for key, value in (("contact_time_s", exact.contact_time_s), ("peak_force_N", exact.peak_force_N)):
        q2, q1 = float(np.max(coarse[key])), float(np.max(fine[key]))
        assert q1 + (q1 - q2) / 3.0 == pytest.approx(value, rel=1e-11), key
    assert smooth_orders.frame.query("method == 'sem'")["ref_err_contact_time"].iloc[0] == pytest.approx(
        1.6e-9, rel=0.05
    )


@pytest.mark.parametrize("method", ["sem", "fem1d"])
def test_the_smooth_case_shows_the_formal_order_in_every_stated_norm(smooth_orders, method) -> None:
    rows = smooth_orders.orders[smooth_orders.orders["method"] == method].set_index("quantity")
    stated = rows[rows["expected_order"].notna()]
    # the history's max norm included: 2 here, against 3/2 on model (the force's t^(3/2) onset)
    assert {"max_1", "history_l2", "history_max"} <= set(stated.index)
    assert (stated["expected_order"] == 2).all()
    for quantity, row in stated.iterrows():
        assert row["fitted_levels"], (method, quantity)
        assert abs(row["observed_order"] - 2) <= ORDER_TOLERANCE, (method, quantity, row["observed_order"])
        assert row["monotone"], (method, quantity)


#: fem1d's levels run on the Thornton case: levels 1 to 5 (the table fits its contact time and
#: its max norm on 1-4, its L2 norm on 2-5; level 6 alone takes 6 s).
THORNTON_FEM1D_LEVELS = slice(1, 6)


@pytest.fixture(scope="module")
def thornton_orders(shipped_project, shipped_config, tmp_path_factory):
    """sem at every shipped level and fem1d at five on Thornton's law past yield
    (config/cases/plastic.yaml), fitted as the table fits them, with the case's own orders."""
    study = shipped_config["work_precision"]
    records = _level_runs(
        shipped_project,
        shipped_config,
        "thornton_past_yield",
        THORNTON_FEM1D_LEVELS,
        tmp_path_factory.mktemp("thornton"),
    )
    frame = work_precision_frame(records, study["methods"])
    orders = observed_orders(
        frame, study["methods"], study["fit_levels"], arrival_window=study["arrival_window"], per_case=study["per_case"]
    )
    return SimpleNamespace(records=records, frame=frame, orders=orders)


def test_the_thornton_case_yields_and_turns_inside_one_contact(thornton_orders) -> None:
    """Both points where the law is not smooth lie inside the first contact, and no wave returns
    during it: the approach passes the yield approach, rises and falls once, and the contact ends
    before 2L/c."""
    finest = [r for r in thornton_orders.records if r.method == "sem"][-1]
    assert finest.summary["approach_over_yield"] > 2.0  # 2.5 at the finest level
    time, approach = np.asarray(finest.series["time"]), np.asarray(finest.series["approach"])
    end = float(np.atleast_1d(finest.summary["contact_end_s"])[0])
    rise = np.diff(approach[time <= end])
    turn = int(np.argmax(approach[time <= end]))
    assert (rise[:turn] > 0).all() and (rise[turn:] < 0).all()
    rod = finest.config["rod"]
    assert end < 2.0 * rod["length_m"] / wave_speed(Material.from_mapping(rod["material"]))


@pytest.mark.parametrize("method", ["sem", "fem1d"])
def test_thorntons_law_keeps_the_elastic_orders_off_its_maximum(thornton_orders, method) -> None:
    """A jump of d2P/dt2 at the yield point and at the unloading turn leaves the second-order
    schemes at 2, and the Hertz start at 3/2 in the max norm; the maximum has no order stated."""
    rows = thornton_orders.orders[thornton_orders.orders["method"] == method].set_index("quantity")
    stated = rows[rows["expected_order"].notna()]
    assert set(stated.index) == {"contact_time", "history_l2", "history_max"}
    assert rows.loc["max_1", "within_expected"] is None
    assert_stated_orders(stated, method)


#: Resolutions (steps per Hertz time) between the study's levels, 8 apart: the unloading turn
#: falls at every phase of its step.
PHASE_SCAN = {"sem": range(800, 961, 8), "fem1d": range(400, 465, 8)}


@pytest.mark.parametrize("method", ["sem", "fem1d"])
def test_the_error_at_thorntons_unloading_turn_depends_on_where_it_falls_in_its_step(
    thornton_orders, shipped_project, shipped_config, method
) -> None:
    """The force's maximum lies at the unloading turn, where d2P/dt2 jumps: its error is
    c h^2 with a c set by where the turn falls inside its step. Over resolutions 8 apart, c of
    the maximum varies more than fourfold (sem: 0.10 to 0.97 in n^2 x the relative error) or
    changes sign (fem1d: -0.09 to 0.74), so a doubling of n can leave the error larger and no
    order can be fitted; c of the contact time keeps one sign and varies less than fourfold
    (sem: -0.30 to -0.46; fem1d: -0.18 to -0.35), so its error falls at every doubling."""
    coarse, fine = (r.summary for r in [r for r in thornton_orders.records if r.method == "sem"][-2:])

    def scalars(summary) -> tuple[float, float]:
        maxima = first_contact_maxima(summary["peak_time_s"], summary["peak_force_N"], summary["contact_end_s"])
        return float(summary["contact_time_s"]), float(maxima[0])

    reference = [q1 + (q1 - q2) / 3.0 for q2, q1 in zip(scalars(coarse), scalars(fine), strict=True)]
    case = shipped_project.cases["thornton_past_yield"]
    coefficients = []
    for n in PHASE_SCAN[method]:
        overrides = {"steps_per_contact": n} | ({"points_per_wavelength": float(n)} if method == "fem1d" else {})
        result = run_case(level_case(case, method, shipped_config["numerics"], overrides), method)
        summary = {
            "contact_time_s": result.contact_time_s,
            "peak_time_s": result.peak_time_s,
            "peak_force_N": result.peak_force_N,
            "contact_end_s": result.contact_end_s,
        }
        coefficients.append([n * n * (q / ref - 1.0) for q, ref in zip(scalars(summary), reference, strict=True)])
    contact_time, maximum = np.asarray(coefficients).T
    # the ranges docs/studies.md quotes (pytest -rP prints them)
    print(
        f"{method}: n^2 x relative error, maximum {maximum.min():+.2f} to {maximum.max():+.2f}, "
        f"contact time {contact_time.min():+.2f} to {contact_time.max():+.2f}"
    )
    assert np.abs(coefficients).max() < 1.2  # O(h^2) in both: c bounded
    assert maximum.min() <= 0.0 or maximum.max() > 4.0 * maximum.min(), maximum
    # one sign (negative), and its largest |c| under four times its smallest
    assert (contact_time < 0).all() and contact_time.min() > 4.0 * contact_time.max(), contact_time


def test_a_history_is_linear_between_its_nodes_and_its_located_contact_end() -> None:
    """A run whose step holds the contact's end (fem1d) has P = 0 at the end it located, not a
    ramp down to its next node: the history's kink is where the run put it."""
    end = 1.05
    run = SimpleNamespace(
        series={"time": np.array([0.0, 0.5, 1.0, 1.5, 2.0]), "contact_force": np.array([0.0, 1.0, 0.1, 0.0, 0.0])},
        summary={"contact_start_s": np.array([0.0]), "contact_end_s": np.array([end])},
    )
    grid = np.array([0.25, 1.0, 1.025, end, 1.25])
    assert np.allclose(_history(run, grid), [0.5, 0.1, 0.05, 0.0, 0.0], rtol=1e-14, atol=0)


# ------------------------------------------------------------------ the table's columns, synthetic


def _frame(
    method: str,
    resolutions,
    errors: dict[str, list[float]],
    *,
    floor: float = 1e-12,
    offsets: dict[str, float] | None = None,
    case_id: str = "c",
) -> pd.DataFrame:
    """Rows of one method: signed errors per scalar quantity (their magnitudes are the errors)."""
    rows = []
    for level, n in enumerate(resolutions):
        row = {"case_id": case_id, "method": method, "level": level, "resolution_value": float(n)}
        for quantity, values in errors.items():
            row[f"err_{quantity}"] = abs(values[level])
            row[f"ref_err_{quantity}"] = floor
            if not quantity.startswith("history"):
                row[f"signed_err_{quantity}"] = values[level]
        row.update({f"arrival_offset_{q}": v for q, v in (offsets or {}).items()})
        rows.append(row)
    return pd.DataFrame(rows)


SPEC = {
    "reference": "sem",
    "expected_orders": {"contact_time": 2, "max": 2, "max_at_arrival": 5 / 3, "history_l2": 2, "history_max": 1.5},
}


def _orders(frame: pd.DataFrame, methods: dict, fit_levels: int = 4) -> pd.DataFrame:
    return observed_orders(frame, methods, fit_levels, arrival_window=WINDOW).set_index(["method", "quantity"])


def test_a_power_law_is_fitted_on_the_finest_levels_with_its_standard_error() -> None:
    n = np.array([100, 200, 400, 800, 1600, 3200])
    frame = _frame("m", n, {"contact_time": list(3.0 / n**2), "history_max": list(0.5 / n**1.5)})
    row = _orders(frame, {"m": SPEC}).loc[("m", "contact_time")]
    assert row["observed_order"] == pytest.approx(2.0, rel=1e-12) and row["order_stderr"] == pytest.approx(0, abs=1e-9)
    assert row["fitted_levels"] == "2-5" and levels_in(row["fitted_levels"]) == {2, 3, 4, 5}
    assert row["monotone"] and not row["sign_change"] and row["within_expected"] and row["asymptotic"]
    history = _orders(frame, {"m": SPEC}).loc[("m", "history_max")]
    assert history["expected_order"] == 1.5 and history["observed_order"] == pytest.approx(1.5, rel=1e-12)
    assert history["sign_change"] is None  # a norm has no sign


def test_sign_changes_non_monotone_errors_and_a_level_below_the_floor_are_reported() -> None:
    n = np.array([100, 200, 400, 800, 1600])
    alternating = [(-1) ** k * 3.0 / m**2 for k, m in enumerate(n)]
    zigzag = [1e-3, 2e-4, 4e-4, 5e-5, 6e-5]  # 400 and 1600 worse than the level before
    below = [1e-3, 2.5e-4, 1e-11, 1.6e-5, 4e-6]  # 400 crosses zero: its error is under the floor
    frame = _frame("m", n, {"contact_time": alternating, "max_1": zigzag, "max_2": below}, floor=1e-12)
    orders = _orders(frame, {"m": SPEC})
    crossing = orders.loc[("m", "contact_time")]
    assert crossing["sign_change"] and crossing["monotone"] and crossing["observed_order"] == pytest.approx(2.0)
    wandering = orders.loc[("m", "max_1")]
    assert not wandering["monotone"] and not wandering["asymptotic"] and not wandering["sign_change"]
    assert orders.loc[("m", "max_2"), "fitted_levels"] == "0-1, 3-4"
    assert levels_in("0-1, 3-4") == {0, 1, 3, 4} and levels_in("") == set()
    # fewer than three levels above ten times the floor: no order, no verdict
    few = _orders(_frame("m", n, {"contact_time": list(3.0 / n**2)}, floor=3.0 / 400**2 / 10 * 1.01), {"m": SPEC}).loc[
        ("m", "contact_time")
    ]
    assert math.isnan(few["observed_order"]) and few["fitted_levels"] == "" and few["within_expected"] is None


def test_an_order_outside_the_tolerance_is_not_within_the_expected() -> None:
    n = np.array([100, 200, 400, 800])
    frame = _frame("m", n, {"contact_time": list(3.0 / n**1.6), "max_1": list(3.0 / n**1.75)})
    orders = _orders(frame, {"m": SPEC})
    assert not orders.loc[("m", "contact_time"), "within_expected"]  # 1.6 against 2
    assert orders.loc[("m", "max_1"), "within_expected"] and orders.loc[("m", "max_1"), "asymptotic"]


def test_a_case_of_per_case_takes_its_own_expected_orders_and_the_others_the_methods() -> None:
    n = np.array([100, 200, 400, 800])
    errors = {"contact_time": list(1.0 / n**2), "history_max": list(1.0 / n**2)}
    frame = pd.concat([_frame("m", n, errors, case_id="rough"), _frame("m", n, errors, case_id="smooth")])
    per_case = {"smooth": {"methods": ["m"], "expected_orders": {"m": {"contact_time": None, "history_max": 2}}}}
    orders = observed_orders(frame, {"m": SPEC}, 4, arrival_window=WINDOW, per_case=per_case)
    orders = orders.set_index(["case_id", "quantity"])
    assert orders.loc[("rough", "history_max"), "expected_order"] == 1.5  # the method's own
    assert not orders.loc[("rough", "history_max"), "within_expected"]  # 2 observed against 1.5 + 0.3
    assert orders.loc[("smooth", "history_max"), "expected_order"] == 2
    assert orders.loc[("smooth", "history_max"), "within_expected"]
    assert math.isnan(orders.loc[("smooth", "contact_time"), "expected_order"])  # replaced, not merged
    assert orders.loc[("smooth", "contact_time"), "within_expected"] is None


def test_a_maximum_at_a_wave_arrival_takes_its_own_expected_order() -> None:
    n = np.array([100, 200, 400, 800])
    errors = {f"max_{k}": list(1.0 / n**2) for k in (1, 2, 3)}
    frame = _frame("m", n, errors, offsets={"max_1": 0.0005, "max_2": -0.019, "max_3": 0.3})
    orders = _orders(frame, {"m": SPEC, "plain": {**SPEC, "expected_orders": {"max": 2}}})
    assert orders.loc[("m", "max_1"), "expected_order"] == pytest.approx(5 / 3)
    assert orders.loc[("m", "max_2"), "expected_order"] == pytest.approx(5 / 3)
    assert orders.loc[("m", "max_3"), "expected_order"] == 2
    assert orders.loc[("m", "max_1"), "arrival_offset"] == 0.0005
    # a method that states no order at an arrival keeps `max` there; no order stated: NaN
    assert expected_order({"expected_orders": {"max": 2}}, "max_1", at_arrival=True) == 2
    assert math.isnan(expected_order({"expected_orders": {"max": None}}, "max_1"))
    assert math.isnan(expected_order({}, "contact_time"))


def test_a_quantity_a_method_does_not_have_gets_no_row() -> None:
    n = np.array([100, 200, 400])
    frame = _frame("m", n, {"contact_time": list(1.0 / n**2), "max_4": [math.nan] * 3})
    assert ("m", "max_4") not in _orders(frame, {"m": SPEC}).index


AXI = {"reference": "axi", "as_reference": "finest", "expected_orders": {"contact_time": None}}


def test_a_method_measured_against_its_finest_level_gets_its_grid_convergence_index() -> None:
    # f = f0 (1 + C h^1.5) on 5, 10, 20: signed errors against the finest level f1
    n = np.array([5.0, 10.0, 20.0])
    f = 1.0 + 0.02 * (1.0 / n) ** 1.5
    oscillating = np.array([1.004, 0.999, 1.001])
    frame = _frame(
        "axi",
        n,
        {
            "contact_time": list(f / f[-1] - 1.0),
            "max_1": list(oscillating / oscillating[-1] - 1.0),
            "history_l2": [1e-2, 3e-3, 0.0],
        },
    )
    orders = _orders(frame, {"axi": AXI})
    monotone = orders.loc[("axi", "contact_time")]
    f0 = 1.0  # the exact value the extrapolation recovers
    assert monotone["gci_order"] == pytest.approx(1.5, rel=1e-9) and not monotone["oscillatory"]
    assert monotone["gci_pct"] == pytest.approx(100 * 1.25 * abs(f[-1] - f0) / f[-1], rel=1e-9)
    assert math.isnan(monotone["u_osc_pct"]) and math.isnan(monotone["expected_order"])
    assert monotone["within_expected"] is None and monotone["asymptotic"] is None
    wave = orders.loc[("axi", "max_1")]
    assert wave["oscillatory"] and math.isnan(wave["gci_pct"]) and math.isnan(wave["gci_order"])
    assert wave["u_osc_pct"] == pytest.approx(100 * 0.5 * (1.004 - 0.999) / 1.001, rel=1e-9)
    assert math.isnan(orders.loc[("axi", "history_l2"), "gci_pct"])  # a norm: no index
    # a method with an extrapolated reference gets none
    other = _orders(_frame("m", n, {"contact_time": list(f / f[-1] - 1.0)}), {"m": SPEC}).loc[("m", "contact_time")]
    assert math.isnan(other["gci_pct"]) and other["oscillatory"] is None


# ------------------------------------------------------------------ the reference of a finest level

STEEL = {"name": "steel", "youngs_modulus_pa": 2.0e11, "density_kg_m3": 7800.0, "poisson_ratio": 0.3}


def _run(n: int, contact_time: float, maxima: list[float], peak_times: list[float]) -> SimpleNamespace:
    """A stored run as the analyses read it, with a triangle of force over the contact."""
    t = np.linspace(0.0, contact_time, 201)
    return SimpleNamespace(
        case_id="c",
        method="axi",
        wall_time_s=0.1 * n,
        config={
            "run": {"level": {5: 0, 10: 1, 20: 2}[n], "numerics": {"elements_across": n}},
            "rod": {"length_m": 0.03, "material": STEEL},
        },
        summary={
            "contact_time_s": contact_time,
            "peak_time_s": np.array(peak_times),
            "peak_force_N": np.array(maxima),
            "contact_start_s": np.array([0.0]),
            "contact_end_s": np.array([contact_time]),
            "energy_error": 0.0,
        },
        series={"time": t, "contact_force": maxima[0] * (1.0 - np.abs(2 * t / contact_time - 1.0))},
    )


def test_the_finest_level_is_the_reference_with_its_uncertainty() -> None:
    round_trip = 2 * 0.03 / wave_speed(Material.from_mapping(STEEL))
    peaks = [round_trip * 1.001, round_trip * 2.4]  # the first just after the first arrival
    runs = [_run(n, 5.6e-4 * (1 + 0.01 / n**2), [1742.0 * (1 - 0.1 / n**2), 3800.0], peaks) for n in (5, 10, 20)]
    frame = work_precision_frame(runs, {"axi": AXI | {"order": 2, "resolution": "elements_across"}})
    finest = frame[frame["level"] == 2].iloc[0]
    assert finest["reference"] == "axi (finest level)" and finest["err_contact_time"] == 0.0
    coarse = frame[frame["level"] == 0].iloc[0]
    assert coarse["signed_err_contact_time"] == pytest.approx((1 + 0.01 / 25) / (1 + 0.01 / 400) - 1, rel=1e-9)
    assert coarse["signed_err_max_1"] < 0 < coarse["signed_err_contact_time"]
    # the uncertainty of the reference: GCI of three levels at ratio 2, order 2 recovered
    f1 = 1 + 0.01 / 400
    assert finest["ref_err_contact_time"] == pytest.approx(1.25 * (f1 - 1.0) / f1, rel=1e-6)
    assert finest["ref_err_max_2"] == 0.0  # the same on every level
    assert finest["arrival_offset_max_1"] == pytest.approx(0.001, rel=1e-9)
    assert finest["arrival_offset_max_2"] == pytest.approx(0.4, rel=1e-9)
    with pytest.raises(ValueError, match="needs 3 levels"):
        work_precision_frame(runs[1:], {"axi": AXI | {"order": 2, "resolution": "elements_across"}})
