"""The outputs of one end-to-end build of the small configuration ``.test/``
(``snakemake -j2 --directory .test``): every artifact, each run with its provenance and the case
file it was made from, the tables and figures with the runs they were made from, the sweeps and
studies, the provenance audit, and a rerun that plans nothing.

The build is the session's ``dottest`` fixture (tests/conftest.py): the checkout's own
``.test/results`` when ``make test`` has just built it and it is up to date, else a build in a
temporary copy of the project. It is never modified; the test that edits files works on a copy
of it. What a build must contain is read from the build's own configuration.

The subprocesses get no PYTHONPATH: the workflow itself (workflow/rules/preflight.smk) puts the
project's ``src/`` first, so it runs the code it lists as inputs, not the repository's editable
install (tests/test_workflow_errors.py, ``test_jobs_run_the_checkouts_own_code``).
"""

from __future__ import annotations

import contextlib
import json
import math
import re
import subprocess
import sys
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import pytest
from PIL import Image

from rodimpact.storage.casefile import case_record, read_case_file
from rodimpact.storage.references import split_reference
from rodimpact.storage.runs import REQUIRED_SUMMARY, read_run, read_summary, run_references
from rodimpact.tools.audit import audit

from helpers.copies import DOTTEST, SMALL_STRESS, DotTestBuild, case_run, clone_build, project_cases, run_path
from helpers.snakemake_cli import job_stats, snakemake

pytestmark = pytest.mark.workflow

#: The cases that list the output strain_field, each with its wave map (the runs of the methods
#: that record the field: sem and fem1d).
WAVE_CASES = ("model", "ball_3.16mm-r10_l30")
ROOT_ATTRS = (
    "case_id", "method", "config_json", "config_sha256", "code_version", "library_versions",
    "wall_time_s", "data_sha256",
)  # fmt: skip
SUMMARY_ATTRS = ("contact_time_s", "peak_force_N", "peak_time_s", "rebound_velocity_m_s", "energy_error")
TABLE2_COLUMNS = (
    "diameter_mm", "mass_g", "measured_us", "published_fem_us", "published_sem_us", "sem_us",
    "sem_error_pct",
)  # fmt: skip
#: The reading of the text's rod with the sensor film (the film band is drawn for it).
FILM_VARIANT = "r10_l30_film"
CODE_VERSION = re.compile(r"\d+\.\d+\.\d+(\.post\d+)?\+g[0-9a-f]{4,40}")


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------


def pdf_info_string(raw: bytes, key: str) -> str:
    """The literal string value of ``/<key>`` in a PDF's info dictionary (no pypdf needed).

    Matplotlib writes the info dictionary uncompressed; a literal string is delimited by
    balanced parentheses with backslash escapes (PDF 32000-1, 7.3.4.2).
    """
    match = re.search(rb"/" + key.encode() + rb"\s*\(", raw)
    assert match, f"no /{key} literal string in the PDF"
    escapes = {b"n": b"\n", b"r": b"\r", b"t": b"\t", b"b": b"\b", b"f": b"\f",
               b"(": b"(", b")": b")", b"\\": b"\\"}  # fmt: skip
    out, depth, i = bytearray(), 0, match.end()
    while True:
        char = raw[i : i + 1]
        if not char:
            raise AssertionError(f"unterminated /{key} string in the PDF")
        if char == b"\\":
            nxt = raw[i + 1 : i + 2]
            if nxt in escapes:
                out += escapes[nxt]
                i += 2
            elif nxt in (b"\n", b"\r"):  # line continuation
                i += 2
            else:
                octal = re.match(rb"[0-7]{1,3}", raw[i + 1 : i + 4])
                if octal:
                    out.append(int(octal.group(0), 8) & 0xFF)
                    i += 1 + len(octal.group(0))
                else:
                    i += 1
            continue
        if char == b"(":
            depth += 1
        elif char == b")":
            if depth == 0:
                break
            depth -= 1
        out += char
        i += 1
    if out.startswith(b"\xfe\xff"):
        return out[2:].decode("utf-16-be")
    return out.decode("latin-1")


