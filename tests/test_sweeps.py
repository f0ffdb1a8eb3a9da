"""Parameter sweeps: the grid, the cases at its points, the loader, and snakemake's Paramspace."""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest
from snakemake.utils import Paramspace

from rodimpact.analysis.sweeps import SWEEP_PARAMETERS, sweep_frame, sweep_point_case, sweep_values
from rodimpact.present.sweep_table import sweep_results_frame


@pytest.fixture(scope="module")
def project(shipped_project):
    return shipped_project


def test_log_range_has_its_endpoints_and_constant_ratio() -> None:
    values = sweep_values({"start": 1e-3, "stop": 2e-2, "num": 25, "spacing": "log"})
    assert len(values) == 25 and values[0] == 1e-3 and values[-1] == 2e-2
    ratios = np.diff(np.log(values))
    # each value is rounded to 6 significant digits (relative change <= 5e-6)
    np.testing.assert_allclose(ratios, math.log(20) / 24, rtol=0, atol=1.0e-5)


def test_linear_range_and_list() -> None:
    assert sweep_values({"start": 0.1, "stop": 0.5, "num": 5}) == [0.1, 0.2, 0.3, 0.4, 0.5]
    assert sweep_values([0.3225, 1.0]) == [0.3225, 1.0]


@pytest.mark.parametrize(
    "spec, field",
    [
        ({"start": 0.0, "stop": 1.0, "num": 3}, "start"),
        ({"start": 1.0, "stop": 2.0, "num": 1}, "num"),
        ({"start": 1.0, "stop": 2.0, "num": 3, "spacing": "cubic"}, "spacing"),
    ],
)
def test_bad_range_is_refused_naming_the_field(spec: dict, field: str) -> None:
    with pytest.raises(ValueError, match=f"^{field}"):
        sweep_values(spec)


def test_values_that_round_to_the_same_name_are_refused() -> None:
    with pytest.raises(ValueError, match="coincide"):
        sweep_values([1.0, 1.0000001])


def test_grid_is_every_combination() -> None:
    frame = sweep_frame({"parameters": {"velocity_m_s": [0.1, 0.2, 0.3], "rod_length_m": [0.1, 0.5]}})
    assert list(frame.columns) == ["velocity_m_s", "rod_length_m"]
    assert len(frame) == 6 and len(frame.drop_duplicates()) == 6


def test_unknown_parameter_is_named() -> None:
    with pytest.raises(ValueError, match=r"^parameters\.diameter: unknown sweep parameter"):
        sweep_frame({"parameters": {"diameter": [1.0]}})


def test_ball_diameter_makes_a_solid_ball_of_the_material(project) -> None:
    case = project.sweeps["ball_sweep-r1_l30"]
    rho = case["impactor"]["material"]["density_kg_m3"]
    point = sweep_point_case(case, {"ball_diameter_m": 0.01}, "ball_diameter_m~0.01")
    assert point["impactor"]["radius_m"] == pytest.approx(0.005, rel=1e-12)
    assert point["impactor"]["mass_kg"] == pytest.approx(rho * math.pi * 1e-6 / 6, rel=1e-12)
    assert point["methods"] == ["sem"] and "sweep" not in point and point["sweep_point"] == {"ball_diameter_m": 0.01}
    assert point["rod"] == case["rod"]  # only the impactor changes
    # a copy: changing the point leaves the sweep case as it was, its grid included
    grid = copy.deepcopy(case["sweep"])
    point["rod"]["length_m"] *= 2
    point["methods"].append("fem1d")
    assert case["rod"]["length_m"] != point["rod"]["length_m"] and case["sweep"] == grid


def test_table2_balls_are_solid_balls_of_the_sweeps_steel(project) -> None:
    """The sweep's rule (mass from diameter and density) gives the printed masses of Table 2
    (two or three printed digits: within 3 %), so its curve and the six rows are one family."""
    case = project.sweeps["ball_sweep-r1_l30"]
    for row in project.cases_in("table2", "r1_l30"):
        point = sweep_point_case(case, {"ball_diameter_m": 2 * row["impactor"]["radius_m"]}, "p")
        assert point["impactor"]["mass_kg"] == pytest.approx(row["impactor"]["mass_kg"], rel=0.03), row["id"]


