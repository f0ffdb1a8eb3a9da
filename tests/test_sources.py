"""The static import graph that decides which code changes rerun which rules."""

from pathlib import Path

import pytest

from rodimpact.plumbing.sources import module_sources, source_digest

SRC = Path(__file__).resolve().parents[1] / "src"


def names(files):
    return {Path(f).relative_to(SRC / "rodimpact").as_posix() for f in files}


def test_solver_closure_has_the_physics_and_not_the_presentation():
    files = names(module_sources(SRC, ["rodimpact.jobs.runner"]))
    assert {
        "jobs/runner.py",
        "storage/runs.py",
        "contact/hertz.py",
        "model/responses.py",
        "solvers/registry.py",
        "solvers/sem/options.py",
        "__init__.py",
    } <= files
    assert not any(f.startswith("present/") for f in files) and "tools/bench.py" not in files


def test_presentation_closure_has_no_solver():
    files = names(module_sources(SRC, ["rodimpact.present.artifacts"]))
    assert {
        "present/artifacts.py",
        "present/figures.py",
        "present/tables.py",
        "storage/runs.py",
        "storage/atomic.py",
    } <= files
    assert not any(f.endswith(("solver.py", "stepper.py")) for f in files)


def test_unknown_entry_module_is_an_error():
    with pytest.raises(ModuleNotFoundError, match="entry_modules"):
        module_sources(SRC, ["rodimpact.nope"])


def _package_copy(tmp_path: Path) -> Path:
    import shutil

    copy = tmp_path / "src"
    shutil.copytree(SRC / "rodimpact", copy / "rodimpact", ignore=shutil.ignore_patterns("__pycache__"))
    return copy


def test_the_digest_follows_exactly_the_closure(tmp_path):
    """A rule's code param: another checkout of the same code has the same digest; a change to a
    file the closure holds changes it, a change to any other file does not."""
    copy = _package_copy(tmp_path)
    solver = ["rodimpact.jobs.runner", "rodimpact.solvers.fem_axi.solver"]
    before = source_digest(copy, solver)
    assert before == source_digest(SRC, solver) and len(before) == 64
    with open(copy / "rodimpact/present/figures.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    assert source_digest(copy, solver) == before
    with open(copy / "rodimpact/solvers/fem_axi/solver.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    assert source_digest(copy, solver) != before
    # and the presentation's digest moved with the figure's file, not with the solver's
    assert source_digest(copy, ["rodimpact.present.artifacts"]) != source_digest(SRC, ["rodimpact.present.artifacts"])


def test_a_module_imported_anew_enters_the_digest(tmp_path):
    copy = _package_copy(tmp_path)
    entry = ["rodimpact.jobs.logs"]
    before = source_digest(copy, entry)
    assert not any(f.endswith("present/figures.py") for f in module_sources(copy, entry))
    with open(copy / "rodimpact/jobs/logs.py", "a", encoding="utf-8") as handle:
        handle.write("\nimport rodimpact.present.figures  # noqa: E402\n")
    assert any(f.endswith("present/figures.py") for f in module_sources(copy, entry))
    assert source_digest(copy, entry) != before