def assert_inputs_match(inputs: list[dict], runs: list[str], hashes: dict[str, str]) -> None:
    """A provenance record lists exactly ``runs``, each with the hash stored in the run."""
    assert sorted(entry["path"] for entry in inputs) == sorted(runs)
    for entry in inputs:
        assert entry["config_sha256"] == hashes[entry["path"]], entry["path"]
        file, case_id = split_reference(entry["path"])  # {group}/{method}/part{k}.h5#{case}
        method = file.parent.name
        assert (entry["case_id"], entry["method"]) == (case_id, method)


@contextlib.contextmanager
def stored_run(built: Path, reference: str) -> Iterator[h5py.Group]:
    """The HDF5 group that holds the run ``reference`` (``file#name``) of the build."""
    file, name = split_reference(reference)
    with h5py.File(built / file, "r") as h5:
        yield h5[name]


def _points(sweep: dict) -> int:
    """The runs of a resolved sweep: every combination of its parameters' values, per method."""
    return math.prod(len(values) for values in sweep["sweep"]["parameters"].values()) * len(sweep["sweep"]["methods"])


# --------------------------------------------------------------------------------------------
# what the build must contain
# --------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def built(dottest: DotTestBuild) -> Path:
    """The working directory of the build (``.test/``: config/, results/, logs/)."""
    return dottest.workdir


@pytest.fixture(scope="module")
def expected(built: Path) -> dict:
    """What the build must contain, from its own configuration."""
    project = project_cases(built)
    variants = sorted(project.variants["table2"])
    by_variant = {
        v: [case_run(built, c, m) for c in project.cases_in("table2", v) for m in c["methods"]] for v in variants
    }
    runs = [case_run(built, c, m) for name in ("model", "table2", "example", "gauge_example")
            for c in project.cases_in(name) for m in c["methods"]]  # fmt: skip
    example = [case_run(built, c, m) for name in ("example", "gauge_example")
               for c in project.cases_in(name) for m in c["methods"]]  # fmt: skip
    plain = [v for v in variants if "contact" not in project.variants["table2"][v]]
    calibrated = [v for v in variants if (project.variants["table2"][v].get("contact") or {}).get("law") == "tabulated"]
    # What the checks below need of the configuration: 'model' by the four methods, the text's
    # rod with and without the film, at least two balls on every reading (an order to check),
    # and the wave maps of WAVE_CASES.
    assert len(project.cases["model"]["methods"]) == 4
    assert {"r10_l30", FILM_VARIANT} <= set(variants) and "r10_l30" in plain
    assert all(len(project.cases_in("table2", v)) >= 2 for v in variants)
    assert tuple(c for c, case in project.cases.items() if "strain_field" in case["outputs"]) == WAVE_CASES
    assert len(runs) == sum(len(r) for r in by_variant.values()) + 4 + len(example) and example
    return {
        "project": project,
        "variants": variants,
        "plain_variants": plain,
        "calibrated_variants": calibrated,
        "runs": runs,
        "model_runs": [run_path(built, "model", m) for m in project.cases["model"]["methods"]],
        "table2_runs": by_variant,
        "sweep_points": {name: _points(sweep) for name, sweep in project.sweeps.items()},
    }


@pytest.fixture(scope="module")
def stored_hashes(built: Path, expected: dict) -> dict[str, str]:
    """config_sha256 of every run, read straight from the HDF5 root attributes."""
    hashes = {}
    for path in expected["runs"]:
        with stored_run(built, path) as h5:
            value = h5.attrs["config_sha256"]
        hashes[path] = value.decode() if isinstance(value, bytes) else str(value)
    return hashes


# --------------------------------------------------------------------------------------------
# the artifacts, the runs and their case files
# --------------------------------------------------------------------------------------------


