"""Tests of rodimpact.storage.provenance: canonical JSON, hashing, code and library versions."""

from __future__ import annotations

import hashlib
import json
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import rodimpact
from rodimpact.storage import provenance

from helpers.repo import ROOT as REPO_ROOT

VERSION_RE = re.compile(rf"^{re.escape(rodimpact.__version__)}\+(unknown|g[0-9a-f]{{4,40}}(\.dirty)?)$")


def test_canonical_json_is_order_independent_and_compact() -> None:
    a = {"b": 1, "a": {"y": [1, 2.5, None], "x": True}, "é": "ü"}
    b = {"é": "ü", "a": {"x": True, "y": [1, 2.5, None]}, "b": 1}
    assert provenance.canonical_json(a) == provenance.canonical_json(b)
    assert provenance.canonical_json(a) == '{"a":{"x":true,"y":[1,2.5,null]},"b":1,"é":"ü"}'
    assert provenance.config_sha256(a) == provenance.config_sha256(b)
    expected = hashlib.sha256(provenance.canonical_json(a).encode("utf-8")).hexdigest()
    assert provenance.config_sha256(a) == expected
    assert re.fullmatch(r"[0-9a-f]{64}", provenance.config_sha256(a))
    assert json.loads(provenance.canonical_json(a)) == a


def test_canonical_json_distinguishes_values() -> None:
    assert provenance.config_sha256({"x": 1}) != provenance.config_sha256({"x": 1.0})
    assert provenance.config_sha256({"x": 1}) != provenance.config_sha256({"x": 2})


@pytest.mark.parametrize(
    ("obj", "path"),
    [
        ({"numerics": {"dt": np.float64(1e-6)}}, r"\$\.numerics\.dt"),
        ({"n": np.int64(3)}, r"\$\.n"),
        ({"stations": [0.0, np.float32(0.5)]}, r"\$\.stations\[1\]"),
        ({"a": {"b": np.array([1.0, 2.0])}}, r"\$\.a\.b"),
        ({"a": (1, 2)}, r"\$\.a"),
        ({"name": np.str_("x")}, r"\$\.name"),
    ],
)
def test_canonical_json_rejects_non_plain_types_naming_key_path(obj: dict, path: str) -> None:
    with pytest.raises(TypeError, match=path):
        provenance.canonical_json(obj)


def test_canonical_json_rejects_non_str_keys_and_nan() -> None:
    with pytest.raises(TypeError, match=r"\$\.a"):
        provenance.canonical_json({"a": {1: "x"}})
    with pytest.raises(ValueError, match=r"\$\.x\[0\]"):
        provenance.canonical_json({"x": [float("nan")]})
    loop: dict = {}
    loop["self"] = loop
    with pytest.raises(ValueError, match="circular"):
        provenance.canonical_json(loop)


@pytest.mark.skipif(shutil.which("git") is None, reason="git executable not available")
def test_code_version_in_this_repo() -> None:
    version = provenance.code_version(REPO_ROOT)
    assert VERSION_RE.match(version), version
    assert provenance.code_version() == version  # default discovers the same repository
    has_commit = (
        subprocess.run(
            ["git", "-C", str(REPO_ROOT), "rev-parse", "--verify", "-q", "HEAD"],
            capture_output=True,
            check=False,
        ).returncode
        == 0
    )
    assert version.endswith("+unknown") != has_commit


def test_code_version_outside_git(tmp_path: Path) -> None:
    assert provenance.code_version(tmp_path) == f"{rodimpact.__version__}+unknown"
    assert provenance.code_version(tmp_path / "missing") == f"{rodimpact.__version__}+unknown"


def test_code_version_without_git_executable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("PATH", "")
    assert provenance.code_version(REPO_ROOT) == f"{rodimpact.__version__}+unknown"


@pytest.mark.skipif(shutil.which("git") is None, reason="git executable not available")
def test_code_version_commit_and_dirty(tmp_path: Path) -> None:
    def git(*args: str) -> None:
        subprocess.run(["git", "-C", str(tmp_path), *args], check=True, capture_output=True)

    git("init", "-q")
    git("config", "user.email", "test@example.invalid")
    git("config", "user.name", "test")
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "a.py").write_text("x = 1\n")
    git("add", ".")
    git("commit", "-q", "-m", "init")
    clean = provenance.code_version(tmp_path)
    assert re.fullmatch(rf"{re.escape(rodimpact.__version__)}\+g[0-9a-f]{{4,40}}", clean)
    (tmp_path / "notes.txt").write_text("outside src does not count\n")
    assert provenance.code_version(tmp_path) == clean
    (tmp_path / "src" / "a.py").write_text("x = 2\n")
    assert provenance.code_version(tmp_path) == clean + ".dirty"


def test_library_versions() -> None:
    versions = provenance.library_versions()
    expected = {"python", "numpy", "scipy", "h5py", "pandas", "matplotlib", "scikit-fem", "snakemake"}
    assert set(versions) == expected
    assert all(isinstance(v, str) and v for v in versions.values())
    assert versions["numpy"] == np.__version__
    assert versions["python"].count(".") == 2