def test_shipped_sweep_is_expanded_over_the_variants_and_not_a_row(project) -> None:
    no_film = [
        v for v in project.variants["table2"] if "film" not in v and "sensor" not in v and not v.endswith("_cal")
    ]
    sensor = ["ball_sweep_sensor-r10_l30_sensor_cal", "ball_sweep_sensor-r1_l30_sensor_cal"]
    assert sorted(project.sweeps) == sorted(
        [f"ball_sweep-{v}" for v in no_film] + ["ball_sweep_film-r10_l30_film"] + sensor
    )
    assert not [c for c in project.cases_in("table2") if c["row"] == "ball_sweep"]
    assert [c["id"] for c in project.sweeps_in("table2", "r1_l30")] == ["ball_sweep-r1_l30"]
    assert project.sweeps_in("model") == []


def test_paramspace_names_round_trip_to_the_grids_floats(project) -> None:
    """Each point's file name, read back by snakemake's Paramspace, gives the grid's very float."""
    frame = sweep_frame(project.sweeps["ball_sweep-r1_l30"]["sweep"])
    space = Paramspace(frame, filename_params="*", single_wildcard="sweep_point")
    names = list(space.instance_patterns)
    assert len(set(names)) == len(frame) == 25
    for name, value in zip(names, frame["ball_diameter_m"]):
        assert name == f"ball_diameter_m~{value}"
        assert float(space.instance({"sweep_point": name})["ball_diameter_m"]) == value


def test_every_parameter_sets_its_field(project) -> None:
    case = project.sweeps["ball_sweep-r1_l30"]
    where = {
        "ball_diameter_m": ("impactor", "radius_m", 0.0123 / 2),
        "mass_kg": ("impactor", "mass_kg", 0.0123),
        "radius_m": ("impactor", "radius_m", 0.0123),
        "velocity_m_s": ("impactor", "velocity_m_s", 0.0123),
        "rod_length_m": ("rod", "length_m", 0.0123),
    }
    film = {
        "film_modulus_pa": ("material", "youngs_modulus_pa", 2.5e9),
        "film_poisson_ratio": ("material", "poisson_ratio", 0.31),
        "film_thickness_m": (None, "thickness_m", 3.0e-5),
    }
    assert set(where) | set(film) == set(SWEEP_PARAMETERS)
    film_case = project.sweeps["ball_sweep_film-r10_l30_film"]
    for name, (part, field, value) in film.items():
        point = sweep_point_case(film_case, {name: value}, "p")
        before, after = film_case["contact"]["film"], point["contact"]["film"]
        before, after = (before, after) if part is None else (before[part], after[part])
        assert before[field] != value and after[field] == value, name
        assert {k: v for k, v in after.items() if k != field} == {k: v for k, v in before.items() if k != field}
    with pytest.raises(ValueError, match="no film"):
        sweep_point_case(case, {"film_thickness_m": 1e-5}, "p")
    for name, (part, field, value) in where.items():
        point = sweep_point_case(case, {name: 0.0123}, "p")
        assert case[part][field] != value and point[part][field] == pytest.approx(value, rel=1e-15), name
        assert point["sweep_point"] == {name: 0.0123} and point["sweep_of"] == "ball_sweep-r1_l30"
        unchanged = {k: v for k, v in point[part].items() if k not in (field, "mass_kg")}
        assert unchanged == {k: v for k, v in case[part].items() if k not in (field, "mass_kg")}, name


def test_contact_time_along_the_sweep_follows_hertz_for_a_rigid_rod(project) -> None:
    """On a stiff short rod the contact is Hertzian: t ~ m^(2/5) R^(-1/5), i.e. t ~ d for a
    solid ball. The sweep's SEM runs show it: fitted log-log slope 1 within 0.05."""
    from rodimpact.jobs.runner import run_case

    case = project.sweeps["ball_sweep-r10_l30"]
    diameters = [1e-3, 2e-3, 4e-3]
    times = [
        run_case(sweep_point_case(case, {"ball_diameter_m": d}, "p"), "sem").summary()["contact_time_s"]
        for d in diameters
    ]
    slope = np.polyfit(np.log(diameters), np.log(times), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.05)


def test_sweep_table_reads_the_points(tmp_path: Path, project) -> None:
    from rodimpact.jobs.runner import run_to_file
    from rodimpact.storage.runs import read_summary

    case = project.sweeps["ball_sweep-r1_l30"]
    paths = [
        run_to_file(sweep_point_case(case, {"ball_diameter_m": d}, f"d{d}"), "sem", tmp_path / f"{d}.h5")
        for d in (3e-3, 2e-3)
    ]
    frame = sweep_results_frame([read_summary(p) for p in paths])
    assert list(frame["ball_diameter_m"]) == [2e-3, 3e-3]  # sorted by mass
    assert set(frame["sweep"]) == {"ball_sweep-r1_l30"} and set(frame["variant"]) == {"r1_l30"}
    assert (frame["contact_time_us"] > 0).all() and (frame["max_force_N"] >= frame["first_peak_force_N"]).all()
