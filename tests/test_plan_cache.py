"""What snakemake's planning keeps between runs: hit only on the very same inputs and code."""

from __future__ import annotations

import multiprocessing
import shutil
import time
from pathlib import Path

import pytest

from rodimpact.jobs.resources import estimate_resources
from rodimpact.plumbing.plan_cache import PlanCache, code_fingerprint, project_key

from helpers.repo import ROOT


@pytest.fixture
def root(tmp_path: Path) -> Path:
    """The project's config/ and schemas in a scratch directory."""
    shutil.copytree(ROOT / "config", tmp_path / "config")
    shutil.copytree(ROOT / "workflow" / "schemas", tmp_path / "workflow" / "schemas")
    return tmp_path


CONFIG = {"cases_dir": "config/cases", "materials": "config/materials.yaml", "targets": {"sets": ["model"]}}


def test_the_project_key_follows_every_input(root: Path) -> None:
    key = project_key(CONFIG, root)
    assert project_key(dict(CONFIG), root) == key
    assert project_key({**CONFIG, "targets": {"sets": ["table2"]}}, root) != key  # snakemake's config
    case_file = root / "config" / "cases" / "model.yaml"
    case_file.write_text(case_file.read_text() + "\n# a comment\n")
    assert project_key(CONFIG, root) != key  # a case file's bytes
    key = project_key(CONFIG, root)
    (root / "config" / "cases" / "new.yaml").write_text("set: new\n")
    assert project_key(CONFIG, root) != key  # a new case file
    key = project_key(CONFIG, root)
    schema = next((root / "workflow" / "schemas").glob("*.yaml"))
    schema.write_text(schema.read_text() + "\n")
    assert project_key(CONFIG, root) != key  # a schema


@pytest.mark.parametrize(
    "make",
    [
        lambda cases: (cases / "dir.yaml").mkdir(),
        lambda cases: (cases / "empty").mkdir(),
        lambda cases: (cases / "gone.yaml").symlink_to(cases / "nowhere.yaml"),
    ],
    ids=["directory named like a case file", "empty directory", "dangling link"],
)
def test_the_project_key_follows_entries_that_are_no_readable_file(root: Path, make) -> None:
    """The loader reads (or refuses) whatever the cases directory holds, so the key covers every
    entry: with the cache in place, ``config/cases/dir.yaml/`` is still refused in one line."""
    key = project_key(CONFIG, root)
    make(root / "config" / "cases")
    assert project_key(CONFIG, root) != key


def test_a_fifo_in_the_configuration_is_keyed_without_a_read(root: Path) -> None:
    """A FIFO named like a case file (or a history) would block a read for ever: the key marks
    what it is and reads nothing (the test would hang otherwise: an alarm stops it)."""
    import os
    import signal

    key = project_key(CONFIG, root)
    os.mkfifo(root / "config" / "cases" / "pipe.yaml")
    signal.alarm(20)
    try:
        assert project_key(CONFIG, root) != key
    finally:
        signal.alarm(0)


def test_a_link_that_now_leads_elsewhere_with_the_same_bytes_changes_the_key(root: Path, tmp_path: Path) -> None:
    """A history replaced by a link to a copy outside the case file's directory: the same bytes,
    but the loader must check where it leads again, so the key changes."""
    history = next((root / "config" / "cases").rglob("*.csv"))
    key = project_key(CONFIG, root)
    outside = tmp_path / "outside.csv"
    outside.write_bytes(history.read_bytes())
    history.unlink()
    history.symlink_to(outside)
    assert project_key(CONFIG, root) != key


def test_a_project_is_loaded_once_and_kept(root: Path, tmp_path: Path) -> None:
    path = tmp_path / "cache" / "plan.pickle"
    loads = []
    cache = PlanCache(path, "code-1")
    project = cache.project(CONFIG, root, lambda: loads.append(1) or {"cases": 1})
    assert project == {"cases": 1}
    project["cases"] = 99  # a change to the object returned is not cached
    assert cache.project(CONFIG, root, lambda: {"cases": 4}) == {"cases": 1}
    cache.save()
    again = PlanCache(path, "code-1")
    assert again.project(CONFIG, root, lambda: loads.append(2) or {"cases": 2}) == {"cases": 1}
    assert loads == [1]
    other_code = PlanCache(path, "code-2")  # other sources: nothing is reused
    assert other_code.project(CONFIG, root, lambda: {"cases": 3}) == {"cases": 3}


def test_a_failed_check_is_not_kept(root: Path, tmp_path: Path) -> None:
    path = tmp_path / "plan.pickle"
    cache = PlanCache(path, "code")

    def bad():
        raise ValueError("bad input")

    for _ in range(2):  # raised every time: nothing was cached
        with pytest.raises(ValueError, match="bad input"):
            cache.project(CONFIG, root, bad)
    cache.save()
    assert not path.exists()


def test_estimates_are_computed_once_per_argument(tmp_path: Path, shipped_project) -> None:
    path = tmp_path / "plan.pickle"
    case = shipped_project.cases["model"]
    calls = []

    def estimate(case, method, timing):
        calls.append(method)
        return estimate_resources(case, method, timing=timing)

    cache = PlanCache(path, "code")
    first = cache.remember((case, "sem", None), estimate)
    assert cache.remember((case, "sem", None), estimate) == first
    cache.save()
    assert PlanCache(path, "code").remember((case, "sem", None), estimate) == first
    assert calls == ["sem"]
    changed = {**case, "impactor": {**case["impactor"], "mass_kg": 2 * case["impactor"]["mass_kg"]}}
    PlanCache(path, "code").remember((changed, "sem", None), estimate)
    assert calls == ["sem", "sem"]


def test_a_damaged_cache_file_is_only_a_miss(tmp_path: Path) -> None:
    path = tmp_path / "plan.pickle"
    path.write_bytes(b"not a pickle")
    assert PlanCache(path, "code").remember((1,), lambda x: x + 1) == 2


def test_the_fingerprint_follows_the_sources(tmp_path: Path) -> None:
    package = tmp_path / "rodimpact"
    package.mkdir()
    (package / "a.py").write_text("x = 1\n")
    first = code_fingerprint(tmp_path)
    (package / "a.py").write_text("x = 2\n")
    assert code_fingerprint(tmp_path) != first
    assert code_fingerprint(ROOT / "src") == code_fingerprint(ROOT / "src")


def _add_and_save(path: str, start: str, key: int) -> None:
    """A cluster job's snakemake: reads the cache when its workflow is parsed, waits for the
    others to have read it too, adds its own estimate and saves at once with them."""
    cache = PlanCache(path, "code")
    while not Path(start).exists():
        pass
    cache.remember((key,), lambda k: k * k)
    cache.save()


def test_processes_saving_at_once_keep_each_others_additions(tmp_path: Path) -> None:
    path, start = tmp_path / "plan.pickle", tmp_path / "start"
    cache = PlanCache(path, "code")
    cache.remember((0,), lambda k: k * k)
    cache.save()
    context = multiprocessing.get_context("fork")
    jobs = [context.Process(target=_add_and_save, args=(str(path), str(start), key)) for key in range(1, 9)]
    for job in jobs:
        job.start()
    time.sleep(0.5)  # every process has read the file with key 0 only
    start.touch()
    for job in jobs:
        job.join(timeout=60)
        assert job.exitcode == 0
    merged = PlanCache(path, "code")
    assert [merged.remember((key,), lambda k: -1) for key in range(9)] == [key * key for key in range(9)]
    assert not merged._changed  # every key was in the file: nothing recomputed
