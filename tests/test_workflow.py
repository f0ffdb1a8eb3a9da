"""End-to-end tests of the snakemake workflow, run through its command line.

Every test works in a temporary copy of the project (Snakefile, config/, workflow/, src/);
snakemake never runs in the repository itself and the repository's config/ is never written.
One full build (``snakemake -j2``, ~30 s on 2 cores) is shared by the module; tests that change
something copy that built project (results and .snakemake metadata included, mtimes kept) or
start from a fresh, unbuilt copy.

The subprocesses get no PYTHONPATH: the workflow itself (workflow/rules/common.smk) puts the
copy's ``src/`` first, so it runs the code it lists as inputs, not the repository's editable
install (``test_jobs_run_the_checkouts_own_code``).
"""

from __future__ import annotations

import ast
import html
import json
import math
import os
import re
import shutil
import subprocess
import sys
from collections import Counter
from html.parser import HTMLParser
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import pytest
import yaml
from PIL import Image

from rodimpact.tools.audit import audit
from rodimpact.config.load import load_global_config, load_project
from rodimpact.solvers.registry import METHODS as REGISTRY
from rodimpact.storage.casefile import read_case_file
from rodimpact.storage.runs import REQUIRED_SUMMARY, read_run, read_summary

pytestmark = pytest.mark.workflow

from conftest import ROOT as REPO_ROOT
PROJECT_PARTS = ("Snakefile", "config", "workflow", "src")
TABLE2_VARIANTS = ("r10_l30", "r1_l301", "r1_l30", "r10_l301")
#: The film readings a copy keeps (the text's rod: the thin-layer film, and the calibrated law
#: with and without the film); the copy drops the film on the other readings.
FILM_VARIANTS = ("r10_l30_film", "r10_l30_film_cal", "r10_l30_cal")
DROPPED_FILM_VARIANTS = ("r1_l301_film", "r1_l30_film", "r10_l301_film")
ALL_VARIANTS = (*TABLE2_VARIANTS, *FILM_VARIANTS)
#: Points of the film sweep in a copy (2 ball sizes x 3 film moduli).
SMALL_FILM_SWEEP = 6
FILM_ARTIFACTS = (*(f"results/tables/{name}.{ext}" for name in ("table2_film", "film_band", "film_indentation")
                    for ext in ("csv", "md", "provenance.json")),
                  *(f"results/figures/film_force.{ext}" for ext in ("pdf", "png")),
                  "results/studies/film_band_r10_l30_film.h5",
                  *(f"results/indentation/{row}-{v}.h5" for row in (
                      "ball_3.16mm", "ball_4.75mm", "ball_5.56mm", "ball_6.34mm", "ball_9.51mm", "ball_12.73mm")
                    for v in ("r10_l30_film_cal", "r10_l30_cal")))
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
BUILD_TIMEOUT_S = 1200  # the shared build takes 3-4 min idle; a loaded machine doubles it
DRY_RUN_TIMEOUT_S = 120


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------


COARSE_FEM_AXI = ("steps_per_contact: 300, max_time_factor: 100.0, max_contacts: 50,\n"
                  "              element: P2, elements_across: 10")


def copy_project(dest: Path) -> Path:
    """A fresh, unbuilt copy of the project at ``dest``.

    These tests are about the workflow's mechanics, not its numerics (tested elsewhere and
    regressed by test_golden.py): the copy runs fem_axi on a coarse mesh with few steps.
    """
    dest.mkdir(parents=True, exist_ok=True)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info", "*.tmp*")
    for part in PROJECT_PARTS:
        source = REPO_ROOT / part
        if source.is_dir():
            shutil.copytree(source, dest / part, ignore=ignore)
        else:
            shutil.copy2(source, dest / part)
    config = dest / "config" / "config.yaml"
    text = config.read_text(encoding="utf-8")
    assert text.count(COARSE_FEM_AXI) == 1, "the fem_axi numerics line of config.yaml moved"
    config.write_text(text.replace(COARSE_FEM_AXI, COARSE_FEM_AXI.replace("300", "80").replace(
        "elements_across: 10", "elements_across: 4")), encoding="utf-8")
    _small_studies(dest)
    _git_commit(dest)
    return dest


def _git_commit(project: Path) -> None:
    """Make the copy a git repository with everything committed: its runs then record an
    exact code version (``make provenance`` refuses ``+unknown`` and ``.dirty``)."""
    (project / ".gitignore").write_text("__pycache__/\n*.pyc\n.snakemake/\nresults/\nlogs/\n", encoding="utf-8")
    git = ["git", "-C", str(project), "-c", "user.name=rodimpact tests", "-c", "user.email=tests@localhost"]
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-q", "-m", "copy of the project"]):
        subprocess.run([*git, *args], check=True, capture_output=True)


#: The studies of a copy: work precision of the three 1-D methods on 'model' (coarsest three
#: levels, timed once), two stress cases without fem_axi, a 2 x 2 stability map.
SMALL_STRESS = ("short_rod", "rubber_on_steel")
#: Points of the Table 2 ball sweep in a copy (per rod geometry variant).
SMALL_SWEEP = 3


def _small_studies(project: Path) -> None:
    """Shrink config.yaml's studies, the stress cases and the Table 2 sweep (comments are
    lost: copies only)."""
    config = project / "config" / "config.yaml"
    document = yaml.safe_load(config.read_text(encoding="utf-8"))
    study = document["work_precision"]
    study["cases"] = ["model"]
    study["timing"] = {"min_repeats": 1, "min_total_s": 0.0, "max_total_s": 0.0}
    study["methods"] = {m: {**spec, "levels": spec["levels"][:3]}
                        for m, spec in study["methods"].items() if m != "fem_axi"}
    document["stability"]["map"].update(mass_kg=[1.0e-3, 1.0e-2], impedance_kg_s=[3.0, 1000.0])
    config.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    stress = project / "config" / "cases" / "stress.yaml"
    document = yaml.safe_load(stress.read_text(encoding="utf-8"))
    document["cases"] = [c for c in document["cases"] if c["id"] in SMALL_STRESS]
    for case in document["cases"]:
        case["methods"] = ["sem", "sem_paper", "fem1d"]
    stress.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    table2 = project / "config" / "cases" / "table2.yaml"  # edited as text: tests add rows to it
    text = table2.read_text(encoding="utf-8")
    sweep = "ball_diameter_m: {start: 1.0e-3, stop: 20.0e-3, num: 25, spacing: log}"
    assert text.count(sweep) == 1, "the ball sweep's line of table2.yaml moved"
    text = text.replace(sweep, sweep.replace("num: 25", f"num: {SMALL_SWEEP}"))
    film_sweep = "ball_diameter_m: {start: 1.0e-3, stop: 20.0e-3, num: 13, spacing: log}"
    assert text.count(film_sweep) == 1, "the film sweep's line of table2.yaml moved"
    text = text.replace(film_sweep, film_sweep.replace("num: 13", "num: 2"))
    for variant in DROPPED_FILM_VARIANTS:  # a variant's block runs to the next one's name
        block = re.search(rf"\n  {variant}:\n(?:    .*\n|\s*\n)*?(?=  \w+:\n|  # )", text)
        assert block, f"the variant {variant} of table2.yaml moved"
        text = text.replace(block.group(0), "\n")
    table2.write_text(text, encoding="utf-8")


