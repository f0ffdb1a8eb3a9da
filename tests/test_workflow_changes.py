"""What a target, a new case and a change plan: only the jobs a target needs, a new row or case
file picked up, and a change to a case, the code of the solvers, of one method or of a figure
rerunning exactly what depends on it, file by file.

The tests of a change work on a copy of the session's ``.test/`` build (the ``dottest``
fixture, tests/conftest.py); the dry runs of targets and new cases on a fresh, shrunk copy of
the shipped configuration (``helpers.copies.copy_project``).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from rodimpact.storage.runs import read_run

from helpers.copies import (
    DOTTEST,
    DotTestBuild,
    batch_part,
    batches,
    clone_build,
    copy_project,
    project_cases,
    run_batch,
    run_path,
)
from helpers.snakemake_cli import BUILD_TIMEOUT_S, job_stats, pending, pending_runs, snakemake, summary

pytestmark = pytest.mark.workflow

#: The cases of a shrunk copy of the shipped configuration that list the output strain_field.
WAVE_CASES = ("model", "ball_3.16mm-r10_l30")


@pytest.fixture
def changed(dottest: DotTestBuild, tmp_path: Path) -> DotTestBuild:
    """A copy of the session's .test/ build, for one test to change."""
    return clone_build(dottest, tmp_path / "project")


# --------------------------------------------------------------------------------------------
# only what a target needs
# --------------------------------------------------------------------------------------------