def test_full_build_produces_every_artifact(built: Path, expected: dict) -> None:
    film = [
        f"results/tables/{name}.{ext}"
        for name in ("table2_film", "film_band", "film_indentation")
        for ext in ("csv", "md", "provenance.json")
    ]
    film += [f"results/figures/film_force.{ext}" for ext in ("pdf", "png")]
    film += [f"results/studies/film_band_{FILM_VARIANT}.h5"]
    film += [
        f"results/indentation/{v}/{c['id']}.h5"
        for v in expected["calibrated_variants"]
        for c in expected["project"].cases_in("table2", v)
    ]
    artifacts = [
        *(f"results/tables/table2_{v}.{ext}" for v in expected["variants"]
          for ext in ("csv", "md", "tex", "provenance.json")),
        *film,
        *(f"results/tables/table2_variants.{ext}" for ext in ("csv", "md", "provenance.json")),
        *(f"results/tables/fig2_comparison.{ext}" for ext in ("csv", "md", "provenance.json")),
        *(f"results/figures/{name}.{ext}"
          for name in ("fig2_contact_force", "fig4_midrod_displacement", "table2_contact_time")
          for ext in ("pdf", "png")),
        *sorted({str(split_reference(run)[0]) for run in expected["runs"]}),  # their parts' files
        *(f"results/tables/{name}" for name in ("work_precision.csv", "work_precision_orders.csv",
                                                 "work_precision_orders.md", "stability.csv", "stability.md",
                                                 "stability_map.csv")),
        *(f"results/figures/{name}.{ext}" for name in ("work_precision_model", "work_precision_linear_spring",
                                                        "stability_map")
          for ext in ("pdf", "png")),
        *(f"results/figures/wave_map_{case}.{ext}" for case in WAVE_CASES for ext in ("pdf", "png", "provenance.json")),
    ]  # fmt: skip
    missing = [a for a in artifacts if not (built / a).is_file() or (built / a).stat().st_size == 0]
    assert not missing, f"missing or empty: {missing}"
    # No stray run files, and no temporary file left anywhere under results/.
    parts = sorted(p.relative_to(built).as_posix() for p in (built / "results/runs").rglob("*.h5"))
    assert all(re.fullmatch(r"results/runs/[^/]+/[^/]+/part[0-9]+\.h5", p) for p in parts), parts
    stored = [str(Path(r).relative_to(built)) for p in parts for r in run_references(built / p)]
    assert sorted(stored) == sorted(expected["runs"])
    # .test's batch.target_s cuts batches of every kind into parts: a group's, the map's, a sweep's
    cut = [p for p in (built / "results").rglob("part1.h5")]
    assert {p.relative_to(built / "results").parts[0] for p in cut} >= {"runs", "stability_map", "sweeps"}, cut
    assert not [p for p in (built / "results").rglob("*") if ".tmp" in p.name]


def test_every_run_records_the_case_file_it_was_made_from(built: Path, expected: dict) -> None:
    """The chain's first stage: each run's case, with its scales and costs, is in a file the run
    names (path, SHA-256 and case hash): its group's case file, which holds exactly the run's case."""
    for path in expected["runs"]:
        record = read_summary(built / path)
        reference = record.config["run"]["case_file"]
        group = Path(path).parts[2]  # results/runs/{group}/{method}/part{k}.h5#{case}
        assert reference["path"] == f"results/cases/{group}.yaml"
        case_file = case_record(read_case_file(built / reference["path"]), record.case_id)
        assert case_file["case_id"] == record.case_id
        assert reference["config_sha256"] == case_file["config_sha256"]
        assert case_file["case"] == {key: value for key, value in record.config.items() if key != "run"}
        derived = case_file["derived"]
        assert set(derived["methods"]) == set(record.config["methods"])
        assert derived["rigid_rod"]["contact_time_s"] > 0 and derived["rod"]["impedance_kg_s"] > 0
        for method in derived["methods"].values():
            assert method["time_step_s"] > 0 and method["steps"] > 1 and method["job"]["mem_mb"] >= 500