def clone_built(built: Path, dest: Path) -> Path:
    """A copy of a built project: results, logs and .snakemake metadata, mtimes preserved."""
    shutil.copytree(built, dest, symlinks=True)
    return dest


class Run:
    """A finished snakemake process; ``output`` is stdout and stderr together."""

    def __init__(self, proc: subprocess.CompletedProcess):
        self.returncode, self.stdout, self.stderr = proc.returncode, proc.stdout, proc.stderr
        self.output = proc.stdout + proc.stderr
        self.args = proc.args

    def describe(self) -> str:
        tail = self.output[-6000:]
        return f"snakemake {' '.join(map(str, self.args[4:]))} -> exit {self.returncode}\n{tail}"


def snakemake(project: Path, *args: str, timeout: float = DRY_RUN_TIMEOUT_S) -> Run:
    """Run the snakemake CLI of this interpreter's environment in ``project``."""
    env = {key: value for key, value in os.environ.items()
           if not key.startswith("SNAKEMAKE") and key != "PYTHONPATH"}
    env.update(MPLBACKEND="Agg")
    proc = subprocess.run(
        [sys.executable, "-m", "snakemake", "--nocolor", *args],
        cwd=project, env=env, capture_output=True, text=True, timeout=timeout, check=False,
    )  # fmt: skip
    return Run(proc)


def job_stats(output: str) -> dict[str, int]:
    """Jobs per rule from snakemake's "Job stats" table (empty when nothing is planned).

    Why this table: it is what snakemake itself counts from the DAG it would execute, for
    dry runs and real runs alike, and its layout (``job count`` header, dashes, one
    ``<rule> <n>`` line per rule, ``total <n>``) has been stable since snakemake 7. The
    per-job blocks are not used because snakemake 9 prints them twice in a dry run. The table
    may also be printed more than once; every copy must agree and sum to its total.
    """
    tables = []
    for match in re.finditer(r"^Job stats:\n(.*?)^total\s+(\d+)\s*$", output, re.M | re.S):
        rows = {}
        for line in match.group(1).splitlines():
            row = re.fullmatch(r"(\S+)\s+(\d+)", line.strip())
            if row and row.group(1) != "job":
                rows[row.group(1)] = int(row.group(2))
        assert sum(rows.values()) == int(match.group(2)), f"inconsistent job stats:\n{match.group(0)}"
        tables.append(rows)
    assert all(table == tables[0] for table in tables), f"job stats tables differ: {tables}"
    return tables[0] if tables else {}


def summary(project: Path, *targets: str) -> list[dict[str, str]]:
    """``snakemake --summary``: one row per output file of the DAG of ``targets``.

    Tab-separated, with columns output_file, date, rule, log-file(s), status and plan;
    ``plan`` is "update pending" for files that would be (re)built. This names the exact
    files a run would write, which the job counts alone cannot.
    """
    run = snakemake(project, "--summary", *targets)
    assert run.returncode == 0, run.describe()
    lines = [line.split("\t") for line in run.stdout.splitlines() if line.count("\t") == 5]
    assert lines and lines[0][0] == "output_file", run.describe()
    header = lines[0]
    return [dict(zip(header, line)) for line in lines[1:]]


def pending(rows: list[dict[str, str]], rule: str | None = None) -> set[str]:
    """Output files a run would (re)build, optionally of one rule only."""
    return {
        row["output_file"]
        for row in rows
        if row["plan"] == "update pending" and (rule is None or row["rule"] == rule)
    }


def project_cases(project: Path):
    """The resolved project of a copy, as the workflow sees it."""
    config = load_global_config(project / "config" / "config.yaml")
    return load_project(config, root=project)


def run_path(case_id: str, method: str) -> str:
    return f"results/runs/{case_id}/{method}.h5"


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


