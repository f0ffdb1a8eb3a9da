"""Provenance helpers: canonical configuration hashing, code and library versions.

Every stored run (see :mod:`rodimpact.storage.runs`) records

* the canonical JSON of the fully resolved configuration and its SHA-256,
* the code version (package version plus git commit, ``.dirty`` when ``src/``
  has uncommitted changes),
* the versions of the numerical libraries used.

Canonical JSON is deterministic: keys sorted, no insignificant whitespace,
UTF-8 text kept as is, and NaN/Infinity rejected. Only plain JSON types are
accepted so that the hash cannot depend on how a value happens to be typed in
memory (``numpy.float64`` versus ``float``, tuple versus list).
"""

from __future__ import annotations

import functools
import hashlib
import json
import logging
import math
import os
import platform
import re
import subprocess
from pathlib import Path
from typing import Any

import numpy as np

import rodimpact

logger = logging.getLogger(__name__)

__all__ = [
    "LIBRARIES",
    "canonical_json",
    "code_version",
    "commit_exists",
    "config_sha256",
    "data_sha256",
    "file_sha256",
    "find_repo_root",
    "library_versions",
]

#: Distributions reported by :func:`library_versions` (besides ``python``).
LIBRARIES: tuple[str, ...] = (
    "numpy",
    "scipy",
    "h5py",
    "pandas",
    "matplotlib",
    "scikit-fem",
    "snakemake",
)

_NOT_INSTALLED = "not installed"
_GIT_TIMEOUT_S = 10.0
_GIT_LOCATION_VARS = frozenset({"GIT_DIR", "GIT_WORK_TREE", "GIT_INDEX_FILE"})
_SHORT_SHA = re.compile(r"^[0-9a-f]{4,40}$")
# Exact types only: numpy.float64 subclasses float and numpy.str_ subclasses str,
# and both must be rejected.
_SCALAR_TYPES: tuple[type, ...] = (str, int, float, bool, type(None))


def _child_path(path: str, key: str | int) -> str:
    if isinstance(key, int):
        return f"{path}[{key}]"
    return f"{path}.{key}"


def _check_plain_json(obj: Any, path: str, active: set[int]) -> None:
    """Raise if ``obj`` is not built from plain JSON types (recursive)."""
    kind = type(obj)
    if kind in _SCALAR_TYPES:
        if kind is float and not math.isfinite(obj):
            raise ValueError(f"canonical_json: value at {path} is {obj!r}; NaN and infinities are not allowed")
        return
    if isinstance(obj, dict) or kind is list:
        if id(obj) in active:
            raise ValueError(f"canonical_json: circular reference at {path}")
        active.add(id(obj))
        if isinstance(obj, dict):
            for key, value in obj.items():
                if type(key) is not str:
                    raise TypeError(
                        f"canonical_json: key {key!r} at {path} has type "
                        f"{type(key).__qualname__}; only str keys are allowed"
                    )
                _check_plain_json(value, _child_path(path, key), active)
        else:
            for index, value in enumerate(obj):
                _check_plain_json(value, _child_path(path, index), active)
        active.discard(id(obj))
        return
    raise TypeError(
        f"canonical_json: value at {path} has type {kind.__module__}.{kind.__qualname__}; "
        "only dict, list, str, int, float, bool and None are allowed "
        "(convert numpy scalars/arrays with .item()/.tolist() and tuples with list())"
    )


def canonical_json(obj: Any) -> str:
    """Serialise ``obj`` to deterministic (canonical) JSON.

    Parameters
    ----------
    obj : dict, list, str, int, float, bool or None
        Plain JSON data. Dictionaries must have ``str`` keys. Numpy scalars or
        arrays, tuples and other types are rejected rather than coerced.

    Returns
    -------
    str
        JSON text with sorted keys, separators ``","`` and ``":"`` and non-ASCII
        characters kept verbatim.

    Raises
    ------
    TypeError
        If a value or key is not a plain JSON type; the message names the key
        path, e.g. ``$.numerics.dt`` or ``$.stations[2]``.
    ValueError
        If a float is NaN or infinite, or a container refers to itself; the
        message names the key path.
    """
    _check_plain_json(obj, "$", set())
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), ensure_ascii=False, allow_nan=False)


def config_sha256(obj: Any) -> str:
    """Hex SHA-256 of :func:`canonical_json` of ``obj`` (UTF-8 encoded).

    Parameters
    ----------
    obj : dict, list, str, int, float, bool or None
        Plain JSON data, see :func:`canonical_json`.

    Returns
    -------
    str
        64 lowercase hexadecimal characters.

    Raises
    ------
    TypeError, ValueError
        As :func:`canonical_json`.
    """
    return hashlib.sha256(canonical_json(obj).encode("utf-8")).hexdigest()


def find_repo_root(start: str | Path | None = None) -> Path | None:
    """Find the nearest directory at or above ``start`` that contains ``.git``.

    Parameters
    ----------
    start : str or Path, optional
        Where to start; defaults to the directory of this module.

    Returns
    -------
    Path or None
        The repository root, or ``None`` when no ``.git`` entry is found.
    """
    here = Path(start) if start is not None else Path(__file__).parent
    here = here.resolve()
    for candidate in (here, *here.parents):
        if (candidate / ".git").exists():
            return candidate
    return None


