"""The static import graph that decides which code changes rerun which rules."""

from pathlib import Path

import pytest

from rodimpact.plumbing.sources import module_sources

SRC = Path(__file__).resolve().parents[1] / "src"


def names(files):
    return {Path(f).relative_to(SRC / "rodimpact").as_posix() for f in files}


def test_solver_closure_has_the_physics_and_not_the_presentation():
    files = names(module_sources(SRC, ["rodimpact.jobs.runner"]))
    assert {"jobs/runner.py", "storage/runs.py", "contact/hertz.py", "model/responses.py",
            "solvers/registry.py", "solvers/sem/options.py", "__init__.py"} <= files
    assert not any(f.startswith("present/") for f in files) and "tools/bench.py" not in files


def test_presentation_closure_has_no_solver():
    files = names(module_sources(SRC, ["rodimpact.present.artifacts"]))
    assert {"present/artifacts.py", "present/figures.py", "present/tables.py", "storage/runs.py", "storage/atomic.py"} <= files
    assert not any(f.endswith(("solver.py", "stepper.py")) for f in files)


def test_unknown_entry_module_is_an_error():
    with pytest.raises(ModuleNotFoundError, match="entry_modules"):
        module_sources(SRC, ["rodimpact.nope"])