def test_every_run_file_has_provenance_and_summary(built: Path, expected: dict) -> None:
    for path in expected["runs"]:
        with stored_run(built, path) as h5:
            assert set(ROOT_ATTRS) <= set(h5.attrs), path
            assert set(SUMMARY_ATTRS) <= set(h5["summary"].attrs), path
        record = read_run(built / path)  # verifies config_sha256 against config_json
        file, case_id = split_reference(path)  # {group}/{method}/part{k}.h5#{case}
        method = file.parent.name
        assert (record.case_id, record.method) == (case_id, method)
        assert record.config["id"] == case_id
        assert record.config["run"]["method"] == method
        # The stored configuration is the resolved case the workflow was given.
        case = expected["project"].cases[case_id]
        assert {k: record.config[k] for k in case} == json.loads(json.dumps(case))
        assert re.fullmatch(r"[0-9a-f]{64}", record.config_sha256)
        assert re.fullmatch(r"\d+\.\d+\.\d+(\.post\d+)?\+g[0-9a-f]{4,40}", record.code_version)
        assert "numpy" in record.library_versions and "h5py" in record.library_versions
        assert math.isfinite(record.wall_time_s) and record.wall_time_s >= 0
        assert set(REQUIRED_SUMMARY) <= set(record.summary)
        contact = record.summary["contact_time_s"]
        assert math.isfinite(contact) and 1e-6 < contact < 1e-2, (path, contact)
        assert len(record.summary["peak_force_N"]) >= 1
        assert max(record.summary["peak_force_N"]) > 0
        assert math.isfinite(record.summary["energy_error"])
        assert "contact_force" in record.series and len(record.series["time"]) > 10
        # the strain field only where the case asks for it, by the methods that record it
        assert bool(record.field) == (case_id in WAVE_CASES and method in ("sem", "fem1d")), path


def test_study_tables(built: Path) -> None:
    """The studies of the build: every stress run ok or failed with a message, each level of the
    sweep with its errors and timing, and the map with one class per point and method."""
    stability = pd.read_csv(built / "results/tables/stability.csv")
    assert sorted(set(stability["case_id"])) == sorted(SMALL_STRESS)
    assert len(stability) == 2 * 3
    assert all(v == "ok" or v.startswith("failed: ") for v in stability["verdict"]), stability["verdict"]
    sweep = pd.read_csv(built / "results/tables/work_precision.csv")
    # three levels of each 1-D method on model; on the smooth case sem and fem1d only (its per_case)
    assert sorted(Counter(zip(sweep["case_id"], sweep["method"])).items()) == [
        (("linear_spring", "fem1d"), 3),
        (("linear_spring", "sem"), 3),
        (("model", "fem1d"), 3),
        (("model", "sem"), 3),
        (("model", "sem_paper"), 3),
    ]
    assert (sweep["wall_time_s"] > 0).all() and sweep["err_contact_time"].notna().all()
    assert sweep["machine"].str.contains("logical CPUs").all()
    stability_map = pd.read_csv(built / "results/tables/stability_map.csv")
    assert len(stability_map) == 4 * 2 and stability_map["class"].notna().all()


