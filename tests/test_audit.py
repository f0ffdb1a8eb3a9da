"""The provenance audit (make provenance): what resolves, and every way a file can fail to."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

from rodimpact.storage.bands import CaseBand, write_band
from rodimpact.storage.faults import REBUILD_HINT
from rodimpact.storage.provenance import library_versions
from rodimpact.storage.runs import read_summary, write_run, write_runs
from rodimpact.storage.sidecar import write_provenance
from rodimpact.tools import audit as audit_module
from rodimpact.tools.audit import audit, audit_run, audit_sidecar, code_problems

from helpers.repo import ROOT

HEAD = subprocess.run(
    ["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=True
).stdout.strip()
VERSION = f"0.1.0+g{HEAD}"


def _run(path: Path, *, velocity: float = 1.0, version: str = VERSION) -> Path:
    """A small run file with every kind of summary value (bool, int, str, float, arrays)."""
    t = np.linspace(0.0, 1e-4, 50)
    return write_run(
        path,
        config={"id": "c1", "impactor": {"velocity_m_s": velocity}, "run": {"method": "sem"}},
        method="sem",
        series={
            "time": (t, "s", "time"),
            "contact_force": (np.sin(t * 3e4), "N", "force"),
            "stations": (np.outer(t, [1.0, 2.0]), "m", "two stations"),
        },
        summary={
            "contact_time_s": 1e-4,
            "peak_force_N": np.array([1.0, 0.5]),
            "peak_time_s": np.array([2e-5, 6e-5]),
            "rebound_velocity_m_s": -0.9,
            "energy_error": 1e-7,
            "success": True,
            "n_steps": 49,
            "status": "completed",
            "contact_end_s": np.empty(0),
        },
        wall_time_s=0.1,
        code_version=version,
    )


@pytest.fixture
def run(tmp_path: Path) -> Path:
    return _run(tmp_path / "results" / "runs" / "c1" / "sem.h5")


def test_an_untouched_run_resolves(run: Path) -> None:
    finding = audit_run(run, library_versions(), ROOT)
    assert finding.ok, finding.problems
    assert finding.code_versions == (VERSION,) and len(finding.config_sha256[0]) == 64


@pytest.mark.parametrize(
    "edit",
    [
        lambda h5: h5["contact_force"].__setitem__(3, 7.0),
        lambda h5: h5["stations"].__setitem__((4, 1), 0.0),
        lambda h5: h5["summary"].attrs.__setitem__("contact_time_s", 1.1e-4),
        lambda h5: h5["summary"].attrs.__setitem__("success", False),
        lambda h5: h5["contact_force"].attrs.__setitem__("units", "kN"),
    ],
    ids=["dataset", "2-D dataset", "summary number", "summary flag", "units"],
)
def test_a_run_edited_after_writing_is_caught(run: Path, edit) -> None:
    with h5py.File(run, "r+") as h5:
        edit(h5)
    finding = audit_run(run, library_versions(), ROOT)
    assert finding.problems == (
        f"its content differs from its data_sha256 (changed after it was written) ({REBUILD_HINT})",
    )
    assert run.stat().st_mtime == 0.0  # marked: snakemake's modification-time check remakes it


def test_every_run_of_a_file_of_runs_is_audited_and_a_changed_one_named(tmp_path: Path, run: Path) -> None:
    """A sweep's part: each of its runs checked as a run file is; a run edited after it was
    written is named (by its name in the file), and the file, the job's output, is marked."""
    part = tmp_path / "results" / "sweeps" / "s" / "sem" / "part0.h5"
    record = read_summary(run)
    series = {"time": (np.linspace(0.0, 1e-4, 50), "s", "time")}
    summary = {key: record.summary[key] for key in ("contact_time_s", "peak_force_N", "peak_time_s")}
    summary.update(rebound_velocity_m_s=-0.9, energy_error=1e-7)
    with write_runs(part) as writer:
        for name in ("p~1", "p~2"):
            config = {"id": f"s.{name}", "run": {"method": "sem"}}
            writer.add(name, config=config, method="sem", series=series, summary=summary, wall_time_s=0.1,
                       code_version=VERSION)  # fmt: skip
    finding = audit_run(part, library_versions(), ROOT)
    assert finding.ok, finding.problems
    assert finding.code_versions == (VERSION,) and len(finding.config_sha256) == 2
    with h5py.File(part, "r+") as h5:
        h5["p~2/time"][3] = 7.0
    finding = audit_run(part, library_versions(), ROOT)
    assert finding.problems == (
        f"run p~2: its content differs from its data_sha256 (changed after it was written) ({REBUILD_HINT})",
    )
    assert part.stat().st_mtime == 0.0


