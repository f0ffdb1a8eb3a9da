"""The version comes from the git tags, in one scheme: rodimpact's own reading of git at run time
and setuptools-scm's (which gives the installed distribution its version, pyproject.toml) agree
on a tagged commit, commits after it, a modified tree and a history with no tag."""

from __future__ import annotations

import subprocess
import tomllib
from pathlib import Path

import pytest

import rodimpact
from rodimpact._version import git_version

setuptools_scm = pytest.importorskip("setuptools_scm")  # in environment.lock (the build backend's)

ROOT = Path(__file__).resolve().parents[1]


def _git(repo: Path, *args: str) -> None:
    subprocess.run(
        ("git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t", *args), check=True, capture_output=True
    )


def _scm(repo: Path) -> str:
    settings = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools_scm"]
    return setuptools_scm.get_version(root=str(repo), **settings)


@pytest.fixture()
def repo(tmp_path: Path) -> Path:
    _git(tmp_path, "init", "-q")
    (tmp_path / "a.txt").write_text("a\n")
    _git(tmp_path, "add", "a.txt")
    _git(tmp_path, "commit", "-q", "-m", "first")
    return tmp_path


def test_untagged_history_counts_its_commits(repo: Path) -> None:
    _git(repo, "commit", "-q", "--allow-empty", "-m", "second")
    assert git_version(repo) == "0.0.0.post2" == _scm(repo)


def test_tagged_commit_is_the_tag_and_later_commits_are_post_releases(repo: Path) -> None:
    _git(repo, "tag", "-a", "v1.2.3", "-m", "release")
    assert git_version(repo) == "1.2.3" == _scm(repo)
    _git(repo, "commit", "-q", "--allow-empty", "-m", "after")
    _git(repo, "commit", "-q", "--allow-empty", "-m", "after again")
    assert git_version(repo) == "1.2.3.post2" == _scm(repo)


def test_modified_tree_on_a_tag_is_post0(repo: Path) -> None:
    _git(repo, "tag", "-a", "v0.4.0", "-m", "release")
    (repo / "a.txt").write_text("changed\n")
    assert git_version(repo) == "0.4.0.post0" == _scm(repo)


def test_tags_not_naming_releases_are_ignored(repo: Path) -> None:
    _git(repo, "tag", "-a", "v2.0.0", "-m", "release")
    _git(repo, "commit", "-q", "--allow-empty", "-m", "after")
    _git(repo, "tag", "-a", "paper-draft", "-m", "not a release")
    assert git_version(repo) == "2.0.0.post1" == _scm(repo)


def test_no_git_repository_gives_none(tmp_path: Path) -> None:
    assert git_version(tmp_path) is None


def test_pyproject_reads_the_version_from_the_tags_only() -> None:
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "version" not in pyproject["project"] and pyproject["project"]["dynamic"] == ["version"]
    assert pyproject["tool"]["setuptools_scm"]["version_scheme"] == "post-release"


def test_the_package_in_this_checkout_reports_its_git_version() -> None:
    if not (ROOT / ".git").exists():
        pytest.skip("not a git checkout: the version is the installed distribution's")
    assert git_version(ROOT) is not None
    assert rodimpact.__version__ == git_version(ROOT)