def test_target_plans_only_its_jobs(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    target = "results/tables/table2_r1_l30.csv"
    run = snakemake(project, "-n", "-j2", target)
    assert run.returncode == 0, run.describe()
    # Which files: the case file of the six r1_l30 balls, their runs by each of the three methods
    # (a batch each, in as many parts as its cost asks) and the five outputs of the table2 job.
    rows = summary(project, target)
    parts = pending(rows, "solve")
    assert job_stats(run.output) == {"case_file": 1, "solve": len(parts), "readings_table": 1}, run.describe()
    balls = [c["id"] for c in project_cases(project).cases_in("table2", "r1_l30")]
    assert batches(parts) == {run_batch(ball, m) for ball in balls for m in ("sem", "fem1d", "fem_axi")}
    assert pending(rows, "readings_table") == {
        f"results/tables/table2_r1_l30.{ext}" for ext in ("csv", "md", "html", "tex", "provenance.json")
    }
    assert pending(rows, "case_file") == {"results/cases/r1_l30.yaml"}  # the reading's cases, one file
    assert pending(rows) == pending(rows, "case_file") | pending(rows, "solve") | pending(rows, "readings_table")
    assert not (project / "results").exists(), "a dry run must not write results"


def test_only_the_cases_asking_for_the_field_have_a_wave_map(tmp_path: Path) -> None:
    """The wave map of a case plans the runs of the methods that record the field; a case that
    does not list strain_field has none, and none of its runs pays for it."""
    project = copy_project(tmp_path / "project")
    assert [c for c, case in project_cases(project).cases.items() if "strain_field" in case["outputs"]] == list(
        WAVE_CASES
    )
    target = "results/figures/wave_map_model.png"
    run = snakemake(project, "-n", "-j2", target)
    assert run.returncode == 0, run.describe()
    assert job_stats(run.output) == {"case_file": 1, "solve": 2, "wave_map": 1}, run.describe()
    assert pending(summary(project, target), "solve") == {batch_part("model", m) for m in ("sem", "fem1d")}
    run = snakemake(project, "-n", "-j2", "results/figures/wave_map_ball_4.75mm-r10_l30.png")
    assert run.returncode != 0 and "no rule makes 'results/figures/wave_map_ball_4.75mm-r10_l30.png'" in run.output


# --------------------------------------------------------------------------------------------
# adding a case is adding YAML
# --------------------------------------------------------------------------------------------

#: A new row of Table 2, for every reading of the rod (a case with no ``variants``).
NEW_TABLE2_ROW = {
    "id": "ball_8.00mm",
    "description": "Added by a test: steel ball, diameter 8.00 mm, mass 2.09 g",
    "impactor": {"mass_kg": 2.09e-3, "radius_m": 4.0e-3},
    "measured": {"contact_time_us": 75.0},
}

NEW_CASE_FILE = """\
set: my_experiment
description: A new experiment, added by a test as one more YAML file.
cases:
  - id: my_ball
    description: A steel ball on a short aluminium rod given by its cross-section area
    impactor: {mass_kg: 1.0e-3, radius_m: 3.0e-3, velocity_m_s: 0.5, material: steel}
    rod: {length_m: 0.2, area_m2: 1.0e-4, material: aluminium_table1}
    measured: {contact_time_us: 50.0, source: "lab notebook, page 1"}
"""


def test_new_row_in_table2_yaml_is_computed(changed: DotTestBuild) -> None:
    table2_yaml = changed.workdir / "config/cases/table2.yaml"
    document = yaml.safe_load(table2_yaml.read_text(encoding="utf-8"))
    document["cases"].append(NEW_TABLE2_ROW)
    table2_yaml.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    new_case = "ball_8.00mm-r10_l30"
    before = pd.read_csv(changed.workdir / "results/tables/table2_r10_l30.csv")
    # the reading's batches are solved again (each part whose cases the new ball changes)
    parts = pending(summary(changed.project, "results/tables/table2_r10_l30.csv", workdir=DOTTEST), "solve")
    assert batches(parts) == {run_batch(new_case, m) for m in ("sem", "fem1d", "fem_axi")}

    run = snakemake(
        changed.project, "-j2", "results/tables/table2_r10_l30.csv", timeout=BUILD_TIMEOUT_S, workdir=DOTTEST
    )
    assert run.returncode == 0, run.describe()
    # The other readings' runs are reused: the new ball's case file, its batches, then the table.
    assert job_stats(run.output) == {"case_file": 1, "solve": len(parts), "readings_table": 1}, run.describe()

    record = read_run(changed.workdir / run_path(changed.workdir, new_case, "sem"))
    assert record.config["measured"]["contact_time_us"] == 75.0
    assert record.config["impactor"]["mass_kg"] == pytest.approx(2.09e-3)
    assert record.config["rod"]["radius_m"] == pytest.approx(0.010)  # from the variant

    table = pd.read_csv(changed.workdir / "results/tables/table2_r10_l30.csv")
    assert len(table) == len(before) + 1
    new = table[table["case_id"] == new_case]
    assert len(new) == 1, table["case_id"].tolist()
    row = new.iloc[0]
    assert row["measured_us"] == 75.0
    assert row["mass_g"] == pytest.approx(2.09) and row["diameter_mm"] == pytest.approx(8.0)
    assert math.isfinite(row["sem_us"]) and row["sem_us"] > 0
    assert row["sem_us"] == pytest.approx(1e6 * record.summary["contact_time_s"], rel=1e-9)
    assert math.isnan(row["published_sem_us"]) and math.isnan(row["published_fem_us"])
    # Rows are sorted by mass (the new ball between the lighter and the heavier ones), and the
    # contact time grows with the mass.
    lighter = int((before["mass_g"] < 2.09).sum())
    assert 0 < lighter < len(before), before["mass_g"].tolist()
    assert table["case_id"].tolist().index(new_case) == lighter
    assert table["case_id"].drop(lighter).tolist() == before["case_id"].tolist()
    assert table["sem_us"].is_monotonic_increasing
    provenance = json.loads((changed.workdir / "results/tables/table2_r10_l30.provenance.json").read_text())
    assert run_path(changed.workdir, new_case, "sem") in [entry["path"] for entry in provenance["inputs"]]


def test_new_case_file_is_picked_up(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    (project / "config/cases/my_experiment.yaml").write_text(NEW_CASE_FILE, encoding="utf-8")
    target = batch_part("my_ball", "sem", group="my_experiment")
    run = snakemake(project, "-n", "-j2", target)
    assert run.returncode == 0, run.describe()
    assert job_stats(run.output) == {"case_file": 1, "solve": 1}, run.describe()
    assert pending(summary(project, target)) == {target, "results/cases/my_experiment.yaml"}
    resolved = project_cases(project)
    assert resolved.sets["my_experiment"] == ["my_ball"]
    assert resolved.cases["my_ball"]["rod"]["area_m2"] == pytest.approx(1.0e-4)


def test_a_new_experiment_with_measurements_gets_its_comparison(tmp_path: Path) -> None:
    """A new case file with measured values and a force history, its set added to targets.sets:
    its comparison table, figure and history figure are built, with no code change."""
    project = copy_project(tmp_path / "project")
    cases = project / "config/cases"
    (cases / "my_lab").mkdir()
    # µs: a half-sine of 60 µs and 50 N (the same impact on a rigid wall peaks at 57 N: a record
    # past twice that is refused before any job, rodimpact.analysis.record_checks)
    t = np.arange(-10.0, 80.0, 0.5)
    force = np.where((t > 0) & (t < 60.0), 50.0 * np.sin(np.pi * np.clip(t, 0, 60) / 60.0), 0.0)
    (cases / "my_lab/ball_a.csv").write_text("time_us,force_N\n" + "".join(f"{a},{b}\n" for a, b in zip(t, force)))
    (cases / "my_lab.yaml").write_text(
        NEW_CASE_FILE.replace("my_experiment", "my_lab").replace(
            'measured: {contact_time_us: 50.0, source: "lab notebook, page 1"}',
            "methods: [sem]\n    measured: {contact_time_us: 50.0, peak_force_n: 250.0, "
            'source: "lab notebook, page 1",\n'
            '               force_history: {file: my_lab/ball_a.csv, note: "piezo film, 1 MOhm"}}',
        ),
        encoding="utf-8",
    )
    config_file = project / "config/config.yaml"
    config = yaml.safe_load(config_file.read_text(encoding="utf-8"))
    config["targets"]["sets"] = ["my_lab"]
    config_file.write_text(yaml.safe_dump(config, sort_keys=False), encoding="utf-8")
    targets = [
        "results/tables/compare_my_lab.csv",
        "results/figures/compare_my_lab.png",
        "results/figures/compare_my_lab_force.png",
    ]
    run = snakemake(project, "-j2", *targets, timeout=BUILD_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    assert job_stats(run.output) == {"case_file": 1, "solve": 1, "compare": 1, "compare_signal": 1}, run.describe()
    table = pd.read_csv(project / targets[0])
    assert set(table["quantity"]) == {
        "contact_time_us",
        "peak_force_n",
        "signal_contact_time_us",
        "history_l2_pct",
        "history_max_pct",
    }
    assert (table["source"] == "lab notebook, page 1").all()
    time = table[table["quantity"] == "contact_time_us"].iloc[0]
    assert time["error_pct"] == pytest.approx(100 * (time["computed"] - 50.0) / 50.0, rel=1e-12)
    signal = table[table["quantity"] == "signal_contact_time_us"].iloc[0]
    assert signal["measured"] == pytest.approx(60.0 * (1 - 2 * math.asin(0.05) / math.pi), rel=1e-3)
    provenance = json.loads((project / "results/tables/compare_my_lab.provenance.json").read_text())
    assert "config/cases/my_lab/ball_a.csv" in [entry["path"] for entry in provenance["input_files"]]


READINGS_CASE_FILE = """\
set: drops
description: Two balls on a steel rod read two ways (its length measured twice), added by a test.
compare: {title: Drop tests}
variants:
  short: {description: "Rod 0.20 m long", source: tape, rod: {length_m: 0.20}}
  long: {description: "Rod 0.21 m long", source: calliper, rod: {length_m: 0.21}}
defaults:
  rod: {radius_m: 5.0e-3, material: steel}
  methods: [sem]
cases:
  - id: ball_a
    impactor: {mass_kg: 1.0e-3, radius_m: 3.0e-3, velocity_m_s: 0.5, material: steel}
    measured: {contact_time_us: 30.0, source: "lab notebook, page 2"}
  - id: ball_b
    impactor: {mass_kg: 8.0e-3, radius_m: 6.0e-3, velocity_m_s: 0.5, material: steel}
    measured: {contact_time_us: 60.0, source: "lab notebook, page 2"}
"""


def test_a_new_experiment_with_readings_gets_the_tables_of_table2(tmp_path: Path) -> None:
    """A new set with variants and measured times, no published results: the tables and the
    figure Table 2 gets, built by the same rules with no code change, and without the paper's
    columns, which its cases do not declare."""
    project = copy_project(tmp_path / "project")
    (project / "config/cases/drops.yaml").write_text(READINGS_CASE_FILE, encoding="utf-8")
    config_file = project / "config/config.yaml"
    config = yaml.safe_load(config_file.read_text(encoding="utf-8"))
    config["targets"]["sets"] = ["drops"]
    config_file.write_text(yaml.safe_dump(config, sort_keys=False), encoding="utf-8")
    targets = [
        *(f"results/tables/drops_{v}.md" for v in ("short", "long")),
        "results/tables/drops_variants.csv",
        "results/figures/drops_contact_time.png",
        "results/tables/compare_drops.csv",
    ]
    run = snakemake(project, "-j2", *targets, timeout=BUILD_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    stats = job_stats(run.output)
    assert {
        k: stats.get(k)
        for k in (
            "readings_table",
            "readings_summary",
            "fig_readings",
            "compare",
            "film_table",
            "sensor_band",
            "indentation",
        )
    } == {
        "readings_table": 2,
        "readings_summary": 1,
        "fig_readings": 1,
        "compare": 1,
        "film_table": None,
        "sensor_band": None,
        "indentation": None,
    }, run.describe()
    for variant, length in (("short", 0.20), ("long", 0.21)):
        table = pd.read_csv(project / f"results/tables/drops_{variant}.csv")
        assert list(table["case_id"]) == [f"ball_a-{variant}", f"ball_b-{variant}"]
        assert not [c for c in table.columns if "published" in c]
        assert table["sem_error_pct"].tolist() == pytest.approx(
            (100 * (table["sem_us"] - table["measured_us"]).abs() / table["measured_us"]).tolist(), rel=1e-8
        )  # the CSV keeps ten significant digits
        md = (project / f"results/tables/drops_{variant}.md").read_text(encoding="utf-8")
        assert md.startswith(f"Drop tests, rod reading {variant}: rod radius 5 mm, length {1000 * length:g} mm")
        assert "Paper" not in md and "Table~2" not in (project / f"results/tables/drops_{variant}.tex").read_text()
    summary_table = pd.read_csv(project / "results/tables/drops_variants.csv")
    assert set(summary_table["variant"]) == {"short", "long"}
    assert not [c for c in summary_table.columns if c.startswith("paper_")]
    assert (project / "results/figures/drops_contact_time.png").stat().st_size > 0


# --------------------------------------------------------------------------------------------
# a change reruns what depends on it
# --------------------------------------------------------------------------------------------


def test_changed_case_value_reruns_only_that_case(changed: DotTestBuild) -> None:
    model_yaml = changed.workdir / "config/cases/model.yaml"
    text = model_yaml.read_text(encoding="utf-8")
    assert text.count("velocity_m_s: 1.0\n") == 1
    model_yaml.write_text(text.replace("velocity_m_s: 1.0\n", "velocity_m_s: 1.1\n"), encoding="utf-8")

    run = snakemake(changed.project, "-n", "-j2", workdir=DOTTEST)
    assert run.returncode == 0, run.describe()
    rows = summary(changed.project, workdir=DOTTEST)
    # model's runs and what shows them (its forces handed on too), and the studies built on model: its work-precision
    # levels (3 methods x 3 levels in .test, a job per method) and the stability map, whose
    # base case it is (every part of its batch per method and of the references')
    assert batches(pending(rows, "solve_map")) == {
        f"results/stability_map/{m}" for m in ("sem", "sem_paper", "reference")
    }
    assert job_stats(run.output) == {
        "case_file": 1,
        "solve": 4,
        "paper_model": 1,
        "all": 1,
        "solve_levels": 3,
        "work_precision_table": 1,
        "work_precision_figure": 1,
        "solve_map": len(pending(rows, "solve_map")),
        "stability_map": 1,
        "forces": 1,
        "wave_map": 1,
    }, run.describe()
    assert pending(rows, "case_file") == {"results/cases/model.yaml"}
    assert pending(rows, "solve") == {batch_part("model", m) for m in ("sem", "sem_paper", "fem1d", "fem_axi")}
    assert pending(rows, "paper_model") == {
        f"results/figures/{name}.{ext}"
        for name in ("fig2_contact_force", "fig4_midrod_displacement", "force_fit_model")
        for ext in ("pdf", "png", "provenance.json")
    } | {f"results/tables/fig2_comparison.{ext}" for ext in ("csv", "md", "html", "provenance.json")}
    assert not {p for p in pending(rows) if "table2" in p or "ball_" in p}


def test_code_change_reruns_the_solvers(changed: DotTestBuild) -> None:
    with open(changed.project / "src/rodimpact/contact/hertz.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")  # content changes, so the checksum changes too

    run = snakemake(changed.project, "-n", "-j2", workdir=DOTTEST)
    assert run.returncode == 0, run.describe()
    stats = job_stats(run.output)
    project = project_cases(changed.workdir)
    rows = summary(changed.project, workdir=DOTTEST)
    every = {
        run_batch(c["id"], m, group=c.get("variant") or c["set"])
        for name in ("model", "table2", "example", "gauge_example")
        for c in project.cases_in(name)
        for m in c["methods"]
    }
    assert batches(pending(rows, "solve")) == every  # every batch of runs of the target sets, every part
    assert stats.get("solve") == len(pending(rows, "solve")), run.describe()
    assert stats.get("calibrate") == 1, run.describe()  # its model runs the solvers in memory
    # the code is a param (the digest of the sources a rule runs), not sixty input files
    assert "Params have changed since last execution" in run.output, run.describe()
    assert "src/rodimpact" not in run.output, run.describe()
    assert pending(rows, "solve") == {row["output_file"] for row in rows if row["rule"] == "solve"}


def test_a_methods_code_change_reruns_only_its_runs(changed: DotTestBuild) -> None:
    """A rule depends on its own method's solver (the registry names it): a change to fem_axi
    reruns fem_axi's runs and what shows them, and no run of another method."""
    with open(changed.project / "src/rodimpact/solvers/fem_axi/solver.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    rows = summary(changed.project, workdir=DOTTEST)  # what a run would rebuild, file by file
    reruns = pending_runs(rows, changed.workdir)
    cases = project_cases(changed.workdir).cases.values()
    # and the runs of the law calibrated by fem_axi's indentation, which reads fem_axi's code, by
    # each of their methods, with the sensor's bands over that law (.test calibrates the sensor
    # as built; test_a_methods_code_change_reruns_the_law_it_calibrates: the film's)
    calibrated = {c["id"]: c for c in cases if (c.get("contact") or {}).get("law") == "tabulated"}
    assert calibrated
    assert batches(pending(rows, "solve")) == {
        run_batch(c["id"], "fem_axi") for c in cases if "fem_axi" in c["methods"] and c["set"] in ("model", "table2")
    } | {run_batch(case, m) for case, c in calibrated.items() for m in c["methods"]}
    calibrated_groups = {c.get("variant") or c["set"] for c in calibrated.values()}
    assert pending(rows, "indentation") == {f"results/indentation/{c['variant']}" for c in calibrated.values()}
    assert pending(rows, "sensor_band") == {f"results/studies/sensor_band/{c['variant']}" for c in calibrated.values()}
    # and the calibrated sweeps' points, whose batches indent each point with fem_axi's code
    sweeps = {
        s
        for s, c in project_cases(changed.workdir).sweeps.items()
        if (c.get("contact") or {}).get("law") == "tabulated"
    }
    assert sweeps and {p for p in reruns if p.startswith("results/sweeps/")} == {
        p.relative_to(changed.workdir).as_posix()
        for s in sweeps
        for p in (changed.workdir / "results/sweeps" / s).rglob("*.h5")
    }
    assert reruns and all(
        "fem_axi" in path
        or path.startswith("results/runs/")
        and Path(path).parts[2] in calibrated_groups
        or path.startswith(("results/indentation/", "results/studies/sensor_band/"))
        or Path(path).parts[2:3]
        and Path(path).parts[2] in sweeps
        for path in reruns
    ), sorted(reruns)


#: The batch of the law calibrated by fem_axi's indentation (the text's rod without the film): the
#: reading's six balls by sem, one part.
CALIBRATED_BATCH = batch_part("ball_3.16mm-r10_l30_cal", "sem")


def test_a_methods_code_change_reruns_the_law_it_calibrates(tmp_path: Path) -> None:
    """The calibrated law's runs read fem_axi's indentation curves: a change to fem_axi reruns
    the curves and the runs (a shrunk copy of the shipped configuration: .test calibrates none)."""
    project = copy_project(tmp_path / "project")
    case = project_cases(project).cases["ball_3.16mm-r10_l30_cal"]
    assert case["contact"]["law"] == "tabulated" and case["methods"] == ["sem"]
    balls = [c["id"] for c in project_cases(project).cases_in("table2", "r10_l30_cal")]
    run = snakemake(project, "-j2", CALIBRATED_BATCH, timeout=BUILD_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    assert job_stats(run.output) == {"case_file": 1, "indentation": 1, "solve": 1}, run.describe()
    assert read_run(project / run_path(project, case["id"], "sem")).case_id == case["id"]
    with open(project / "src/rodimpact/solvers/fem_axi/solver.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    rows = summary(project, CALIBRATED_BATCH)
    curves = {f"results/indentation/r10_l30_cal/{ball}.h5" for ball in balls}
    assert pending(rows, "indentation") == {"results/indentation/r10_l30_cal"}
    assert pending_runs(rows, project) == curves | {CALIBRATED_BATCH}
    assert {run_path(project, ball, "sem").partition("#")[0] for ball in balls} == {CALIBRATED_BATCH}


def test_figure_code_change_reruns_no_solver(changed: DotTestBuild) -> None:
    """Each rule depends on the modules its script imports, not on the whole package."""
    with open(changed.project / "src/rodimpact/present/figures.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    run = snakemake(changed.project, "-n", "-j2", workdir=DOTTEST)
    assert run.returncode == 0, run.describe()
    stats = job_stats(run.output)
    assert "solve" not in stats, run.describe()
    assert stats.get("paper_model") == 1 and stats.get("fig_readings") == 1, run.describe()


#: The rules that compute (solvers, the continuum's indentation, the bands, the calibration, the
#: case files): none of them runs presentation code.
COMPUTE_RULES = (
    "case_file",
    "solve",
    "solve_levels",
    "solve_stress",
    "solve_map",
    "solve_sweep",
    "indentation",
    "film_band",
    "sensor_band",
    "calibrate",
)


@pytest.mark.parametrize(
    "module", ["table.py", "columns.py", "compare.py", "calibration_tables.py", "figures.py", "words.py"]
)
def test_a_presentation_change_reruns_only_presentation_jobs(changed: DotTestBuild, module: str) -> None:
    """Compute stores numbers, presentation adds words: a change to any presentation module
    (the table machinery, the shared columns, a table, a figure, the words) plans no solver,
    indentation, band, case file or calibration job, and reruns the presentation that imports it."""
    with open(changed.project / "src/rodimpact/present" / module, "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    run = snakemake(changed.project, "-n", "-j2", workdir=DOTTEST)
    assert run.returncode == 0, run.describe()
    stats = job_stats(run.output)
    assert stats and not set(stats) & set(COMPUTE_RULES), run.describe()
    assert set(stats) - {"all"}, run.describe()


def test_the_studys_separate_cases_are_a_target_of_their_own(tmp_path: Path) -> None:
    """work_precision.separate: outside rule all; its target runs only its methods' levels on
    its cases and its table."""
    project = copy_project(tmp_path / "project")
    config = project / "config" / "config.yaml"
    document = yaml.safe_load(config.read_text(encoding="utf-8"))
    document["work_precision"]["separate"] = {"cases": ["ball_12.73mm-r1_l30"], "methods": ["sem"]}
    config.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    everything = snakemake(project, "-n")
    assert everything.returncode == 0, everything.describe()
    assert "work_precision_separate_table" not in job_stats(everything.output)
    assert "results/convergence/ball_12.73mm-r1_l30/" not in everything.output
    separate = snakemake(project, "-n", "results/tables/work_precision_separate_orders.md")
    assert separate.returncode == 0, separate.describe()
    assert job_stats(separate.output) == {"case_file": 1, "solve_levels": 1, "work_precision_separate_table": 1}, (
        separate.describe()
    )
