"""The sensor film's tables and figures, from small synthetic runs, bands and curves written
with the project's own writers (rodimpact.storage): the numbers of each frame, and the renders."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rodimpact.present.figure_artifacts import make_fig_film_force
from rodimpact.present.film_figures import plot_film_force
from rodimpact.present.film_tables import (
    INDENTATION_COLUMNS,
    film_band_frame,
    film_indentation_frame,
    film_table,
    film_table_frame,
    make_film_indentation_table,
    make_film_table,
)
from rodimpact.present.readings import readings_frame, table2_frame, table2_panels, variants_summary
from rodimpact.present.sensor_tables import make_axes_table
from rodimpact.present.table import write_artifact
from rodimpact.present.table2_figures import plot_table2_contact_time
from rodimpact.storage.bands import BAND_PARAMETERS, CaseBand, read_band, write_band
from rodimpact.storage.curves import ContactCurve, read_contact_curve, write_contact_curve
from rodimpact.storage.runs import read_run, read_summary, write_run

FILM = {
    "thickness_m": 2.8e-5,
    "area_m2": 2.1e-5,
    "material": {"name": "pvdf", "youngs_modulus_pa": 3.0e9, "poisson_ratio": 0.35, "density_kg_m3": 1780.0},
}
#: row -> (mass g, diameter mm, measured us, published fem us, published sem us)
ROWS = {"ball_a": (8.46, 12.73, 111.10, 121.71, 64.82), "ball_b": (0.13, 3.16, 36.42, 31.20, 15.32)}
ROLES = {"no_film": "rod", "film": "rod_film", "film_calibrated": "rod_film_cal", "no_film_calibrated": "rod_cal"}
CONTACT = {
    "rod": None,
    "rod_film": {"law": "hertz_film", "film": FILM},
    "rod_film_cal": {"law": "tabulated", "from": "fem_axi_indentation", "film": FILM},
    "rod_cal": {"law": "tabulated", "from": "fem_axi_indentation"},
}
METHODS_OF = {
    "rod": ("sem", "fem1d", "fem_axi"),
    "rod_film": ("sem", "fem1d", "fem_axi"),
    "rod_film_cal": ("sem",),
    "rod_cal": ("sem",),
}


def contact_time_us(row: str, variant: str, method: str) -> float:
    """A distinct contact time per run: the tests recompute every number from these."""
    base = ROWS[row][2]
    shift = {"rod": 0.6, "rod_film": 0.9, "rod_film_cal": 0.95, "rod_cal": 0.62}[variant]
    return base * shift * {"sem": 1.0, "fem1d": 1.001, "fem_axi": 1.03}[method]


def case_config(row: str, variant: str) -> dict:
    mass, diameter, measured, fem, sem = ROWS[row]
    config = {
        "id": f"{row}-{variant}",
        "row": row,
        "variant": variant,
        "set": "table2",
        "impactor": {"mass_kg": mass / 1000, "radius_m": diameter / 2000, "velocity_m_s": 0.3225},
        "rod": {"radius_m": 0.01, "length_m": 0.0301},
        "measured": {"contact_time_us": measured},
        "published": {
            "fem": {"contact_time_us": fem, "error_pct": abs(fem - measured) / measured * 100},
            "sem": {"contact_time_us": sem, "error_pct": abs(sem - measured) / measured * 100},
        },
    }
    if CONTACT[variant] is not None:
        config["contact"] = CONTACT[variant]
    return config


def write_synthetic_run(root: Path, row: str, variant: str, method: str, radius_ratio: float = 6.0) -> Path:
    tc = 1e-6 * contact_time_us(row, variant, method)
    time = np.linspace(0.0, 1.2 * tc, 61)
    force = np.where(time <= tc, 100.0 * ROWS[row][0] * np.sin(np.pi * np.minimum(time / tc, 1.0)), 0.0)
    summary = {
        "contact_time_s": tc,
        "peak_force_N": np.array([force.max()]),
        "peak_time_s": np.array([tc / 2]),
        "rebound_velocity_m_s": -0.3,
        "energy_error": 0.0,
        "contact_start_s": np.array([0.0]),
        "contact_end_s": np.array([tc]),
        "n_contacts": 1,
    }
    if variant == "rod_film" and method != "fem_axi":
        summary.update(contact_law="hertz_film", film_radius_to_thickness=radius_ratio)
    path = root / "runs" / f"{row}-{variant}" / f"{method}.h5"
    return write_run(
        path,
        config=case_config(row, variant),
        method=method,
        wall_time_s=0.1,
        code_version="test",
        series={"time": (time, "s", "time"), "contact_force": (force, "N", "contact force")},
        summary=summary,
    )


def synthetic_band(
    case_id: str, corner_us: list[float], measured: float, nominal: float, monotone: bool = True
) -> CaseBand:
    axis = np.array([nominal - 1, nominal, nominal + 1]) if monotone else np.array([nominal, nominal + 1, nominal])
    return CaseBand(
        case_id=case_id,
        measured_us=measured,
        nominal_us=nominal,
        corner_parameters=np.ones((len(corner_us), len(BAND_PARAMETERS))),
        corner_us=np.asarray(corner_us, float),
        axis_values={n: np.array([1.0, 2.0, 3.0]) for n in BAND_PARAMETERS},
        axis_us={n: axis.astype(float) for n in BAND_PARAMETERS},
    )


@pytest.fixture(scope="module")
def store(tmp_path_factory) -> dict:
    """Runs of both rows on the four readings, and the band file of the film reading."""
    root = tmp_path_factory.mktemp("film_present")
    runs = [
        write_synthetic_run(root, row, variant, method, radius_ratio=4.0 if row == "ball_b" else 9.0)
        for row in ROWS
        for variant, methods in METHODS_OF.items()
        for method in methods
    ]
    bands = [
        synthetic_band("ball_a-rod_film", [95.0, 105.0, 100.0], measured=111.10, nominal=100.0),
        synthetic_band("ball_b-rod_film", [30.0, 38.0, 33.0], measured=36.42, nominal=33.0, monotone=False),
    ]
    band = write_band(root / "film_band_rod_film.h5", bands, variant="rod_film", method="sem", config=[])
    return {"root": root, "runs": runs, "band": band}


def test_film_table_numbers(store: dict) -> None:
    records = [read_summary(p) for p in store["runs"]]
    _, bands = read_band(store["band"])
    frame = film_table_frame(records, ROLES, bands)
    assert list(frame["row"]) == ["ball_b", "ball_a"]  # by mass
    for column in (
        "sem_no_film_us",
        "fem1d_no_film_us",
        "fem_axi_no_film_us",
        "sem_film_us",
        "fem1d_film_us",
        "fem_axi_film_us",
        "sem_film_calibrated_us",
        "sem_no_film_calibrated_us",
        "thin_layer_band_min_us",
        "thin_layer_band_max_us",
        "sensor_band_min_us",
        "sensor_band_max_us",
        "radius_to_thickness",
        "model_form_pct",
        "sensor_model_form_pct",
    ):
        assert column in frame, column
    for record in frame.itertuples():
        measured = ROWS[record.row][2]
        assert record.measured_us == pytest.approx(measured, rel=1e-12)
        assert record.mass_g == pytest.approx(ROWS[record.row][0], rel=1e-12)
        film_sem = contact_time_us(record.row, "rod_film", "sem")
        assert record.sem_film_us == pytest.approx(film_sem, rel=1e-9)
        assert record.sem_film_error_pct == pytest.approx(abs(film_sem - measured) / measured * 100, rel=1e-9)
        axi = contact_time_us(record.row, "rod", "fem_axi")
        assert record.fem_axi_no_film_error_pct == pytest.approx(abs(axi - measured) / measured * 100, rel=1e-9)
        calibrated = contact_time_us(record.row, "rod_film_cal", "sem")
        continuum = contact_time_us(record.row, "rod_film", "fem_axi")
        assert record.model_form_pct == pytest.approx((calibrated - continuum) / continuum * 100, rel=1e-9)
        assert record.model_form_pct == pytest.approx((0.95 / (0.9 * 1.03) - 1) * 100, abs=1e-9)
        assert record.radius_to_thickness == pytest.approx(4.0 if record.row == "ball_b" else 9.0, abs=1e-12)
    assert list(frame["thin_layer_band_min_us"]) == pytest.approx([30.0, 95.0], abs=1e-12)
    assert list(frame["thin_layer_band_max_us"]) == pytest.approx([38.0, 105.0], abs=1e-12)
    # no sensor reading: its band and model-form columns are there, and empty
    assert frame[["sensor_band_min_us", "sensor_band_max_us", "sensor_model_form_pct"]].isna().all().all()


def test_film_table_refuses_a_stray_run(store: dict) -> None:
    records = [read_summary(p) for p in store["runs"]]
    with pytest.raises(ValueError, match="none of the variants"):
        film_table_frame(records, {"no_film": "rod", "film": "rod_film"})
    with pytest.raises(ValueError, match="unknown roles"):
        film_table_frame(records, {**ROLES, "other": "rod"})


def test_film_band_frame_inside_and_monotone(store: dict) -> None:
    variant, bands = read_band(store["band"])
    cases = {f"{row}-rod_film": case_config(row, "rod_film") for row in ROWS}
    frame = film_band_frame({variant: bands}, cases)
    assert list(frame["row"]) == ["ball_b", "ball_a"]
    b, a = frame.iloc[0], frame.iloc[1]
    assert (b["band_min_us"], b["band_max_us"], b["nominal_us"]) == pytest.approx((30.0, 38.0, 33.0), abs=1e-12)
    assert b["measured_in_band"] and not b["monotone"]  # 30 <= 36.42 <= 38
    assert not a["measured_in_band"] and a["monotone"]  # 111.1 > 105
    assert a["mass_g"] == pytest.approx(8.46, rel=1e-12)
    assert frame["measured_in_band"].dtype == bool and frame["monotone"].dtype == bool


def test_film_indentation_frame(tmp_path: Path) -> None:
    force = np.array([1.0, 10.0, 100.0])
    approach = 1e-7 * force ** (2 / 3)
    law = approach * np.array([1.10, 1.05, 0.98])
    radius = np.array([20e-6, 50e-6, 120e-6])
    data = {
        "approach_m": approach,
        "force_N": force,
        "contact_radius_m": radius,
        "displacement_m": 2 * approach,
        "law_approach_m": law,
    }
    with_film = ContactCurve(
        "ball_b-rod_film_cal",
        data,
        {"analytic_law": "hertz_film", "interpolation_error_half": 2e-3},
        case_config("ball_b", "rod_film_cal"),
    )
    bare = ContactCurve(
        "ball_b-rod_cal",
        data,
        {"analytic_law": "hertz", "interpolation_error_half": 1e-3},
        case_config("ball_b", "rod_cal"),
    )
    curves = [read_contact_curve(write_contact_curve(tmp_path / f"{c.case_id}.h5", c)) for c in (with_film, bare)]
    frame = film_indentation_frame(curves)
    assert len(frame) == 6
    film = frame[frame["case_id"] == "ball_b-rod_film_cal"].reset_index(drop=True)
    assert list(film["point"]) == [0, 1, 2] and set(film["law"]) == {"hertz_film"}
    assert list(film["law_error_pct"]) == pytest.approx([10.0, 5.0, -2.0], abs=1e-9)
    assert list(film["continuum_approach_um"]) == pytest.approx(list(1e6 * approach), rel=1e-12)
    assert list(film["contact_radius_um"]) == pytest.approx([20.0, 50.0, 120.0], rel=1e-12)
    assert list(film["radius_to_film_thickness"]) == pytest.approx(list(radius / 2.8e-5), rel=1e-12)
    assert film["interpolation_error_half"].iloc[0] == pytest.approx(2e-3, rel=1e-12)
    bare_rows = frame[frame["case_id"] == "ball_b-rod_cal"]
    assert bare_rows["radius_to_film_thickness"].isna().all() and set(bare_rows["law"]) == {"hertz"}


def test_no_indentation_curve_is_a_table_of_its_header_alone(tmp_path: Path) -> None:
    out = {k: tmp_path / f"film_indentation.{k}" for k in ("csv", "md", "html", "provenance.json")}
    write_artifact(
        make_film_indentation_table([]),
        csv=out["csv"],
        md=out["md"],
        html=out["html"],
        provenance=out["provenance.json"],
    )
    assert out["csv"].read_text(encoding="utf-8") == ",".join(INDENTATION_COLUMNS) + "\n"
    assert list(pd.read_csv(out["csv"]).columns) == list(INDENTATION_COLUMNS)


def test_readings_variants_summary_and_panels(store: dict) -> None:
    records = [read_summary(p) for p in store["runs"]]
    readings = readings_frame(records)
    by_variant = readings.set_index("variant")
    assert by_variant.loc["rod", "contact_law"] == "hertz" and not by_variant.loc["rod", "film"]
    assert by_variant.loc["rod_film", "contact_law"] == "hertz_film" and by_variant.loc["rod_film", "film"]
    assert by_variant.loc["rod_film_cal", "contact_law"] == "tabulated" and by_variant.loc["rod_film_cal", "film"]
    frames = {v: table2_frame([r for r in records if r.config["variant"] == v]) for v in METHODS_OF}
    summary = variants_summary(frames, by_variant.to_dict("index"))
    assert list(summary.columns[:4]) == ["variant", "film", "contact_law", "method"]
    row = summary[(summary["variant"] == "rod_film") & (summary["method"] == "sem")].iloc[0]
    assert row["film"] and row["contact_law"] == "hertz_film"
    signed = [(contact_time_us(r, "rod_film", "sem") - ROWS[r][2]) / ROWS[r][2] * 100 for r in ROWS]
    assert row["mean_signed_error_pct"] == pytest.approx(np.mean(signed), abs=1e-9)  # -10 % each
    assert row["max_error_pct"] == pytest.approx(10.0, abs=1e-9)
    assert table2_panels(readings, ["rod_film"]) == {"rod": ["rod_film"]}  # calibrated readings not drawn


def test_the_film_table_is_headed_in_words_with_units(store: dict) -> None:
    """The film table declares its columns: the shared ones, those made per method and reading,
    and its own (the bands, the contact radius, the model-form errors)."""
    records = [read_summary(p) for p in store["runs"]]
    _, bands = read_band(store["band"])
    table = film_table(records, ROLES, bands)
    headers = {name: table.column(name).header for name in ("measured_us", "mass_g", "sem_film_error_pct", "row")}
    assert headers == {
        "measured_us": "Measured (µs)",
        "mass_g": "Mass (g)",
        "sem_film_error_pct": "SEM, film error (%)",
        "row": "Ball",
    }
    assert table.column("thin_layer_band_min_us").header == "Thin-layer band min (approximation) (µs)"
    assert all(1 <= len(panel.columns) <= 8 for panel in table.panels)


def test_film_force_figure_renders(store: dict, tmp_path: Path) -> None:
    runs = [p for p in store["runs"] if p.parent.name.endswith(("-rod", "-rod_film")) and p.stem in ("sem", "fem_axi")]
    assert len(runs) == 8
    fig = plot_film_force([read_run(p) for p in runs], ["ball_b", "ball_a"])
    axes = fig.axes
    assert len(axes) == 2
    for ax in axes:
        assert ax.get_xlabel().endswith("(µs)") and ax.get_ylabel().endswith("(N)")
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert len(labels) == 4, labels
        assert sum("with film" in label for label in labels) == 2 and sum("no film" in label for label in labels) == 2
        assert all("_" not in label for label in labels), labels  # words, not ids
    out = {k: tmp_path / f"film_force.{k}" for k in ("pdf", "png")}
    make_fig_film_force(
        runs, ["ball_b", "ball_a"], pdf=out["pdf"], png=out["png"], provenance=tmp_path / "film_force.provenance.json"
    )
    assert out["png"].stat().st_size > 1000 and out["pdf"].stat().st_size > 1000
    record = json.loads((tmp_path / "film_force.provenance.json").read_text())
    assert len(record["inputs"]) == 8


def test_table2_film_artifact_and_sidecar(store: dict, tmp_path: Path) -> None:
    out = {k: tmp_path / f"table2_film.{k}" for k in ("csv", "md", "html", "provenance.json")}
    write_artifact(
        make_film_table(store["runs"], ROLES, store["band"]),
        csv=out["csv"],
        md=out["md"],
        html=out["html"],
        provenance=out["provenance.json"],
    )
    table = pd.read_csv(out["csv"])
    assert len(table) == 2 and "model_form_pct" in table
    markdown = out["md"].read_text(encoding="utf-8")
    assert "Measured (µs)" in markdown and "Model-form error (%)" in markdown
    assert "<th" in out["html"].read_text(encoding="utf-8") and "Model-form error" in out["html"].read_text()
    record = json.loads(out["provenance.json"].read_text())
    assert len(record["inputs"]) == len(store["runs"])
    assert [f["kind"] for f in record["input_files"]] == ["band"]
    assert set(record["sha256"]) == {str(out["csv"]), str(out["md"]), str(out["html"])}
    with pytest.raises(ValueError, match="not of the film reading"):
        make_film_table(store["runs"], {**ROLES, "film": "rod"}, store["band"])


def test_table2_figure_draws_the_film_on_its_rod(store: dict) -> None:
    records = [read_summary(p) for p in store["runs"]]
    readings = readings_frame(records)
    frames = {v: table2_frame([r for r in records if r.config["variant"] == v]) for v in METHODS_OF}
    variant, bands = read_band(store["band"])
    band_frame = film_band_frame({variant: bands}, {r.case_id: r.config for r in records})
    sweeps = pd.DataFrame(
        {
            "variant": ["rod_film"] * 6,
            "row": ["sweep"] * 6,
            "method": ["sem"] * 6,
            "film_modulus_pa": [2e9, 2e9, 3e9, 3e9, 4e9, 4e9],
            "diameter_mm": [3.0, 12.0] * 3,
            "mass_g": [0.11, 7.1] * 3,
            "contact_time_us": [40.0, 120.0, 36.0, 110.0, 34.0, 104.0],
        }
    )
    fig = plot_table2_contact_time(
        frames,
        sweeps,
        panels=table2_panels(readings, ["rod_film"]),
        readings=readings,
        bands=band_frame,
        set_title="Table 2",
    )
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert len(visible) == 1 and "µs" in visible[0].get_ylabel() and "g" in visible[0].get_xlabel()
    labels = [" ".join(t.get_text().split()) for t in fig.legends[0].get_texts()]  # unwrapped
    # the rows and the sweep at the nominal 3 GPa are one model, one entry; the bars and the shade
    # of the moduli 2 to 4 GPa are its ranges, one entry
    model = "SEM, implicit scheme, film as a thin layer (approximation, too soft)"
    assert model in labels and any("band" in label and "approximation" in label for label in labels), labels
    (line,) = [line for line in visible[0].lines if line.get_label() == model and line.get_linestyle() == "-"]
    assert list(line.get_ydata()) == [36.0, 110.0]  # the sweep at the nominal modulus
    (shade,) = visible[0].collections[:1]
    (path,) = shade.get_paths()
    assert path.vertices[:, 1].min() == pytest.approx(34.0) and path.vertices[:, 1].max() == pytest.approx(120.0)
    low, high = visible[0].get_ylim()
    assert 0 < low <= 30.0 and high >= 120.0  # the band of the lightest ball and the sweep are inside


def test_the_film_axes_table_and_the_band_table_without_axes(store: dict, tmp_path: Path) -> None:
    """make film-axes' table: a row per case and constant, monotone where the band's axis is; the
    default build's band (no axes) has no Monotone column, and no axes table can be made of it."""
    out = {k: tmp_path / f"axes.{k}" for k in ("csv", "md", "html")}
    write_artifact(
        make_axes_table([store["band"]], [], kind="film"), provenance=tmp_path / "axes.provenance.json", **out
    )
    frame = pd.read_csv(out["csv"])
    assert len(frame) == 2 * len(BAND_PARAMETERS) and set(frame["constant"]) == set(BAND_PARAMETERS)
    assert frame.groupby("case_id")["monotone"].all().to_dict() == {"ball_a-rod_film": True, "ball_b-rod_film": False}
    assert "Lengthens at" in out["md"].read_text() and "Continuum" not in out["md"].read_text()
    variant, bands = read_band(store["band"])
    bare = [dataclasses.replace(b, axis_values={}, axis_us={}) for b in bands]
    path = write_band(tmp_path / "film_band_bare.h5", bare, variant=variant, method="sem", config=[])
    assert "monotone" not in film_band_frame({variant: read_band(path)[1]}, {}).columns
    with pytest.raises(ValueError, match="has its axes"):
        make_axes_table([path], [], kind="film")