# --------------------------------------------------------------------------------------------
# the shared full build
# --------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A copy of the project after ``snakemake -j2`` (the whole paper). Never modified."""
    project = copy_project(tmp_path_factory.mktemp("built") / "project")
    run = snakemake(project, "-j2", timeout=BUILD_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    return project


@pytest.fixture(scope="module")
def expected(built: Path) -> dict:
    """What the build must contain, from the copy's configuration."""
    project = project_cases(built)
    model = project.cases["model"]
    by_variant = {
        v: [run_path(c["id"], m) for c in project.cases_in("table2", v) for m in c["methods"]]
        for v in ALL_VARIANTS
    }
    runs = [run_path(c["id"], m) for name in ("model", "table2")
            for c in project.cases_in(name) for m in c["methods"]]  # fmt: skip
    # The paper: 'model' with four methods, six balls x four rod readings with three; the text's
    # rod with the film by three methods, with the calibrated law by sem, with and without film.
    assert sorted(project.variants["table2"]) == sorted(ALL_VARIANTS)
    assert [len(by_variant[v]) for v in ALL_VARIANTS] == [18, 18, 18, 18, 18, 6, 6]
    assert len(runs) == 4 + 5 * 18 + 2 * 6
    return {
        "project": project,
        "runs": runs,
        "model_runs": [run_path("model", m) for m in model["methods"]],
        "table2_runs": by_variant,
    }


@pytest.fixture(scope="module")
def stored_hashes(built: Path, expected: dict) -> dict[str, str]:
    """config_sha256 of every run, read straight from the HDF5 root attributes."""
    hashes = {}
    for path in expected["runs"]:
        with h5py.File(built / path, "r") as h5:
            value = h5.attrs["config_sha256"]
        hashes[path] = value.decode() if isinstance(value, bytes) else str(value)
    return hashes


def assert_inputs_match(inputs: list[dict], runs: list[str], hashes: dict[str, str]) -> None:
    """A provenance record lists exactly ``runs``, each with the hash stored in the run."""
    assert sorted(entry["path"] for entry in inputs) == sorted(runs)
    for entry in inputs:
        assert entry["config_sha256"] == hashes[entry["path"]], entry["path"]
        case_id, method = Path(entry["path"]).parent.name, Path(entry["path"]).stem
        assert (entry["case_id"], entry["method"]) == (case_id, method)


# --------------------------------------------------------------------------------------------
# 1. the full build
# --------------------------------------------------------------------------------------------


def test_full_build_produces_every_artifact(built: Path, expected: dict) -> None:
    artifacts = [
        *(f"results/tables/table2_{v}.{ext}" for v in ALL_VARIANTS
          for ext in ("csv", "md", "tex", "provenance.json")),
        *FILM_ARTIFACTS,
        *(f"results/tables/table2_variants.{ext}" for ext in ("csv", "md", "provenance.json")),
        *(f"results/tables/fig2_comparison.{ext}" for ext in ("csv", "md", "provenance.json")),
        *(f"results/figures/{name}.{ext}"
          for name in ("fig2_contact_force", "fig4_midrod_displacement", "table2_contact_time")
          for ext in ("pdf", "png")),
        *expected["runs"],
        *(f"results/tables/{name}" for name in ("work_precision.csv", "work_precision_orders.csv",
                                                 "work_precision_orders.md", "stability.csv", "stability.md",
                                                 "stability_map.csv")),
        *(f"results/figures/{name}.{ext}" for name in ("work_precision_model", "stability_map")
          for ext in ("pdf", "png")),
        *(f"results/figures/wave_map_{case}.{ext}" for case in WAVE_CASES for ext in ("pdf", "png", "provenance.json")),
    ]  # fmt: skip
    missing = [a for a in artifacts if not (built / a).is_file() or (built / a).stat().st_size == 0]
    assert not missing, f"missing or empty: {missing}"
    # No stray run files, and no temporary file left anywhere under results/.
    stored = sorted(p.relative_to(built).as_posix() for p in (built / "results/runs").rglob("*.h5"))
    assert stored == sorted(expected["runs"])
    assert not [p for p in (built / "results").rglob("*") if ".tmp" in p.name]


def test_every_run_records_the_case_file_it_was_made_from(built: Path, expected: dict) -> None:
    """The chain's first stage: each run's case, with its scales and costs, is a file the run
    names (path, SHA-256 and case hash), and the file holds exactly the run's case."""
    for path in expected["runs"]:
        record = read_summary(built / path)
        reference = record.config["run"]["case_file"]
        assert reference["path"] == f"results/cases/{record.case_id}.yaml"
        case_file = read_case_file(built / reference["path"])
        assert reference["config_sha256"] == case_file["config_sha256"]
        assert case_file["case"] == {key: value for key, value in record.config.items() if key != "run"}
        derived = case_file["derived"]
        assert set(derived["methods"]) == set(record.config["methods"])
        assert derived["rigid_rod"]["contact_time_s"] > 0 and derived["rod"]["impedance_kg_s"] > 0
        for method in derived["methods"].values():
            assert method["time_step_s"] > 0 and method["steps"] > 1 and method["job"]["mem_mb"] >= 500


def test_every_run_file_has_provenance_and_summary(built: Path, expected: dict) -> None:
    for path in expected["runs"]:
        with h5py.File(built / path, "r") as h5:
            assert set(ROOT_ATTRS) <= set(h5.attrs), path
            assert set(SUMMARY_ATTRS) <= set(h5["summary"].attrs), path
        record = read_run(built / path)  # verifies config_sha256 against config_json
        case_id, method = Path(path).parent.name, Path(path).stem
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
    """The studies of the copy: every stress run ok or failed with a message, each level of the
    sweep with its errors and timing, and the map with one class per point and method."""
    stability = pd.read_csv(built / "results/tables/stability.csv")
    assert sorted(set(stability["case_id"])) == sorted(SMALL_STRESS)
    assert len(stability) == 2 * 3
    assert all(v == "ok" or v.startswith("failed: ") for v in stability["verdict"]), stability["verdict"]
    sweep = pd.read_csv(built / "results/tables/work_precision.csv")
    assert sorted(Counter(sweep["method"]).items()) == [("fem1d", 3), ("sem", 3), ("sem_paper", 3)]
    assert (sweep["wall_time_s"] > 0).all() and sweep["err_contact_time"].notna().all()
    assert sweep["machine"].str.contains("logical CPUs").all()
    stability_map = pd.read_csv(built / "results/tables/stability_map.csv")
    assert len(stability_map) == 4 * 2 and stability_map["class"].notna().all()


def test_table2_csvs(built: Path, expected: dict) -> None:
    cases = expected["project"].cases
    for variant, runs in expected["table2_runs"].items():
        table = pd.read_csv(built / f"results/tables/table2_{variant}.csv")
        assert set(TABLE2_COLUMNS) <= set(table.columns), variant
        assert len(table) == 6, variant
        assert sorted(table["case_id"]) == sorted({Path(r).parent.name for r in runs})
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
            # fem_axi, coarse in these copies: the continuum contact, close to the SEM (without
            # the film: with it, the thin-layer law and the continuum differ, docs/contact-laws.md)
            if "fem_axi" in cases[row.case_id]["methods"] and "contact" not in cases[row.case_id]:
                assert row.fem_axi_us == pytest.approx(row.sem_us, rel=0.1)
        assert table["mass_g"].is_monotonic_increasing
        assert table["sem_us"].is_monotonic_increasing, f"{variant}: heavier ball, longer contact"
        assert "ball_3.16mm" in (built / f"results/tables/table2_{variant}.md").read_text()
        assert r"\begin{tabular}" in (built / f"results/tables/table2_{variant}.tex").read_text()
    summary_table = pd.read_csv(built / "results/tables/table2_variants.csv")
    assert sorted(set(summary_table["variant"])) == sorted(ALL_VARIANTS)
    assert sorted(set(summary_table["method"])) == ["fem1d", "fem_axi", "sem"]
    assert (summary_table["n_cases"] == 6).all()


def test_table_provenance_matches_run_files(
    built: Path, expected: dict, stored_hashes: dict[str, str]
) -> None:
    for variant, runs in expected["table2_runs"].items():
        record = json.loads((built / f"results/tables/table2_{variant}.provenance.json").read_text())
        assert_inputs_match(record["inputs"], runs, stored_hashes)
        assert f"results/tables/table2_{variant}.csv" in record["artifacts"]
    record = json.loads((built / "results/tables/table2_variants.provenance.json").read_text())
    all_table2 = [run for runs in expected["table2_runs"].values() for run in runs]
    assert_inputs_match(record["inputs"], all_table2, stored_hashes)


@pytest.mark.parametrize("figure", ["fig2_contact_force", "fig4_midrod_displacement", "table2_contact_time",
                                    *(f"wave_map_{case}" for case in WAVE_CASES)])
def test_figures_carry_provenance(
    built: Path, expected: dict, stored_hashes: dict[str, str], figure: str
) -> None:
    runs = (
        expected["model_runs"]
        if figure in ("fig2_contact_force", "fig4_midrod_displacement")
        else [run_path(figure.removeprefix("wave_map_"), m) for m in ("sem", "fem1d")]
        if figure.startswith("wave_map_")
        else [run for runs in expected["table2_runs"].values() for run in runs]
    )
    with Image.open(built / f"results/figures/{figure}.png") as png:
        png.load()
        assert png.size[0] > 100 and png.size[1] > 100
        from_png = json.loads(png.info["Description"])
    sweeps = [entry for entry in from_png["inputs"] if entry["path"].startswith("results/sweeps/")]
    if figure == "table2_contact_time":  # and the curves of the ball sweep, every variant
        assert len(sweeps) == SMALL_SWEEP * len(TABLE2_VARIANTS) + SMALL_FILM_SWEEP
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


def test_sweep_points_are_runs_and_a_table(built: Path, expected: dict) -> None:
    """The Table 2 ball sweep: one HDF5 run per point and variant, named by its Paramspace
    instance, and a table whose contact times grow with the ball's mass along each curve."""
    project = expected["project"]
    files = sorted(p.relative_to(built).as_posix() for p in (built / "results/sweeps").rglob("*.h5"))
    assert len(files) == SMALL_SWEEP * len(TABLE2_VARIANTS) + SMALL_FILM_SWEEP
    point = r"ball_diameter_m~[0-9.e-]+(_film_modulus_pa~[0-9.e+]+)?"
    assert all(re.fullmatch(rf"results/sweeps/ball_sweep(_film)?-\w+/sem/{point}\.h5", f) for f in files), files
    table = pd.read_csv(built / "results/tables/sweep_table2.csv")
    assert len(table) == len(files) and set(table["variant"]) == {*TABLE2_VARIANTS, "r10_l30_film"}
    film = table[table["sweep"] == "ball_sweep_film-r10_l30_film"]
    assert len(film) == SMALL_FILM_SWEEP and sorted(set(film["film_modulus_pa"])) == [2e9, 3e9, 4e9]
    for modulus, curve in film.groupby("film_modulus_pa"):  # a softer film, a longer contact
        stiffer = film[(film["film_modulus_pa"] > modulus) & film["ball_diameter_m"].isin(curve["ball_diameter_m"])]
        for row in stiffer.itertuples():
            assert row.contact_time_us < curve.loc[curve["ball_diameter_m"] == row.ball_diameter_m,
                                                   "contact_time_us"].item()
    table = table[table["sweep"] != "ball_sweep_film-r10_l30_film"]
    for variant, curve in table.groupby("variant"):
        assert curve["mass_g"].is_monotonic_increasing and curve["contact_time_us"].is_monotonic_increasing, variant
        rho = project.sweeps[f"ball_sweep-{variant}"]["impactor"]["material"]["density_kg_m3"]
        mass = rho * math.pi * curve["ball_diameter_m"] ** 3 / 6 * 1000
        np.testing.assert_allclose(curve["mass_g"], mass, rtol=1e-9)  # the CSV keeps 10 digits
    record = read_run(built / files[0])
    assert record.config["run"]["study"]["name"] == "sweep" and "sweep_point" in record.config


def test_provenance_audit_passes_on_a_fresh_build(built: Path) -> None:
    result = audit(built)
    assert result.success, [f for f in result.findings if not f.ok][:5]
    kinds = Counter(f.kind for f in result.findings)
    assert kinds["run"] >= 76 and kinds["artifact"] >= 20 and not kinds["unknown"], kinds
    # the copy is an untagged history: its version is 0.0.0.post1 (rodimpact._version), plus the commit
    assert all(re.fullmatch(r"\d+\.\d+\.\d+(\.post\d+)?\+g[0-9a-f]{4,40}", v) for f in result.findings for v in f.code_versions)


def test_provenance_audit_fails_on_hand_edits_and_stale_artifacts(built: Path, tmp_path: Path) -> None:
    project = clone_built(built, tmp_path / "project")
    table = project / "results/tables/table2_r1_l30.csv"
    table.write_text(table.read_text().replace("ball_3.16mm", "ball_3.16mm ", 1))
    with h5py.File(project / "results/runs/model/fem1d.h5", "r+") as h5:
        h5["contact_force"][5] *= 1.01
    (project / "results/tables/old_table.csv").write_text("a,b\n1,2\n")
    model_yaml = project / "config/cases/model.yaml"
    model_yaml.write_text(model_yaml.read_text().replace("velocity_m_s: 1.0\n", "velocity_m_s: 1.1\n"))

    proc = subprocess.run([sys.executable, "-m", "rodimpact.tools.audit", "--root", str(project)],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    failed = {}
    for line in proc.stdout.splitlines():
        if line.startswith("FAIL "):
            path, problem = line[5:].split(": ", 1)
            failed.setdefault(path, []).append(problem)
    assert "bytes differ from those recorded" in " ".join(failed["results/tables/table2_r1_l30.csv"])
    assert "its content differs from its data_sha256" in " ".join(failed["results/runs/model/fem1d.h5"])
    assert "no provenance record lists it" in " ".join(failed["results/tables/old_table.csv"])
    assert "not an output of the current workflow" in " ".join(failed["results/tables/old_table.csv"])
    assert "snakemake: params changed" in " ".join(failed["results/runs/model/sem.h5"])
    # what was made from the changed case's runs is planned again
    assert "snakemake: an input is out of date" in " ".join(failed["results/figures/fig2_contact_force.png"])
    untouched = "results/runs/ball_3.16mm-r1_l30/sem.h5"
    assert untouched not in failed and "results/tables/table2_r10_l30.csv" not in failed


# --------------------------------------------------------------------------------------------
# 2. only what a target needs
# --------------------------------------------------------------------------------------------


def test_target_plans_only_its_jobs(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    target = "results/tables/table2_r1_l30.csv"
    run = snakemake(project, "-n", "-j2", target)
    assert run.returncode == 0, run.describe()
    assert job_stats(run.output) == {"case_file": 6, "solve": 18, "table2": 1}, run.describe()
    # Which files: the six r1_l30 balls' case files, their runs by the three methods and the
    # five outputs of the table2 job.
    rows = summary(project, target)
    balls = [c["id"] for c in project_cases(project).cases_in("table2", "r1_l30")]
    assert pending(rows, "solve") == {run_path(ball, m) for ball in balls for m in ("sem", "fem1d", "fem_axi")}
    assert pending(rows, "table2") == {
        f"results/tables/table2_r1_l30.{ext}" for ext in ("csv", "md", "html", "tex", "provenance.json")
    }
    assert pending(rows, "case_file") == {f"results/cases/{ball}.yaml" for ball in balls}
    assert pending(rows) == pending(rows, "case_file") | pending(rows, "solve") | pending(rows, "table2")
    assert not (project / "results").exists(), "a dry run must not write results"


def test_only_the_cases_asking_for_the_field_have_a_wave_map(tmp_path: Path) -> None:
    """The wave map of a case plans the runs of the methods that record the field; a case that
    does not list strain_field has none, and none of its runs pays for it."""
    project = copy_project(tmp_path / "project")
    assert [c for c, case in project_cases(project).cases.items() if "strain_field" in case["outputs"]] == list(
        WAVE_CASES)
    target = "results/figures/wave_map_model.png"
    run = snakemake(project, "-n", "-j2", target)
    assert run.returncode == 0, run.describe()
    assert job_stats(run.output) == {"case_file": 1, "solve": 2, "wave_map": 1}, run.describe()
    assert pending(summary(project, target), "solve") == {run_path("model", m) for m in ("sem", "fem1d")}
    run = snakemake(project, "-n", "-j2", "results/figures/wave_map_ball_4.75mm-r10_l30.png")
    assert run.returncode != 0 and "no rule makes 'results/figures/wave_map_ball_4.75mm-r10_l30.png'" in run.output


# --------------------------------------------------------------------------------------------
# 3. adding a case is adding YAML
# --------------------------------------------------------------------------------------------

NEW_TABLE2_ROW = """
  - id: ball_8.00mm
    description: "Added by a test: steel ball, diameter 8.00 mm, mass 2.09 g"
    impactor:
      mass_kg: 2.09e-3
      radius_m: 4.0e-3
    measured: {contact_time_us: 75.0}
"""

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


def test_new_row_in_table2_yaml_is_computed(built: Path, tmp_path: Path) -> None:
    project = clone_built(built, tmp_path / "project")
    with open(project / "config/cases/table2.yaml", "a", encoding="utf-8") as handle:
        handle.write(NEW_TABLE2_ROW)
    new_case = "ball_8.00mm-r10_l30"

    run = snakemake(project, "-j2", "results/tables/table2_r10_l30.csv", timeout=BUILD_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    # The existing runs are reused: the new ball's case file, its three runs, then the table.
    assert job_stats(run.output) == {"case_file": 1, "solve": 3, "table2": 1}, run.describe()

    record = read_run(project / run_path(new_case, "sem"))
    assert record.config["measured"]["contact_time_us"] == 75.0
    assert record.config["impactor"]["mass_kg"] == pytest.approx(2.09e-3)
    assert record.config["rod"]["radius_m"] == pytest.approx(0.010)  # from the variant

    table = pd.read_csv(project / "results/tables/table2_r10_l30.csv")
    assert len(table) == 7
    new = table[table["case_id"] == new_case]
    assert len(new) == 1, table["case_id"].tolist()
    row = new.iloc[0]
    assert row["measured_us"] == 75.0
    assert row["mass_g"] == pytest.approx(2.09) and row["diameter_mm"] == pytest.approx(8.0)
    assert math.isfinite(row["sem_us"]) and row["sem_us"] > 0
    assert row["sem_us"] == pytest.approx(1e6 * record.summary["contact_time_s"], rel=1e-9)
    assert math.isnan(row["published_sem_us"]) and math.isnan(row["published_fem_us"])
    # Rows are sorted by mass, and the contact time grows with the mass.
    assert table["case_id"].tolist().index(new_case) == 4
    assert table["sem_us"].is_monotonic_increasing
    provenance = json.loads((project / "results/tables/table2_r10_l30.provenance.json").read_text())
    assert run_path(new_case, "sem") in [entry["path"] for entry in provenance["inputs"]]


def test_new_case_file_is_picked_up(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    (project / "config/cases/my_experiment.yaml").write_text(NEW_CASE_FILE, encoding="utf-8")
    target = run_path("my_ball", "sem")
    run = snakemake(project, "-n", "-j2", target)
    assert run.returncode == 0, run.describe()
    assert job_stats(run.output) == {"case_file": 1, "solve": 1}, run.describe()
    assert pending(summary(project, target)) == {target, "results/cases/my_ball.yaml"}
    resolved = project_cases(project)
    assert resolved.sets["my_experiment"] == ["my_ball"]
    assert resolved.cases["my_ball"]["rod"]["area_m2"] == pytest.approx(1.0e-4)


# --------------------------------------------------------------------------------------------
# 4. reruns
# --------------------------------------------------------------------------------------------


def test_rerun_after_full_build_plans_nothing(built: Path) -> None:
    run = snakemake(built, "-n", "-j2")
    assert run.returncode == 0, run.describe()
    assert "Nothing to be done" in run.output, run.describe()
    assert job_stats(run.output) == {}, run.describe()


def test_changed_case_value_reruns_only_that_case(built: Path, tmp_path: Path) -> None:
    project = clone_built(built, tmp_path / "project")
    model_yaml = project / "config/cases/model.yaml"
    text = model_yaml.read_text(encoding="utf-8")
    assert text.count("velocity_m_s: 1.0\n") == 1
    model_yaml.write_text(text.replace("velocity_m_s: 1.0\n", "velocity_m_s: 1.1\n"), encoding="utf-8")

    run = snakemake(project, "-n", "-j2")
    assert run.returncode == 0, run.describe()
    # model's runs and what shows them (its forces handed on too), and the studies built on model: its work-precision
    # levels (3 methods x 3 levels in the copy, a job per method) and the stability map, whose
    # base case it is (2 masses x 3 methods in the copy, a job per mass and method)
    assert job_stats(run.output) == {"case_file": 1, "solve": 4, "fig2": 1, "fig4": 1, "fig2_comparison": 1,
                                     "all": 1, "solve_levels_sem": 1, "solve_levels_sem_paper": 1,
                                     "solve_levels_fem1d": 1, "work_precision_table": 1,
                                     "work_precision_figure": 1, "solve_map_row": 6,
                                     "stability_map": 1, "forces_model": 1, "fig_force_fit": 1,
                                     "wave_map": 1}, run.describe()
    assert pending(rows := summary(project), "case_file") == {"results/cases/model.yaml"}
    assert pending(rows, "solve") == {run_path("model", m) for m in ("sem", "sem_paper", "fem1d", "fem_axi")}
    assert pending(rows, "fig2") == {
        "results/figures/fig2_contact_force.pdf", "results/figures/fig2_contact_force.png",
        "results/figures/fig2_contact_force.provenance.json",
    }  # fmt: skip
    assert not {p for p in pending(rows) if "table2" in p or "ball_" in p}


def test_code_change_reruns_the_solvers(built: Path, tmp_path: Path) -> None:
    project = clone_built(built, tmp_path / "project")
    with open(project / "src/rodimpact/contact/hertz.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")  # content changes, so the checksum changes too

    run = snakemake(project, "-n", "-j2")
    assert run.returncode == 0, run.describe()
    stats = job_stats(run.output)
    assert stats.get("solve") == 4 + 5 * 18 + 2 * 6, run.describe()  # every run of 'model' and Table 2
    assert "Updated input files: src/rodimpact/contact/hertz.py" in run.output
    rows = summary(project)
    assert pending(rows, "solve") == {row["output_file"] for row in rows if row["rule"] == "solve"}


def test_a_methods_code_change_reruns_only_its_runs(built: Path, tmp_path: Path) -> None:
    """A rule depends on its own method's solver (the registry names it): a change to fem_axi
    reruns fem_axi's runs and what shows them, and no run of another method."""
    project = clone_built(built, tmp_path / "project")
    with open(project / "src/rodimpact/solvers/fem_axi/solver.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    rows = summary(project)  # what a run would rebuild, file by file
    reruns = {row["output_file"] for row in rows if row["plan"] == "update pending" and row["output_file"].endswith(".h5")}
    cases = project_cases(project).cases.values()
    # and the runs of the law calibrated by fem_axi's indentation, which reads fem_axi's code
    calibrated = {c["id"] for c in cases if (c.get("contact") or {}).get("law") == "tabulated"}
    assert pending(rows, "solve") == {run_path(c["id"], "fem_axi") for c in cases
                                      if "fem_axi" in c["methods"] and c["set"] in ("model", "table2")} | {
        run_path(case, "sem") for case in calibrated}
    assert pending(rows, "indentation") == {f"results/indentation/{case}.h5" for case in calibrated}
    assert reruns and all("fem_axi" in path or Path(path).parent.name in calibrated
                          or path.startswith("results/indentation/") for path in reruns), sorted(reruns)


def test_figure_code_change_reruns_no_solver(built: Path, tmp_path: Path) -> None:
    """Each rule depends on the modules its script imports, not on the whole package."""
    project = clone_built(built, tmp_path / "project")
    with open(project / "src/rodimpact/present/figures.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    run = snakemake(project, "-n", "-j2")
    assert run.returncode == 0, run.describe()
    stats = job_stats(run.output)
    assert "solve" not in stats, run.describe()
    assert stats.get("fig2") == 1 and stats.get("fig_table2") == 1, run.describe()


# --------------------------------------------------------------------------------------------
# 5. bad input stops everything before any job
# --------------------------------------------------------------------------------------------


def test_jobs_run_the_checkouts_own_code(tmp_path: Path) -> None:
    """A job imports the copy's src/, not the repository's installed package."""
    project = copy_project(tmp_path / "project")
    runner = project / "src" / "rodimpact" / "jobs" / "runner.py"
    runner.write_text(runner.read_text() + '\nraise ImportError("runner.py of the copy")\n')
    run = snakemake(project, "-j1", run_path("model", "sem"), timeout=BUILD_TIMEOUT_S)
    assert run.returncode != 0, run.describe()
    log = (project / "logs" / "runs" / "model" / "sem.log")
    assert "runner.py of the copy" in run.output + (log.read_text() if log.exists() else ""), run.describe()


def _negative_mass(project: Path) -> None:
    path = project / "config/cases/model.yaml"
    text = path.read_text(encoding="utf-8")
    assert text.count("mass_kg: 0.5\n") == 1
    path.write_text(text.replace("mass_kg: 0.5\n", "mass_kg: -0.5\n"), encoding="utf-8")


def _unknown_method(project: Path) -> None:
    path = project / "config/cases/model.yaml"
    text = path.read_text(encoding="utf-8")
    assert text.count("methods: [sem, sem_paper, fem1d, fem_axi]") == 1
    path.write_text(text.replace("methods: [sem, sem_paper, fem1d, fem_axi]", "methods: [sem, fem2d]"),
                    encoding="utf-8")


def _unknown_variant(project: Path) -> None:
    path = project / "config/cases/table2.yaml"
    text = path.read_text(encoding="utf-8")
    anchor = "  - id: ball_4.75mm\n"
    assert text.count(anchor) == 1
    path.write_text(text.replace(anchor, anchor + "    variants: [r10_l30, r2_l30]\n"), encoding="utf-8")


@pytest.mark.parametrize(
    ("break_config", "file", "case", "field"),
    [
        pytest.param(_negative_mass, "config/cases/model.yaml", "model", "impactor.mass_kg", id="negative-mass"),
        pytest.param(_unknown_method, "config/cases/model.yaml", "model", "methods[1]", id="unknown-method"),
        pytest.param(_unknown_variant, "config/cases/table2.yaml", "ball_4.75mm", "variants[1]", id="unknown-variant"),
    ],
)  # fmt: skip
def test_bad_input_stops_before_any_job(
    tmp_path: Path, break_config, file: str, case: str, field: str
) -> None:
    project = copy_project(tmp_path / "project")
    break_config(project)
    run = snakemake(project, "-n", "-j2")
    assert run.returncode != 0, run.describe()
    lines = [line for line in run.output.splitlines() if line.strip()]
    assert len(lines) == 1, f"expected one line, got:\n{run.output}"
    message = lines[0]
    assert message.startswith("rodimpact: invalid configuration: ")
    assert file in message and f"case '{case}'" in message and f"field '{field}'" in message, message
    assert "Traceback" not in run.output
    assert not (project / "results").exists()
    assert not (project / "logs").exists()


# --------------------------------------------------------------------------------------------
# 6. atomic outputs
# --------------------------------------------------------------------------------------------

# A 1 ms step is longer than the whole horizon (1.0001 x the ~0.88 ms contact-time estimate of
# 'model'): the first step ends past the horizon with the first contact not over, so the
# solver reports failure and runner.run_case raises SolverFailed (checked with the library).
FAILING_NUMERICS = """\
    numerics:
      sem: {dt_s: 1.0e-3, max_time_factor: 1.0001}
"""


def test_failing_solver_leaves_no_file(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    with open(project / "config/cases/model.yaml", "a", encoding="utf-8") as handle:
        handle.write(FAILING_NUMERICS)
    target = run_path("model", "sem")
    # --keep-incomplete: snakemake must not be the one that cleans up; the rule itself must
    # never leave a (half-)file behind.
    run = snakemake(project, "-j1", "--keep-incomplete", target, timeout=BUILD_TIMEOUT_S)
    assert run.returncode != 0, run.describe()
    assert "Error in rule solve" in run.output, run.describe()
    log = (project / "logs/runs/model/sem.log").read_text(encoding="utf-8")
    assert "SolverFailed" in log and "before the first contact ended" in log, log
    assert not (project / target).exists()
    run_dir = project / "results/runs/model"
    leftovers = [p.name for p in run_dir.iterdir()] if run_dir.exists() else []
    assert not [name for name in leftovers if ".tmp" in name], leftovers
    assert leftovers == [], leftovers


# --------------------------------------------------------------------------------------------
# 7. the HTML report
# --------------------------------------------------------------------------------------------

REPORT_TIMEOUT_S = 120
REPORT_MAX_BYTES = 20 * 2**20
REPORT_CATEGORIES = {"Paper, Table 2", "Paper, Fig. 2 and Fig. 4", "Error against run time", "Stability",
                     "The force handed on"}
REPORT_MIME = {".csv": "text/csv", ".png": "image/png", ".pdf": "application/pdf"}
#: The attribute through which each tag makes a browser fetch something as the page renders.
FETCHING = {"script": "src", "link": "href", "img": "src", "iframe": "src", "frame": "src",
            "embed": "src", "source": "src", "track": "src", "video": "src", "audio": "src",
            "object": "data", "input": "src"}  # fmt: skip


class _Fetches(HTMLParser):
    """What a page or an HTML fragment makes the browser fetch: (tag, address) pairs that
    are not embedded data. Script bodies are not markup (they hold the embedded libraries)."""

    def __init__(self) -> None:
        super().__init__()
        self.fetched: list[tuple[str, str]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        address = values.get(FETCHING.get(tag, ""))
        if address is not None and not address.startswith("data:"):
            self.fetched.append((tag, address))
        style = values.get("style") or ""
        self.fetched += [(tag, url) for url in re.findall(r"url\(\s*['\"]?([^'\")]+)", style)
                         if not url.startswith("data:")]


def _fetched(markup: str) -> list[tuple[str, str]]:
    parser = _Fetches()
    parser.feed(markup)
    parser.close()
    return parser.fetched


def _report_variable(page: str, name: str):
    """The JSON value of ``var <name> = ...;`` in its own script element of snakemake's
    report page (``<script id="<name, with - for _>">``, the value on one line)."""
    script = name.replace("_", "-")
    match = re.search(rf'<script id="{script}">\s*var {name} = (.*);\s*</script>', page)
    assert match, f"no variable {name} in the report"
    return json.loads(match.group(1))


def _text(fragment: str) -> str:
    """The words of an HTML fragment, whitespace collapsed."""
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", fragment)).split())


def _settings_line(config: dict, method: str) -> str:
    """How a caption states a method's settings: its own settings, from config.yaml."""
    block = config["numerics"][method]
    names = REGISTRY[method].options.names()
    values = ("null" if block.get(key) is None else block[key] for key in names)
    return f"{method}: " + ", ".join(f"{key} = {value}" for key, value in zip(names, values))


def _expected_report(project_dir: Path) -> dict[str, list[str]]:
    """Each report item of the default target, with what its caption must say: key text of
    its template, and values of the copy's own configuration (whose fem_axi level and studies
    differ from the repository's)."""
    config = load_global_config(project_dir / "config" / "config.yaml")
    project = load_project(config, root=project_dir)
    settings = {m: _settings_line(config, m) for m in REGISTRY}
    model, table2 = project.cases["model"]["methods"], project.cases_in("table2")[0]["methods"]
    expected: dict[str, list[str]] = {}
    for variant in ALL_VARIANTS:
        expected[f"results/tables/table2_{variant}.csv"] = [
            f"Table 2 of the paper, rod geometry reading {variant}", "41.66 % to 57.93 %",
            "9.54 % to 49.42 %", '(docs/paper-notes.md, "Impulse responses")', '(docs/paper-notes.md, "The experiment\'s rod")', "table2_variants.csv",
            *(case["id"] for case in project.cases_in("table2", variant)),
            *(settings[m] for m in project.cases_in("table2", variant)[0]["methods"])]
    expected["results/tables/table2_variants.csv"] = [
        "Error against the measurements, per rod geometry reading and method", "Paper's mean error",
        *ALL_VARIANTS, *(settings[m] for m in table2)]
    expected["results/tables/table2_film.csv"] = ["Table 2 with and without the sensor film", "Against the paper"]
    expected["results/tables/film_band.csv"] = ["prediction band", "Against the paper"]
    expected["results/tables/film_indentation.csv"] = ["calibrated by the continuum", "Against the paper"]
    for ext in ("png", "pdf"):
        expected[f"results/figures/film_force.{ext}"] = ["with and without the sensor film", "Against the paper"]
    sweeps = project.sweeps_in("table2") if hasattr(project, "sweeps_in") else []
    sweep_text = ["The continuous curve", *(c["id"] for c in sweeps)] if sweeps else ["No sweep is configured"]
    for name in config["targets"]["sets"]:
        swept = project.sweeps_in(name) if hasattr(project, "sweeps_in") else []
        if swept:
            expected[f"results/tables/sweep_{name}.csv"] = [
                f"Parameter sweeps of the case set {name}", *(c["id"] for c in swept),
                *(settings[m] for m in sorted({m for c in swept for m in c["sweep"]["methods"]}))]
    for ext in ("png", "pdf"):
        expected[f"results/figures/table2_contact_time.{ext}"] = [
            "Contact time against ball mass", *TABLE2_VARIANTS, *sweep_text, "41.66 % to 57.93 %",
            *(settings[m] for m in table2)]
        expected[f"results/figures/fig2_contact_force.{ext}"] = [
            "Fig. 2 of the paper: the contact force P(t)", "11 % in contact time", "9 % in the local extrema",
            "300,000 nodes", "fig2_comparison.csv", *(settings[m] for m in model)]
        expected[f"results/figures/fig4_midrod_displacement.{ext}"] = [
            "Fig. 4 of the paper: the axial displacement of the cross-section at 0.5 of the rod length",
            *(settings[m] for m in model)]
        for case in config["work_precision"]["cases"]:
            expected[f"results/figures/work_precision_{case}.{ext}"] = [
                f"Error against run time, case {case}", "The paper has no such study",
                *(f"{m}: {len(spec['levels'])} levels" for m, spec in config["work_precision"]["methods"].items())]
        spec = config["stability"]["map"]
        expected[f"results/figures/stability_map.{ext}"] = [
            "Stability map of the SEM schemes", f"{spec['steps_per_contact']} steps per Hertz time",
            ", ".join(map(str, spec["mass_kg"])) + " kg",
            f"{len(spec['mass_kg']) * len(spec['impedance_kg_s'])} points",
            "2 Z / k_c(α_H)"]
        expected[f"results/figures/force_fit_model.{ext}"] = [
            "The contact force handed on", "Chebyshev series", "1 % of the largest force"]
        for case in WAVE_CASES:
            grid = project.cases[case]["field_grid"]
            expected[f"results/figures/wave_map_{case}.{ext}"] = [
                "The waves in the rod: the axial strain", case, "The incident wave", "Its reflection at the far end",
                "The superposition during the contact", "The waves left after the separation",
                f"recorded on {grid['sections']} cross-sections", "a superposition of waves propagating",
                *(settings[m] for m in ("sem", "fem1d"))]
    expected["results/tables/stability_map.csv"] = expected["results/figures/stability_map.png"]
    expected["results/tables/fig2_comparison.csv"] = [
        "Fig. 2's numbers", "Contact time vs SEM", "11 % and 9 %", *(settings[m] for m in model)]
    levels = [f"{m}: {len(spec['levels'])} levels" for m, spec in config["work_precision"]["methods"].items()]
    expected["results/tables/work_precision.csv"] = ["Every level of the error-against-run-time study", *levels]
    expected["results/tables/work_precision_orders.csv"] = ["Observed orders of convergence", *levels]
    stress = [c for name in config["stability"]["sets"] for c in project.cases_in(name)]
    expected["results/tables/stability.csv"] = [
        "Stability on stiff and extreme cases", "verdict", *(c["id"] for c in stress),
        *(f"{m}: relative contact-time error {tolerance['contact_time']}"
          for m, tolerance in config["stability"]["tolerances"].items()),
        *(settings[m] for m in sorted({m for c in stress for m in c["methods"]}))]
    return expected


def test_report_captions_name_no_method_or_setting() -> None:
    """The captions take each method's settings from the configuration (whose numerics blocks
    hold exactly each method's own, generated from the registry): no caption lists them."""
    templates = sorted((REPO_ROOT / "workflow" / "report").glob("*.rst"))
    assert len(templates) >= 10
    for path in templates:
        text = path.read_text(encoding="utf-8")
        assert "own_settings" not in text and '"tolerance", "energy_tolerance"' not in text, path.name


def test_report_is_self_contained_and_captioned(built: Path, tmp_path: Path) -> None:
    """``snakemake --report``: one HTML file that fetches nothing, with every table and figure
    of the default target, each captioned from the live configuration, and the description."""
    project = clone_built(built, tmp_path / "p")
    run = snakemake(project, "--report", "report.html", timeout=REPORT_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    report = project / "report.html"
    assert 0 < report.stat().st_size < REPORT_MAX_BYTES, report.stat().st_size
    page = report.read_text(encoding="utf-8")
    # Self-contained: no element fetches anything (snakemake inlines its libraries and styles
    # and embeds every result as a data: URI), and no stylesheet imports one.
    assert _fetched(page) == []
    assert not re.search(r"@import\s+(url\()?\s*['\"]?(https?:)?//", page)

    results = _report_variable(page, "results")
    expected = _expected_report(project)
    assert sorted(results) == sorted(expected)
    categories = _report_variable(page, "categories")
    swept = any(path.startswith("results/tables/sweep_") for path in expected)
    assert set(categories) == REPORT_CATEGORIES | ({"Parameter sweeps"} if swept else set())
    for path, result in results.items():
        assert result["name"] == Path(path).name
        assert result["data_uri"].startswith(f"data:{result['mime_type']};")
        assert result["mime_type"] == REPORT_MIME[Path(path).suffix]
        assert "system-message" not in result["caption"], f"{path}: reStructuredText error in its caption"
        assert _fetched(result["caption"]) == [], path
        caption = _text(result["caption"])
        missing = [phrase for phrase in expected[path] if phrase not in caption]
        assert not missing, f"{path}: caption lacks {missing}:\n{caption}"
    # the tables shown in their captions are the artifacts' own HTML tables, rounded
    shown = [*(f"table2_{v}" for v in ALL_VARIANTS), "table2_variants", "fig2_comparison",
             *(Path(p).stem for p in expected if p.startswith("results/tables/sweep_"))]
    for stem in shown:
        table = _text((project / f"results/tables/{stem}.html").read_text(encoding="utf-8"))
        assert table and table in _text(results[f"results/tables/{stem}.csv"]["caption"]), stem
    table = _text((project / "results/tables/work_precision_orders.html").read_text(encoding="utf-8"))
    assert table and table in _text(results["results/tables/work_precision_orders.csv"]["caption"])

    description = _report_variable(page, "workflow_desc")
    assert "system-message" not in description and _fetched(description) == []
    text = _text(description)
    for phrase in ["rodimpact: the axial impact of a rigid body on an elastic rod", "DOI 10.18721/JPM.11115",
                   *REPORT_CATEGORIES]:
        assert phrase in text, f"the description lacks {phrase!r}:\n{text}"
