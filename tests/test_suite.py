"""The test suite's own rules, read from its source with :mod:`ast`.

1. Tests share, they do not import each other: no module under tests/ imports conftest (its
   fixtures reach a test as arguments) or a ``test_*`` module; what tests share besides
   fixtures lives in the package ``tests/helpers``.
2. Every test that runs snakemake carries the marker ``workflow`` (``-m "not workflow"`` then
   skips every one of them). A test runs snakemake when its function, a fixture it takes or a
   module-level function either calls (at any depth inside its module) does one of these:

   - calls ``snakemake(...)`` or ``start(...)`` (tests/helpers/snakemake_cli.py), or builds a
     command line holding the string ``"snakemake"`` and starts it (``subprocess.run([...,
     "-m", "snakemake", ...])``);
   - imports snakemake's API (``snakemake``, ``snakemake.api``, ``snakemake.cli``,
     ``snakemake.workflow``; not a library module such as ``snakemake.utils`` or
     ``snakemake.persistence.file``);
   - takes the fixture ``dottest`` (the session's build of ``.test/``);
   - audits a project with the workflow (``audit(...)`` without ``workflow=False``, or the
     command ``rodimpact.tools.audit`` without ``--no-workflow``: it asks ``snakemake
     --summary``).

   Such a test is marked by the module's ``pytestmark = pytest.mark.workflow`` or by its own
   ``@pytest.mark.workflow``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
MODULES = sorted(TESTS.glob("*.py")) + sorted((TESTS / "helpers").glob("*.py"))
TEST_MODULES = sorted(TESTS.glob("test_*.py"))
#: What runs snakemake when called (tests/helpers/snakemake_cli.py).
RUNNERS = {"snakemake", "start"}
#: Calls that start a process (a command line among their arguments runs).
PROCESS_CALLS = {"run", "Popen", "call", "check_call", "check_output"}
#: Modules through which Python code runs a workflow (snakemake's API and command line); not
#: its other modules (snakemake.utils, snakemake.persistence), which tests may use as a library.
RUN_APIS = {"snakemake", "snakemake.api", "snakemake.cli", "snakemake.workflow"}
#: The session's fixture whose first use builds .test/ (tests/conftest.py).
BUILD_FIXTURES = {"dottest"}


def _tree(path: Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


def _imported(tree: ast.Module) -> list[tuple[str, int]]:
    """Every module a source imports (at any depth), with its line."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module:
            found.append((node.module, node.lineno))
    return found


def test_no_module_imports_conftest_or_another_test_module() -> None:
    wrong = [
        f"{path.relative_to(TESTS)}:{line} imports {name}"
        for path in MODULES
        for name, line in _imported(_tree(path))
        if name.split(".")[0] == "conftest" or name.split(".")[0].startswith("test_")
    ]
    assert wrong == []


def test_the_import_check_sees_both_kinds() -> None:
    source = ast.parse("from conftest import ROOT\nimport test_workflow\nfrom helpers.repo import ROOT\n")
    assert [name for name, _ in _imported(source)] == ["conftest", "test_workflow", "helpers.repo"]


# --------------------------------------------------------------------------------------------
# the marker
# --------------------------------------------------------------------------------------------


def _strings(node: ast.AST) -> list[str]:
    return [n.value for n in ast.walk(node) if isinstance(n, ast.Constant) and isinstance(n.value, str)]


def _starts_a_process(call: ast.Call) -> bool:
    """``subprocess.run(...)``, ``Popen(...)`` and their kin."""
    func = call.func
    name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
    return name in PROCESS_CALLS


def _runs_snakemake_itself(node: ast.AST) -> bool:
    """Whether ``node``'s own code (not counting the module's functions it calls) runs snakemake."""
    for sub in ast.walk(node):
        if isinstance(sub, ast.Call) and isinstance(sub.func, ast.Name):
            if sub.func.id in RUNNERS:
                return True
            if sub.func.id == "audit" and not any(
                k.arg == "workflow" and isinstance(k.value, ast.Constant) and k.value.value is False
                for k in sub.keywords
            ):
                return True
        if isinstance(sub, ast.Call) and _starts_a_process(sub):
            for words in (_strings(arg) for arg in sub.args if isinstance(arg, (ast.List, ast.Tuple))):
                if "snakemake" in words:
                    return True
                if "rodimpact.tools.audit" in words and "--no-workflow" not in words:
                    return True
        if isinstance(sub, (ast.Import, ast.ImportFrom)):
            names = [a.name for a in sub.names] if isinstance(sub, ast.Import) else [sub.module or ""]
            if any(n in RUN_APIS for n in names):
                return True
        if isinstance(sub, (ast.FunctionDef, ast.AsyncFunctionDef)):
            if BUILD_FIXTURES & {a.arg for a in sub.args.args}:
                return True
    return False


