"""The ``rodimpact`` console command (rodimpact.tools.cli): ``run`` and its one-line errors."""

from __future__ import annotations

import io
import json
import re
import tomllib
from pathlib import Path

import pytest
import yaml

import rodimpact
from rodimpact.jobs.runner import run_case
from rodimpact.tools.cli import main, run_file

from helpers.repo import ROOT


@pytest.fixture
def case_file(tmp_path: Path) -> Path:
    """The model case, SEM only, in a file outside config/cases."""
    document = yaml.safe_load((ROOT / "config" / "cases" / "model.yaml").read_text(encoding="utf-8"))
    document["cases"][0]["methods"] = ["sem"]
    path = tmp_path / "mine.yaml"
    path.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    return path


def test_run_prints_the_summary_of_each_run(case_file: Path, shipped_project) -> None:
    out = io.StringIO()
    assert run_file(case_file, ROOT, None, None, out) == 0
    (line,) = out.getvalue().splitlines()
    expected = run_case(shipped_project.cases["model"], "sem")
    shown = float(re.search(r"contact\s+([0-9.e+-]+) us", line).group(1))
    assert line.startswith("model") and " sem " in line and "completed" in line
    assert shown == pytest.approx(1e6 * expected.contact_time_s, rel=1e-3)  # printed to 4 digits


@pytest.mark.parametrize(
    "args, expected",
    [
        (["--case", "nosuch"], "rodimpact: no case 'nosuch' in "),
        (["--method", "fem_axi"], "rodimpact: case 'model' does not run 'fem_axi'; its methods: sem"),
    ],
)
def test_run_refuses_what_the_file_does_not_hold_in_one_line(case_file: Path, capsys, args, expected) -> None:
    assert main(["run", str(case_file), "--root", str(ROOT), *args]) == 1
    err = capsys.readouterr().err
    assert err.startswith(expected) and err.count("\n") == 1


def test_run_checks_the_file_as_the_workflow_does(case_file: Path, capsys) -> None:
    case_file.write_text(
        case_file.read_text(encoding="utf-8").replace("mass_kg: 0.5", "mass_kg: -0.5"), encoding="utf-8"
    )
    assert main(["run", str(case_file), "--root", str(ROOT)]) == 1
    err = capsys.readouterr().err
    assert err.startswith("rodimpact: invalid configuration: ") and "field 'impactor.mass_kg': must be > 0" in err
    assert err.count("\n") == 1


def test_version_is_the_packages(capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"rodimpact {rodimpact.__version__}"


def test_pyproject_declares_the_direct_dependencies_and_the_command() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    pinned = [
        line.split("#")[0].strip() for line in (ROOT / "requirements.in").read_text(encoding="utf-8").splitlines()
    ]
    checks = {"pytest", "ruff", "snakefmt"}  # make test's: the test extra
    tools = {*checks, "setuptools", "wheel", "setuptools-scm"}  # and the build backend: not runtime
    runtime = [p for p in pinned if p and re.split(r"[=<>]", p)[0] not in tools]
    assert project["dependencies"] == runtime
    assert project["optional-dependencies"]["test"] == [p for p in pinned if p and re.split(r"[=<>]", p)[0] in checks]
    assert project["scripts"]["rodimpact"] == "rodimpact.tools.cli:main"


def test_audit_takes_its_options_after_the_command(tmp_path: Path, capsys) -> None:
    """``rodimpact audit --root DIR --no-workflow --json FILE``, as its help lists them: an empty
    project has nothing to audit, and the options reach the audit."""
    (tmp_path / "results").mkdir()
    report = tmp_path / "audit.json"
    status = main(["audit", "--root", str(tmp_path), "--no-workflow", "--json", str(report)])
    out = capsys.readouterr().out
    assert status == 0 and out == "0 files audited: 0 resolve to their config and code, 0 do not; code versions: none\n"
    assert json.loads(report.read_text(encoding="utf-8")) == {"success": True, "findings": []}
