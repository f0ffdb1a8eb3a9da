"""What snakemake computes to plan the workflow, kept between its runs: the checked project and
each job's resource estimate.

Every snakemake run (a dry run, ``--summary``, a build, a report) parses the workflow: it checks
the whole configuration (:func:`rodimpact.config.load.load_project`) and estimates the resources of
every job it plans (:func:`rodimpact.jobs.resources.estimate_resources`). Both are functions
of files and arguments only, and both are slow (the contact-time estimate of a film integrates
its law). :class:`PlanCache` keeps their results in one file, ``.snakemake/rodimpact/plan.pickle``,
keyed on SHA-256 digests of everything they read:

* the project: snakemake's ``config`` (the config file and any ``--config``), the files under
  ``config/``, the materials file and the case files it names, and the schemas;
* an estimate: the resolved case, the method and the timing it is asked for;
* both: the package's sources (``src/rodimpact``) and the Python version
  (:func:`code_fingerprint`); another fingerprint discards the whole file.

A change of any of those misses the cache and redoes the work, so a bad input still gets its one
error before any job; only a project that passed the check is kept. The file is written whole or
not at all (:func:`rodimpact.storage.atomic.atomic_output`), only by a process that added to it,
and under a lock (``plan.lock``) inside which the file's entries are merged with the process's:
cluster jobs that save at once keep each other's additions. An unreadable file is ignored. It is
a pickle because the checked project is a tree of frozen dataclasses, not plain data; it is
read only from the workflow's own ``.snakemake/`` and only with the same sources and Python.

What snakemake does on its own
    Each run parses the Snakefile anew and evaluates its input and resource functions again;
    nothing of that is kept between runs (``--cache`` keeps rules' outputs, not the parse). Its
    ``onstart`` hook runs only when jobs are about to be scheduled: not for a dry run, a run
    with nothing to do or ``--no-hooks`` (``snakemake.workflow.Workflow.execute``).

Why that is not enough here
    Without the cache every dry run and every cluster job's snakemake checks the whole
    configuration and estimates every job again. ``workflow/rules/common.smk`` saves the cache
    from ``onstart`` (before the first job, so that a cluster job finds it) and from an
    :mod:`atexit` handler (after every run that planned, dry runs included).

If snakemake's internals change
    Should snakemake leave without running :mod:`atexit` handlers, or stop calling ``onstart``,
    the cache is not written: planning is slower, never different (the key covers every input).
    ``tests/test_plumbing.py::test_a_dry_run_leaves_the_plan_cache`` checks that a dry run
    writes it; ``tests/test_plan_cache.py`` checks the keys.
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import logging
import os
import pickle
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, TypeVar

from rodimpact.inputs.files import InputFileError, read_bytes, regular_file
from rodimpact.storage.atomic import atomic_output

__all__ = ["CACHE_FILE", "PlanCache", "code_fingerprint", "project_key"]

log = logging.getLogger(__name__)

#: The cache file, relative to the working directory of the workflow.
CACHE_FILE = Path(".snakemake") / "rodimpact" / "plan.pickle"
#: Checked projects kept (the newest ones): a few configurations in turn stay cached.
MAX_PROJECTS = 4
#: Estimates kept: the oldest go first past this number.
MAX_ESTIMATES = 50_000
_FORMAT = 2

T = TypeVar("T")


def _digest(*parts: bytes) -> str:
    sha = hashlib.sha256()
    for part in parts:
        sha.update(len(part).to_bytes(8, "little"))
        sha.update(part)
    return sha.hexdigest()


def _entry_bytes(path: Path) -> bytes:
    """What the loader would find at ``path``, read as it reads (:mod:`rodimpact.inputs.files`):
    a regular file's contents, and where a link leads; else a marker of what it is (a
    directory, a FIFO, a dangling link, a file too large), never a read of it. An entry that is
    no readable file changes the key as a file would, and so does a link that now leads
    elsewhere with the same bytes: the loader then checks where it leads."""
    try:
        resolved = regular_file(path)  # once: the read below starts from the resolved file
        data = read_bytes(resolved)
    except InputFileError as error:
        return f"{error.kind}:{error.reason}".encode()
    target = b"" if str(resolved) == os.path.abspath(path) else b"link:" + str(resolved).encode()
    return target + b"file:" + data


def _tree_bytes(path: Path, pattern: str = "*") -> list[bytes]:
    """Names and contents of the entries matching ``pattern`` under ``path`` (recursively: files,
    and directories and other entries by a marker), or of ``path`` itself when it is a file; a
    marker when it does not exist."""
    if path.is_file():
        return [path.name.encode(), _entry_bytes(path)]
    if not path.is_dir():
        return [b"missing:" + str(path).encode()]
    parts = []
    for entry in sorted(p for p in path.rglob(pattern) if "__pycache__" not in p.parts):
        parts += [entry.relative_to(path).as_posix().encode(), _entry_bytes(entry)]
    return parts


def code_fingerprint(src: str | Path) -> str:
    """SHA-256 of every Python source of the package under ``src`` and of the Python version."""
    return _digest(sys.version.encode(), *_tree_bytes(Path(src) / "rodimpact", "*.py"))


def _json(value: Any) -> bytes:
    """Deterministic JSON of plain data (keys sorted; other objects by their ``repr``)."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), default=repr).encode()