def _called(node: ast.AST) -> set[str]:
    """Names ``node`` calls or takes as arguments (a fixture is a parameter's name)."""
    names = {n.func.id for n in ast.walk(node) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
        names |= {a.arg for a in node.args.args}
    return names


def _is_workflow_mark(node: ast.AST) -> bool:
    """``pytest.mark.workflow``, alone or in a list of marks."""
    return any(
        isinstance(n, ast.Attribute)
        and n.attr == "workflow"
        and isinstance(n.value, ast.Attribute)
        and n.value.attr == "mark"
        for n in ast.walk(node)
    )


def unmarked_snakemake_tests(tree: ast.Module) -> list[str]:
    """The test functions of a module that run snakemake (module docstring, rule 2) without the
    marker ``workflow``."""
    functions = {n.name: n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}
    classes = [n for n in tree.body if isinstance(n, ast.ClassDef)]
    module_level = [n for n in tree.body if not isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))]
    if any(
        isinstance(n, ast.Assign)
        and any(isinstance(t, ast.Name) and t.id == "pytestmark" for t in n.targets)
        and _is_workflow_mark(n.value)
        for n in module_level
    ):
        return []
    runs = {name for name, node in functions.items() if _runs_snakemake_itself(node)}
    if any(_runs_snakemake_itself(n) for n in module_level + classes):
        runs |= set(functions)  # the module's own code runs snakemake: every test counts
    grew = True
    while grew:  # through the module's functions and fixtures, at any depth
        more = {name for name, node in functions.items() if name not in runs and _called(node) & runs}
        runs |= more
        grew = bool(more)
    return sorted(
        name
        for name in runs
        if name.startswith("test_") and not any(_is_workflow_mark(d) for d in functions[name].decorator_list)
    )


@pytest.mark.parametrize("path", TEST_MODULES, ids=lambda p: p.name)
def test_every_test_that_runs_snakemake_is_marked(path: Path) -> None:
    assert unmarked_snakemake_tests(_tree(path)) == []


def _marked_check(source: str) -> list[str]:
    return unmarked_snakemake_tests(ast.parse(source))


def test_the_marker_check_finds_what_runs_snakemake() -> None:
    """The rule's cases, each on a small module: a test that runs snakemake directly, through a
    function or a fixture of its module, through ``python -m snakemake`` or the audit, or takes
    the .test build is found unless marked; a module's pytestmark marks all."""
    helper = "def _build(p):\n    return snakemake(p, '-j1')\n"
    fixture = "@pytest.fixture\ndef built(tmp_path):\n    return _build(tmp_path)\n"
    assert _marked_check(helper + "def test_a(tmp_path):\n    _build(tmp_path)\n") == ["test_a"]
    assert _marked_check(helper + fixture + "def test_b(built):\n    pass\n") == ["test_b"]
    assert _marked_check("def test_c():\n    subprocess.run([sys.executable, '-m', 'snakemake', '-n'])\n") == ["test_c"]
    assert _marked_check("def test_d(dottest):\n    pass\n") == ["test_d"]
    assert _marked_check("def test_e(p):\n    audit(p)\n") == ["test_e"]
    assert _marked_check("def test_f(p):\n    audit(p, workflow=False)\n") == []
    assert _marked_check("from snakemake.utils import Paramspace\ndef test_g():\n    Paramspace\n") == []
    assert _marked_check("def test_k():\n    from snakemake.api import SnakemakeApi\n") == ["test_k"]
    assert _marked_check("def test_l():\n    from snakemake.persistence.file import FilePersistence\n") == []
    assert (
        _marked_check("@pytest.mark.parametrize('argv', [['snakemake', '-n']])\ndef test_m(argv):\n    parse(argv)\n")
        == []
    )
    assert _marked_check(helper + "@pytest.mark.workflow\ndef test_h(tmp_path):\n    _build(tmp_path)\n") == []
    assert _marked_check("pytestmark = pytest.mark.workflow\n" + helper + "def test_i(p):\n    _build(p)\n") == []
    assert (
        _marked_check("pytestmark = [pytest.mark.workflow, pytest.mark.slow]\ndef test_j(p):\n    snakemake(p)\n") == []
    )