def _git(root: Path, *args: str) -> str:
    """Run ``git -C root args`` and return stripped stdout (raises on failure)."""
    env = {k: v for k, v in os.environ.items() if k not in _GIT_LOCATION_VARS}
    env["LC_ALL"] = "C"
    result = subprocess.run(
        ["git", "-C", str(root), *args],
        capture_output=True,
        text=True,
        timeout=_GIT_TIMEOUT_S,
        check=True,
        env=env,
    )
    return result.stdout.strip()


def code_version(repo_root: str | Path | None = None) -> str:
    """Version string of the code that produced a result.

    Parameters
    ----------
    repo_root : str or Path, optional
        Top-level directory of the git work tree (must contain ``.git``).
        Defaults to the nearest directory above this module containing ``.git``.

    Returns
    -------
    str
        ``"{__version__}+g{short_commit}"``, with ``".dirty"`` appended when
        ``git status --porcelain -- src`` reports changes (including untracked
        files), or ``"{__version__}+unknown"`` when git, the repository or a
        commit is unavailable. Never raises because of git.
    """
    version = rodimpact.__version__
    unknown = f"{version}+unknown"
    root = find_repo_root() if repo_root is None else Path(repo_root)
    if root is None or not (root / ".git").exists():
        logger.debug("code_version: no git repository at %s", root)
        return unknown
    try:
        short = _git(root, "rev-parse", "--short", "HEAD")
        status = _git(root, "status", "--porcelain", "--", "src")
    except (OSError, subprocess.SubprocessError) as exc:
        detail = getattr(exc, "stderr", None) or exc
        logger.warning("code_version: git failed in %s (%s); using %s", root, str(detail).strip(), unknown)
        return unknown
    if not _SHORT_SHA.match(short):
        logger.warning("code_version: unexpected git rev-parse output %r; using %s", short, unknown)
        return unknown
    dirty = ".dirty" if status else ""
    return f"{version}+g{short}{dirty}"


def commit_exists(repo_root: str | Path, commit: str) -> bool:
    """Whether ``commit`` (a hex prefix) names a commit of the repository at ``repo_root``."""
    if not _SHORT_SHA.match(commit):
        return False
    try:
        _git(Path(repo_root), "cat-file", "-e", f"{commit}^{{commit}}")
    except (OSError, subprocess.SubprocessError):
        return False
    return True


def library_versions() -> dict[str, str]:
    """Versions of Python and of the numerical and workflow libraries.

    Returns
    -------
    dict of str to str
        Keys ``python`` and those in :data:`LIBRARIES` (``numpy``, ``scipy``,
        ``h5py``, ``pandas``, ``matplotlib``, ``scikit-fem``, ``snakemake``);
        values are version strings or ``"not installed"``. Looked up once per process
        (the installed distributions do not change while it runs).
    """
    return dict(_library_versions())


@functools.lru_cache(maxsize=1)
def _library_versions() -> tuple[tuple[str, str], ...]:
    import importlib.metadata  # slow to import, and only the writer of a run asks

    versions = {"python": platform.python_version()}
    for name in LIBRARIES:
        try:
            versions[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            versions[name] = _NOT_INSTALLED
    return tuple(versions.items())


def _summary_bytes(value: Any) -> tuple[bytes, ...]:
    """Type tag and bytes of one summary value, the same before writing and after reading."""
    if isinstance(value, (str, np.str_)):
        return b"s", str(value).encode("utf-8")
    if isinstance(value, (bool, np.bool_)):
        return b"b", b"1" if value else b"0"
    if isinstance(value, (int, np.integer)):
        return b"i", np.int64(value).tobytes()
    if isinstance(value, (float, np.floating)):
        return b"f", np.float64(value).tobytes()
    array = np.asarray(value)
    kind = {"b": np.uint8, "i": np.int64, "u": np.int64}.get(array.dtype.kind, np.float64)
    return b"a", repr(array.shape).encode(), np.ascontiguousarray(array, dtype=kind).tobytes()


def data_sha256(config_json: str, method: str, series: Any, summary: Any) -> str:
    """Hex SHA-256 of a run's content: its config, method, every series and the summary.

    Parameters
    ----------
    config_json : str
        The run's canonical config JSON.
    method : str
        The method that made the run.
    series : mapping of str to (array, units, description)
        Every dataset; arrays are hashed as C-ordered float64 with their shape.
    summary : mapping of str to scalar, str or 1-D array
        Every summary attribute (bool, int, float, str or numeric array; numpy or Python
        types hash alike).

    Returns
    -------
    str
        64 hex characters; a run file edited after it was written no longer matches.
    """
    digest = hashlib.sha256()

    def feed(*parts: bytes) -> None:
        for part in parts:
            digest.update(len(part).to_bytes(8, "little"))
            digest.update(part)

    feed(config_json.encode("utf-8"), method.encode("utf-8"))
    for name in sorted(series):
        values, units, description = series[name]
        array = np.ascontiguousarray(values, dtype=np.float64)
        feed(name.encode(), units.encode(), description.encode(), repr(array.shape).encode(), array.tobytes())
    for key in sorted(summary):
        feed(key.encode("utf-8"), *_summary_bytes(summary[key]))
    return digest.hexdigest()


def file_sha256(path: str | Path) -> str:
    """Hex SHA-256 of a file's bytes."""
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()