def test_table2_csvs(built: Path, expected: dict) -> None:
    cases = expected["project"].cases
    for variant, runs in expected["table2_runs"].items():
        table = pd.read_csv(built / f"results/tables/table2_{variant}.csv")
        assert set(TABLE2_COLUMNS) <= set(table.columns), variant
        assert len(table) == len(expected["project"].cases_in("table2", variant)), variant
        assert sorted(table["case_id"]) == sorted({split_reference(r)[1] for r in runs})
        for row in table.itertuples():
            case = cases[row.case_id]
            assert row.measured_us == pytest.approx(case["measured"]["contact_time_us"])
            assert row.published_sem_us == pytest.approx(case["published"]["sem"]["contact_time_us"])
            assert row.mass_g == pytest.approx(1000 * case["impactor"]["mass_kg"])
            assert row.diameter_mm == pytest.approx(2000 * case["impactor"]["radius_m"])
            assert math.isfinite(row.sem_us) and row.sem_us > 0
            error = abs(row.sem_us - row.measured_us) / row.measured_us * 100
            assert row.sem_error_pct == pytest.approx(error, rel=1e-6)
            if "fem1d" not in cases[row.case_id]["methods"]:
                continue
            # fem1d: the same physics, discretised independently
            assert row.fem1d_us == pytest.approx(row.sem_us, rel=1e-4)
            error = abs(row.fem1d_us - row.measured_us) / row.measured_us * 100
            assert row.fem1d_error_pct == pytest.approx(error, rel=1e-6)
            # fem_axi, coarse in .test: the continuum contact, close to the SEM (without
            # the film: with it, the thin-layer law and the continuum differ, docs/contact-laws.md)
            if "fem_axi" in cases[row.case_id]["methods"] and "contact" not in cases[row.case_id]:
                assert row.fem_axi_us == pytest.approx(row.sem_us, rel=0.1)
        assert table["mass_g"].is_monotonic_increasing
        assert table["sem_us"].is_monotonic_increasing, f"{variant}: heavier ball, longer contact"
        assert "ball_3.16mm" in (built / f"results/tables/table2_{variant}.md").read_text()
        assert r"\begin{tabular}" in (built / f"results/tables/table2_{variant}.tex").read_text()
    summary_table = pd.read_csv(built / "results/tables/table2_variants.csv")
    assert sorted(set(summary_table["variant"])) == expected["variants"]
    assert sorted(set(summary_table["method"])) == ["fem1d", "fem_axi", "sem"]
    for row in summary_table.itertuples():
        assert row.n_cases == len(expected["project"].cases_in("table2", row.variant)), row


def test_table_provenance_matches_run_files(built: Path, expected: dict, stored_hashes: dict[str, str]) -> None:
    for variant, runs in expected["table2_runs"].items():
        record = json.loads((built / f"results/tables/table2_{variant}.provenance.json").read_text())
        assert_inputs_match(record["inputs"], runs, stored_hashes)
        assert f"results/tables/table2_{variant}.csv" in record["artifacts"]
    record = json.loads((built / "results/tables/table2_variants.provenance.json").read_text())
    all_table2 = [run for runs in expected["table2_runs"].values() for run in runs]
    assert_inputs_match(record["inputs"], all_table2, stored_hashes)


@pytest.mark.parametrize(
    "figure",
    [
        "fig2_contact_force",
        "fig4_midrod_displacement",
        "table2_contact_time",
        *(f"wave_map_{case}" for case in WAVE_CASES),
    ],
)
def test_figures_carry_provenance(built: Path, expected: dict, stored_hashes: dict[str, str], figure: str) -> None:
    runs = (
        expected["model_runs"]
        if figure in ("fig2_contact_force", "fig4_midrod_displacement")
        else [run_path(built, figure.removeprefix("wave_map_"), m) for m in ("sem", "fem1d")]
        if figure.startswith("wave_map_")
        else [run for runs in expected["table2_runs"].values() for run in runs]
    )
    with Image.open(built / f"results/figures/{figure}.png") as png:
        png.load()
        assert png.size[0] > 100 and png.size[1] > 100
        from_png = json.loads(png.info["Description"])
    sweeps = [entry for entry in from_png["inputs"] if entry["path"].startswith("results/sweeps/")]
    if figure == "table2_contact_time":  # and the curves of the ball sweeps, every variant
        assert len(sweeps) == sum(expected["sweep_points"].values())
    else:
        assert not sweeps
    from_png["inputs"] = [entry for entry in from_png["inputs"] if entry not in sweeps]
    assert_inputs_match(from_png["inputs"], runs, stored_hashes)
    sidecar = json.loads((built / f"results/figures/{figure}.provenance.json").read_text())
    assert all(re.fullmatch(r"[0-9a-f]{64}", entry["data_sha256"]) for entry in sidecar["inputs"])
    assert set(sidecar["sha256"]) == {f"results/figures/{figure}.pdf", f"results/figures/{figure}.png"}

    raw = (built / f"results/figures/{figure}.pdf").read_bytes()
    assert raw.startswith(b"%PDF-")
    for run in runs:
        assert stored_hashes[run].encode() in raw, f"{figure}.pdf lacks the hash of {run}"
    from_pdf = json.loads(pdf_info_string(raw, "Subject"))
    assert_inputs_match([e for e in from_pdf["inputs"] if e not in sweeps], runs, stored_hashes)