def test_an_edited_config_is_caught(run: Path) -> None:
    with h5py.File(run, "r+") as h5:
        h5.attrs["config_json"] = h5.attrs["config_json"].replace("1.0", "1.5")
    assert audit_run(run, library_versions(), ROOT).problems[0].startswith("config_sha256 mismatch")


@pytest.mark.parametrize(
    "version, problem",
    [
        ("0.1.0+unknown", "unknown"),
        (f"{VERSION}.dirty", "uncommitted"),
        ("0.1.0+gdeadbee", "not in this repository"),
    ],
)
def test_code_that_cannot_be_named_does_not_resolve(version: str, problem: str) -> None:
    (message,) = code_problems(version, ROOT)
    assert problem in message
    assert code_problems(VERSION, ROOT) == []


def test_other_library_versions_do_not_resolve(run: Path) -> None:
    libraries = {**library_versions(), "numpy": "1.0.0"}
    (problem,) = audit_run(run, libraries, ROOT).problems
    assert problem.startswith("made with other library versions: numpy ") and "(now 1.0.0)" in problem


def _table(tmp_path: Path, runs: list[Path]) -> tuple[Path, Path]:
    csv, sidecar = tmp_path / "results/tables/t.csv", tmp_path / "results/tables/t.provenance.json"
    csv.parent.mkdir(parents=True, exist_ok=True)
    csv.write_text("a,b\n1,2\n")
    write_provenance(
        sidecar.relative_to(tmp_path),
        [read_summary(r.relative_to(tmp_path)) for r in runs],
        [csv.relative_to(tmp_path)],
    )
    return csv, sidecar


def _by_path(findings) -> dict:
    return {f.path: f for f in findings}


