"""The fixtures the tests share: the repository root, the materials of the paper's cases, the
shipped configuration and project, loaded once per session, and one end-to-end build of the
small configuration in ``.test/`` for the workflow tests.

Plain constants and functions the tests share live in the package ``tests/helpers`` (its
``__init__.py`` names its modules); a test module imports them from there, never from this
file or from another test module (tests/test_suite.py checks this).
The shipped configuration and project are read-only: a test that changes a case changes a
``copy.deepcopy`` of it. Their fixtures check this when the session ends. The ``.test/`` build
is read-only too: a test that changes it works on ``helpers.copies.clone_build`` of it.
"""

from __future__ import annotations

import copy
from collections.abc import Iterator
from pathlib import Path

import pytest

from rodimpact.config.load import load_global_config, load_project
from rodimpact.config.project import Project
from rodimpact.model.materials import Material

from helpers.copies import DotTestBuild, dottest_build
from helpers.paper import ALUMINIUM, STEEL
from helpers.repo import ROOT


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def steel() -> Material:
    return STEEL


@pytest.fixture(scope="session")
def aluminium() -> Material:
    return ALUMINIUM


def _unchanged(shared, pristine, name: str) -> None:
    assert shared == pristine, f"a test changed the session's {name}: change a copy.deepcopy of it instead"


@pytest.fixture(scope="session")
def shipped_config() -> Iterator[dict]:
    """config/config.yaml, checked, every default filled in (read-only)."""
    config = load_global_config(ROOT / "config" / "config.yaml")
    pristine = copy.deepcopy(config)
    yield config
    _unchanged(config, pristine, "shipped_config")


@pytest.fixture(scope="session")
def shipped_project(shipped_config: dict) -> Iterator[Project]:
    """Every shipped case, resolved (read-only)."""
    project = load_project(shipped_config, root=ROOT)
    pristine = copy.deepcopy(project)
    yield project
    _unchanged(project, pristine, "shipped_project")


@pytest.fixture(scope="session")
def dottest(tmp_path_factory: pytest.TempPathFactory) -> DotTestBuild:
    """The small configuration ``.test/`` built end to end (``snakemake -j2 --directory .test``):
    the checkout's own ``.test/results`` when ``make test`` has just built it and it is up to
    date, else a build in a temporary copy of the project (never modified by a test)."""
    return dottest_build(tmp_path_factory.mktemp("dottest"))