def test_every_set_with_measurements_is_compared(built: Path, expected: dict) -> None:
    """The sets of targets.sets whose cases carry measurements (table2, the worked example), and
    only they, get their comparison: a table with a row per case, method and quantity, its
    summary, a figure, and a figure of its force histories, a row per case."""
    project = expected["project"]
    tables = sorted(p.name for p in (built / "results/tables").glob("compare_*.csv"))
    assert tables == [
        "compare_example.csv",
        "compare_example_summary.csv",
        "compare_gauge_example.csv",
        "compare_gauge_example_summary.csv",
        "compare_table2.csv",
        "compare_table2_summary.csv",
    ]
    example = pd.read_csv(built / "results/tables/compare_example.csv")
    cases = project.sets["example"]
    assert sorted(set(example["case_id"])) == sorted(cases)
    assert (built / "results/figures/compare_example_force.png").stat().st_size > 10_000
    for case_id in cases:
        runs = project.cases[case_id]["methods"]
        assert set(example[example["case_id"] == case_id]["method"]) == set(runs)
    table2 = pd.read_csv(built / "results/tables/compare_table2.csv")
    measured = [c for c in project.sets["table2"] if (project.cases[c]["measured"] or {}).get("contact_time_us")]
    assert set(table2["case_id"]) == set(measured) and set(table2["quantity"]) == {"contact_time_us"}
    assert not list((built / "results/figures").glob("compare_table2_*.png"))  # no history measured there


def test_a_strain_gauged_set_is_compared_and_calibrated(built: Path, expected: dict) -> None:
    """The strain-gauge example: its comparison has each record's first-pulse rows, its records
    are drawn in one figure, and its calibration (a fit, not a prediction) is written whole, with
    the sidecar the audit reads."""
    project = expected["project"]
    cases = project.sets["gauge_example"]
    compare = pd.read_csv(built / "results/tables/compare_gauge_example.csv")
    pulse = {"strain_arrival_us", "strain_peak_microstrain", "strain_integral_microstrain_us"}
    assert pulse | {"strain_l2_pct", "strain_max_pct"} == set(compare["quantity"])
    assert sorted(set(compare["case_id"])) == sorted(cases)
    assert (built / "results/figures/compare_gauge_example_strain.png").stat().st_size > 10_000
    calibration = pd.read_csv(built / "results/tables/calibration_gauge_example.csv")
    block = project.calibrate["gauge_example"]
    assert len(calibration) == len(cases) * len(block["quantities"])
    assert set(calibration["quantity"]) == set(block["quantities"]) <= pulse
    assert calibration["held_out_status"].eq("converged").all()
    constants = pd.read_csv(built / "results/tables/calibration_gauge_example_parameters.csv")
    assert list(constants["parameter"]) == [p["path"] for p in block["parameters"]]
    assert constants["warning"].isna().all() and not constants["at_bound"].any()
    assert "A fit, not a prediction" in (built / "results/tables/calibration_gauge_example.md").read_text()
    sidecar = json.loads((built / "results/tables/calibration_gauge_example.provenance.json").read_text())
    assert sidecar["input_files"][0]["path"] == "results/calibration/gauge_example.h5"
    assert (built / "results/figures/calibration_gauge_example.png").stat().st_size > 10_000


