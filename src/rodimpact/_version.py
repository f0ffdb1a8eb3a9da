"""The version of rodimpact, read from the git tags: its one place.

A release is an annotated tag ``vX.Y.Z``. The version of a commit is

* ``X.Y.Z`` on the tagged commit itself (``X.Y.Z.post0`` when tracked files are modified);
* ``X.Y.Z.postN`` N commits after the newest reachable tag;
* ``0.0.0.postN`` in a history with no such tag (N: the commits in it).

This is setuptools-scm's ``post-release`` scheme without a local part, which ``pyproject.toml``
(``[tool.setuptools_scm]``) gives the installed distribution; ``tests/test_version.py`` checks
that both agree. In a git checkout the version is read from git at run time, so it never goes
stale between installs; elsewhere (a wheel) it is the installed distribution's. The commit
itself is not part of the version: :func:`rodimpact.storage.provenance.code_version` appends it.

Imports only the standard library.
"""

from __future__ import annotations

import functools
import re
import subprocess
from importlib import metadata
from pathlib import Path

#: the tags that name releases
TAG_PATTERN = "v[0-9]*"
#: the version with no tag and no git: setuptools-scm's ``fallback_version``
FALLBACK = "0.0.0"
_DESCRIBED = re.compile(r"^v(?P<tag>\d+(?:\.\d+)*)-(?P<distance>\d+)-g[0-9a-f]+(?P<dirty>-dirty)?$")


def _git(root: Path, *args: str) -> str:
    return subprocess.run(
        ("git", "-C", str(root), *args), capture_output=True, text=True, check=True, timeout=30
    ).stdout.strip()


def git_version(root: str | Path) -> str | None:
    """The version of the commit checked out at ``root``, or None when git cannot tell.

    Parameters
    ----------
    root : str or Path
        The top of a git work tree.

    Returns
    -------
    str or None
        ``"X.Y.Z"``, ``"X.Y.Z.postN"`` or ``"0.0.0.postN"`` (see the module's docstring); None
        when git is missing or ``root`` holds no commit.
    """
    root = Path(root)
    try:
        described = _git(root, "describe", "--tags", "--long", "--dirty", "--match", TAG_PATTERN)
    except (OSError, subprocess.SubprocessError):
        described = ""
    match = _DESCRIBED.match(described)
    if match:
        distance = int(match["distance"])
        if distance == 0 and not match["dirty"]:
            return match["tag"]
        return f"{match['tag']}.post{distance}"
    try:
        count = int(_git(root, "rev-list", "--count", "HEAD"))
    except (OSError, subprocess.SubprocessError, ValueError):
        return None
    return f"{FALLBACK}.post{count}"


@functools.lru_cache(maxsize=1)
def version() -> str:
    """The version of this copy of rodimpact (see the module's docstring); looked up once."""
    root = Path(__file__).resolve().parents[2]
    if (root / ".git").exists() and (root / "pyproject.toml").is_file():
        found = git_version(root)
        if found is not None:
            return found
    try:
        return metadata.version("rodimpact")
    except metadata.PackageNotFoundError:
        return FALLBACK