def test_a_table_resolves_through_its_sidecar(tmp_path: Path, run: Path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("rodimpact.storage.sidecar.code_version", lambda: VERSION)
    _table(tmp_path, [run])
    found = _by_path(audit_sidecar("results/tables/t.provenance.json", {}, ROOT))
    assert found["results/tables/t.csv"].ok and found["results/tables/t.provenance.json"].ok
    assert found["results/tables/t.csv"].config_sha256 == (read_summary(run).config_sha256,)


def test_a_hand_edited_table_and_a_table_older_than_its_run(tmp_path: Path, run: Path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("rodimpact.storage.sidecar.code_version", lambda: VERSION)
    csv, _ = _table(tmp_path, [run])
    csv.write_text("a,b\n1,3\n")
    found = _by_path(audit_sidecar("results/tables/t.provenance.json", {}, ROOT))
    assert found["results/tables/t.csv"].problems == (
        "bytes differ from those recorded when it was written (edited by hand?)",
    )
    _run(run, velocity=2.0)  # the run is remade with another config; the table is not
    found = _by_path(audit_sidecar("results/tables/t.provenance.json", {}, ROOT))
    assert "now has another config" in found["results/tables/t.provenance.json"].problems[0]


def test_audit_covers_every_file_and_flags_strays(tmp_path: Path, run: Path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("rodimpact.storage.sidecar.code_version", lambda: VERSION)
    monkeypatch.setattr(audit_module, "find_repo_root", lambda start=None: ROOT)
    _table(tmp_path, [run])
    (tmp_path / "results/report.html").write_text("<html></html>")  # exempt: a view of the artifacts
    (tmp_path / "results/report_screenshot.png").write_bytes(b"")  # exempt: a view of the report
    (tmp_path / "results/tables/stray.csv").write_text("x\n")
    (tmp_path / "results/runs/c1/sem.h5.tmp.123.ab").write_bytes(b"")
    result = audit(tmp_path, workflow=False)
    found = _by_path(result.findings)
    assert sorted(found) == [
        "results/runs/c1/sem.h5",
        "results/runs/c1/sem.h5.tmp.123.ab",
        "results/tables/stray.csv",
        "results/tables/t.csv",
        "results/tables/t.provenance.json",
    ]
    assert found["results/tables/stray.csv"].problems == ("no provenance record lists it",)
    assert "temporary file" in found["results/runs/c1/sem.h5.tmp.123.ab"].problems[-1]
    assert not result.success and "3 resolve to their config and code, 2 do not" in result.message
    (tmp_path / "results/tables/stray.csv").unlink()
    (tmp_path / "results/runs/c1/sem.h5.tmp.123.ab").unlink()
    assert audit(tmp_path, workflow=False).success


def test_cli_writes_every_finding(tmp_path: Path, run: Path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(audit_module, "find_repo_root", lambda start=None: ROOT)
    out = tmp_path / "logs" / "audit.json"
    assert audit_module.main(["--root", str(tmp_path), "--no-workflow", "--json", str(out)]) == 0
    report = json.loads(out.read_text())
    assert report["success"] and [f["path"] for f in report["findings"]] == ["results/runs/c1/sem.h5"]


def test_a_benchmark_table_resolves_without_input_runs(tmp_path: Path, monkeypatch) -> None:
    import pandas as pd

    from rodimpact.tools.bench import write_benchmark

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("rodimpact.storage.sidecar.code_version", lambda: VERSION)
    write_benchmark(
        pd.DataFrame({"steps": [1, 2], "wall_time_s": [0.1, 0.2]}),
        csv="results/benchmarks/b.csv",
        provenance="results/benchmarks/b.provenance.json",
    )
    found = _by_path(audit_sidecar("results/benchmarks/b.provenance.json", {}, ROOT))
    assert found["results/benchmarks/b.csv"].ok and found["results/benchmarks/b.provenance.json"].ok


@pytest.mark.parametrize(
    "where",
    [
        "studies/film_band_rod_film.h5",
        "studies/film_band_axes_rod_film.h5",
        "studies/sensor_band/rod_sensor/c1.h5",
        "studies/sensor_band_axes/rod_sensor/c1.h5",
    ],
)
def test_every_band_file_is_audited_as_a_band(tmp_path: Path, monkeypatch, where: str) -> None:
    """The default build's bands and the named targets' bands with their axes (make film-axes,
    make sensor-axes) are band files, their data checked against their hash, not runs."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("rodimpact.storage.provenance.code_version", lambda: VERSION)
    monkeypatch.setattr(audit_module, "find_repo_root", lambda start=None: ROOT)
    band = CaseBand("c1", 36.0, 33.0, np.ones((2, 1)), np.array([30.0, 38.0]), {}, {}, ("film_thickness_m",))
    path = write_band(tmp_path / "results" / where, [band], variant="rod_film", method="sem", config=[])
    found = _by_path(audit(tmp_path, workflow=False).findings)
    assert found[f"results/{where}"].kind == "band" and found[f"results/{where}"].ok
    with h5py.File(path, "r+") as h5:  # a hand-edited band no longer matches its hash
        h5["c1/corner_us"][0] = 31.0
    assert not _by_path(audit(tmp_path, workflow=False).findings)[f"results/{where}"].ok


@pytest.mark.workflow
def test_a_named_targets_files_resolve_by_their_record_outside_snakemake(tmp_path: Path, monkeypatch) -> None:
    """make sensor-plastic's files (written outside snakemake, with their provenance record) are
    not asked of snakemake; a file elsewhere that no rule makes still is (snakemake's answer
    stubbed: nothing is an output)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("rodimpact.storage.sidecar.code_version", lambda: VERSION)
    monkeypatch.setattr(audit_module, "find_repo_root", lambda start=None: ROOT)
    monkeypatch.setattr(audit_module, "workflow_status", lambda root, targets=(): {})
    out = tmp_path / "results" / "sensor_plastic"
    out.mkdir(parents=True)
    (out / "sensor_plastic.md").write_text("# table\n")
    write_provenance(out / "sensor_plastic.provenance.json", [], ["results/sensor_plastic/sensor_plastic.md"])
    assert audit(tmp_path, workflow=True).success
    (tmp_path / "results/tables").mkdir(parents=True)
    (tmp_path / "results/tables/t.md").write_text("# table\n")
    write_provenance(tmp_path / "results/tables/t.provenance.json", [], ["results/tables/t.md"])
    found = _by_path(audit(tmp_path, workflow=True).findings)
    assert found["results/sensor_plastic/sensor_plastic.md"].ok
    assert "not an output of the current workflow" in found["results/tables/t.md"].problems[-1]