def test_sweep_points_are_runs_in_parts_and_a_table(built: Path, expected: dict) -> None:
    """The Table 2 ball sweeps: each point one run, named by its Paramspace instance, in the file
    of its part (consecutive points, one job each; the forty-point sweep cut into several at the
    small configuration's target); and a table whose contact times grow with the ball's mass
    along each curve."""
    project = expected["project"]
    files = sorted(p.relative_to(built).as_posix() for p in (built / "results/sweeps").rglob("*.h5"))
    assert all(re.fullmatch(r"results/sweeps/ball_sweep(_film|_sensor)?-\w+/sem/part\d+\.h5", f) for f in files), files
    references = [reference for f in files for reference in run_references(built / f)]
    assert len(references) == sum(expected["sweep_points"].values())
    point = r"ball_diameter_m~[0-9.e-]+(_film_modulus_pa~[0-9.e+]+)?"
    assert all(re.fullmatch(point, split_reference(r)[1]) for r in references), references
    parts = Counter(Path(f).parent.parent.name for f in files)
    assert parts["ball_sweep-r10_l30"] >= 3 and expected["sweep_points"]["ball_sweep-r10_l30"] >= 40, parts
    # each part holds consecutive points of the grid, in order
    for sweep, count in parts.items():
        names = [
            split_reference(r)[1]
            for k in range(count)
            for r in run_references(built / f"results/sweeps/{sweep}/sem/part{k}.h5")
        ]
        assert len(names) == expected["sweep_points"][sweep] and len(set(names)) == len(names)
    table = pd.read_csv(built / "results/tables/sweep_table2.csv")
    swept = {sweep["id"].rpartition("-")[2] for sweep in project.sweeps.values()}
    assert len(table) == len(references) and set(table["variant"]) == swept
    film_sweep = f"ball_sweep_film-{FILM_VARIANT}"
    film = table[table["sweep"] == film_sweep]
    assert len(film) == expected["sweep_points"][film_sweep] and sorted(set(film["film_modulus_pa"])) == [2e9, 3e9, 4e9]
    for modulus, curve in film.groupby("film_modulus_pa"):  # a softer film, a longer contact
        stiffer = film[(film["film_modulus_pa"] > modulus) & film["ball_diameter_m"].isin(curve["ball_diameter_m"])]
        for row in stiffer.itertuples():
            assert (
                row.contact_time_us
                < curve.loc[curve["ball_diameter_m"] == row.ball_diameter_m, "contact_time_us"].item()
            )
    table = table[table["sweep"] != film_sweep]
    for (sweep, variant), curve in table.groupby(["sweep", "variant"]):
        assert curve["mass_g"].is_monotonic_increasing and curve["contact_time_us"].is_monotonic_increasing, variant
        rho = project.sweeps[sweep]["impactor"]["material"]["density_kg_m3"]
        mass = rho * math.pi * curve["ball_diameter_m"] ** 3 / 6 * 1000
        np.testing.assert_allclose(curve["mass_g"], mass, rtol=1e-9)  # the CSV keeps 10 digits
    record = read_run(references[0])
    assert record.config["run"]["study"]["name"] == "sweep" and "sweep_point" in record.config
    assert record.config["run"]["study"]["point"] == split_reference(references[0])[1]
    # a point of the calibrated law's sweep: its batch indented the point's own ball
    sensor = [read_run(r) for r in references if "/ball_sweep_sensor-" in r]
    assert sensor and all(r.config["run"]["contact_curve"]["computed_in_job"] for r in sensor)
    assert len({r.config["run"]["contact_curve"]["summary"]["max_force_N"] for r in sensor}) == len(sensor)


