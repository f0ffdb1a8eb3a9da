"""The static import graph that decides which code changes rerun which rules."""

from pathlib import Path

import pytest

from rodimpact.sources import module_sources

SRC = Path(__file__).resolve().parents[1] / "src"


def names(files):
    return {Path(f).relative_to(SRC / "rodimpact").as_posix() for f in files}


def test_solver_closure_has_the_physics_and_not_the_presentation():
    files = names(module_sources(SRC, ["rodimpact.runner"]))
    assert {"runner.py", "store.py", "hertz.py", "responses.py", "sem/solver.py", "sem/history.py",
            "sem/__init__.py", "__init__.py"} <= files
    assert not files & {"figures.py", "tables.py", "bench.py", "artifacts.py"}


def test_presentation_closure_has_no_solver():
    files = names(module_sources(SRC, ["rodimpact.artifacts"]))
    assert {"artifacts.py", "figures.py", "tables.py", "store.py", "atomic.py"} <= files
    assert not any(f.startswith("sem/") for f in files)


def test_unknown_entry_module_is_an_error():
    with pytest.raises(ModuleNotFoundError, match="entry_modules"):
        module_sources(SRC, ["rodimpact.nope"])