def project_key(config: Mapping[str, Any], root: str | Path, schema_dir: str | Path | None = None) -> str:
    """SHA-256 of what :func:`rodimpact.config.load.load_project` reads: ``config``, the files under
    ``<root>/config``, the materials file and the cases directory ``config`` names (when they
    are paths) and the schemas under ``schema_dir`` (default ``<root>/workflow/schemas``)."""
    root = Path(root)
    schemas = root / "workflow" / "schemas" if schema_dir is None else Path(schema_dir)
    parts = [_json(config), *_tree_bytes(root / "config"), *_tree_bytes(schemas)]
    for name in ("materials", "cases_dir"):
        value = config.get(name) if isinstance(config, Mapping) else None
        if isinstance(value, str):
            parts += [name.encode(), *_tree_bytes(root / value)]
    return _digest(*parts)


class PlanCache:
    """The planning results of one workflow directory (see the module docstring).

    Parameters
    ----------
    path : path
        The cache file (:data:`CACHE_FILE` under the workflow's directory); a relative path is
        taken from the working directory when the cache is made (snakemake changes back to the
        directory it was started in before the :mod:`atexit` handlers run, under ``--directory``).
    fingerprint : str
        :func:`code_fingerprint` of the sources the cached results were computed with.
    """

    def __init__(self, path: str | Path, fingerprint: str) -> None:
        self.path, self.fingerprint = Path(path).absolute(), fingerprint
        self._projects: dict[str, Any] = {}
        self._estimates: dict[str, Any] = {}
        self._changed = False
        self._read()

    def _stored(self) -> tuple[dict[str, Any], dict[str, Any]]:
        """The projects and estimates in the file (none when it is missing, damaged, or of other sources)."""
        try:
            with open(self.path, "rb") as handle:
                stored = pickle.load(handle)
        except FileNotFoundError:
            return {}, {}
        except Exception as error:  # noqa: BLE001 (a damaged or foreign file is only a miss)
            log.warning("ignoring the plan cache %s: %s", self.path, error)
            return {}, {}
        if (
            isinstance(stored, dict)
            and stored.get("format") == _FORMAT
            and stored.get("fingerprint") == self.fingerprint
        ):
            return dict(stored["projects"]), dict(stored["estimates"])
        return {}, {}

    def _read(self) -> None:
        self._projects, self._estimates = self._stored()

    def project(
        self, config: Mapping[str, Any], root: str | Path, load: Callable[[], T], schema_dir: str | Path | None = None
    ) -> T:
        """The checked project of ``config`` under ``root`` (schemas in ``schema_dir``, default
        ``<root>/workflow/schemas``): cached, or ``load()`` (which raises for a bad input; nothing
        is cached then)."""
        key = project_key(config, root, schema_dir)
        if key in self._projects:
            self._projects[key] = self._projects.pop(key)  # the newest last
            return pickle.loads(self._projects[key])
        project = load()
        # kept as it was checked: a later change to the object returned is not cached
        self._projects[key] = pickle.dumps(project, protocol=pickle.HIGHEST_PROTOCOL)
        while len(self._projects) > MAX_PROJECTS:
            del self._projects[next(iter(self._projects))]
        self._changed = True
        return project

    def remember(self, args: tuple[Any, ...], compute: Callable[..., T]) -> T:
        """``compute(*args)``, cached on the JSON of ``args`` (plain data: a case, a method...):
        for a pure function of ``args`` and of the package's sources only."""
        key = _digest(_json(args))
        if key not in self._estimates:
            self._estimates[key] = compute(*args)
            self._changed = True
        return self._estimates[key]

    def save(self) -> None:
        """Write the cache file if anything was added: under an exclusive lock of its lock file, the
        file's entries merged with this process's (so that processes saving at once, as cluster
        jobs do, keep each other's additions), then written atomically. A failure is only logged."""
        if not self._changed:
            return
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            with open(self.path.with_suffix(".lock"), "a+b") as lock:
                fcntl.flock(lock, fcntl.LOCK_EX)
                projects, estimates = self._stored()
                self._projects = {**{k: v for k, v in projects.items() if k not in self._projects}, **self._projects}
                self._estimates = {**estimates, **self._estimates}
                while len(self._projects) > MAX_PROJECTS:
                    del self._projects[next(iter(self._projects))]
                while len(self._estimates) > MAX_ESTIMATES:
                    del self._estimates[next(iter(self._estimates))]
                stored = {
                    "format": _FORMAT,
                    "fingerprint": self.fingerprint,
                    "projects": self._projects,
                    "estimates": self._estimates,
                }
                with atomic_output(self.path) as tmp:
                    tmp.write_bytes(pickle.dumps(stored, protocol=pickle.HIGHEST_PROTOCOL))
        except OSError as error:
            log.warning("could not write the plan cache %s: %s", self.path, error)
            return
        self._changed = False