# --------------------------------------------------------------------------------------------
# the provenance audit, and a rerun
# --------------------------------------------------------------------------------------------


def test_provenance_audit_passes_on_a_fresh_build(built: Path) -> None:
    result = audit(built)
    assert result.success, [f for f in result.findings if not f.ok][:5]
    kinds = Counter(f.kind for f in result.findings)
    # every HDF5 file of the build is a run (the contact-law curves and the bands aside), and
    # every table and figure is an artifact its provenance record names
    h5 = [p.relative_to(built).as_posix() for p in (built / "results").rglob("*.h5")]
    bands = ("results/studies/film_band_", "results/studies/sensor_band/")
    runs = [p for p in h5 if not p.startswith(("results/indentation/", "results/calibration/", *bands))]
    artifacts = [
        p
        for p in (built / "results").rglob("*")
        if p.is_file() and p.parent.name in ("tables", "figures") and not p.name.endswith(".provenance.json")
    ]
    assert kinds["run"] == len(runs) and kinds["artifact"] >= len(artifacts) >= 20 and not kinds["unknown"], kinds
    assert kinds["band"] == len([p for p in h5 if p.startswith(bands)]) >= 3, kinds
    assert kinds["calibration"] == len([p for p in h5 if p.startswith("results/calibration/")]) == 1, kinds
    # a copy is an untagged history: its version is 0.0.0.post1 (rodimpact._version), plus the commit
    assert all(CODE_VERSION.fullmatch(v) for f in result.findings for v in f.code_versions)


def test_provenance_audit_fails_on_hand_edits_and_stale_artifacts(dottest: DotTestBuild, tmp_path: Path) -> None:
    project = clone_build(dottest, tmp_path / "project").workdir
    table = project / "results/tables/table2_r10_l30_film.csv"
    table.write_text(table.read_text().replace("ball_3.16mm", "ball_3.16mm ", 1))
    damaged, name = run_path(project, "model", "fem1d").split("#")
    with h5py.File(project / damaged, "r+") as h5:
        h5[name]["contact_force"][5] *= 1.01
    (project / "results/tables/old_table.csv").write_text("a,b\n1,2\n")
    model_yaml = project / "config/cases/model.yaml"
    model_yaml.write_text(model_yaml.read_text().replace("velocity_m_s: 1.0\n", "velocity_m_s: 1.1\n"))

    proc = subprocess.run(
        [sys.executable, "-m", "rodimpact.tools.audit", "--root", str(project)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 1, proc.stdout + proc.stderr
    failed = {}
    for line in proc.stdout.splitlines():
        if line.startswith("FAIL "):
            path, problem = line[5:].split(": ", 1)
            failed.setdefault(path, []).append(problem)
    assert "bytes differ from those recorded" in " ".join(failed["results/tables/table2_r10_l30_film.csv"])
    assert "run model: its content differs from its data_sha256" in " ".join(failed[damaged])
    assert "no provenance record lists it" in " ".join(failed["results/tables/old_table.csv"])
    assert "not an output of the current workflow" in " ".join(failed["results/tables/old_table.csv"])
    assert "snakemake: params changed" in " ".join(failed[run_path(project, "model", "sem").split("#")[0]])
    # what was made from the changed case's runs is planned again
    assert "snakemake: an input is out of date" in " ".join(failed["results/figures/fig2_contact_force.png"])
    untouched = run_path(project, "ball_3.16mm-r10_l30", "sem").split("#")[0]
    assert untouched not in failed and "results/tables/table2_r10_l30.csv" not in failed


def test_rerun_after_full_build_plans_nothing(dottest: DotTestBuild) -> None:
    run = snakemake(dottest.project, "-n", "-j2", workdir=DOTTEST)
    assert run.returncode == 0, run.describe()
    assert "Nothing to be done" in run.output, run.describe()
    assert job_stats(run.output) == {}, run.describe()
