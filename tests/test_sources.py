"""The static import graph that decides which code changes rerun which rules."""

import re
from pathlib import Path

import pytest

from rodimpact.plumbing.sources import imported_modules, module_sources, source_digest

SRC = Path(__file__).resolve().parents[1] / "src"


def names(files):
    return {Path(f).relative_to(SRC / "rodimpact").as_posix() for f in files}


def test_solver_closure_has_the_physics_and_not_the_presentation():
    files = names(module_sources(SRC, ["rodimpact.jobs.runner"]))
    assert {
        "jobs/runner.py",
        "storage/runs.py",
        "contact/hertz.py",
        "model/responses.py",
        "solvers/registry.py",
        "solvers/sem/options.py",
        "__init__.py",
    } <= files
    assert not any(f.startswith("present/") for f in files) and "tools/bench.py" not in files


#: Every presentation rule's module (workflow/rules/*.smk, ``presentation("module:function")``).
PRESENTATION = sorted(
    {
        m.group(1)
        for path in (SRC.parent / "workflow" / "rules").glob("*.smk")
        for m in re.finditer(r'presentation\("([\w.]+):\w+"\)', path.read_text(encoding="utf-8"))
    }
)
#: The compute jobs' code (their scripts' entry modules), each with its own solver where it runs one.
COMPUTE = {
    "solve": ["rodimpact.jobs.batch", "rodimpact.jobs.logs", "rodimpact.solvers.fem_axi.solver"],
    "case_file": ["rodimpact.jobs.cases"],
    "calibrate": ["rodimpact.jobs.calibrate", "rodimpact.solvers.sem.solver"],
    "indentation": ["rodimpact.jobs.indentation"],
    "film_band": ["rodimpact.jobs.band"],
    "sensor_band": ["rodimpact.jobs.sensor_band"],
}


def test_presentation_closure_has_no_solver():
    assert len(PRESENTATION) >= 10 and "rodimpact.present.readings" in PRESENTATION
    for module in PRESENTATION:
        files = names(module_sources(SRC, [module, "rodimpact.jobs.logs"]))
        assert {"storage/atomic.py"} <= files
        assert not any(f.endswith(("solver.py", "stepper.py")) for f in files), module


@pytest.mark.parametrize("job", sorted(COMPUTE))
def test_no_compute_job_runs_presentation_code(job: str):
    """Compute stores numbers, presentation adds words: no compute job's code digest covers a
    module of rodimpact.present, so a change there reruns no compute job."""
    files = names(module_sources(SRC, COMPUTE[job]))
    assert not any(f.startswith("present/") for f in files), sorted(f for f in files if f.startswith("present/"))


def test_unknown_entry_module_is_an_error():
    with pytest.raises(ModuleNotFoundError, match="entry_modules"):
        module_sources(SRC, ["rodimpact.nope"])


def _package_copy(tmp_path: Path) -> Path:
    import shutil

    copy = tmp_path / "src"
    shutil.copytree(SRC / "rodimpact", copy / "rodimpact", ignore=shutil.ignore_patterns("__pycache__"))
    return copy


def test_the_digest_follows_exactly_the_closure(tmp_path):
    """A rule's code param: another checkout of the same code has the same digest; a change to a
    file the closure holds changes it, a change to any other file does not."""
    copy = _package_copy(tmp_path)
    solver = ["rodimpact.jobs.runner", "rodimpact.solvers.fem_axi.solver"]
    before = source_digest(copy, solver)
    assert before == source_digest(SRC, solver) and len(before) == 64
    with open(copy / "rodimpact/present/figures.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    assert source_digest(copy, solver) == before
    with open(copy / "rodimpact/solvers/fem_axi/solver.py", "a", encoding="utf-8") as handle:
        handle.write("# touched\n")
    assert source_digest(copy, solver) != before
    # and the presentation's digest moved with the figure's file, not with the solver's
    figure = ["rodimpact.present.figure_artifacts"]
    assert source_digest(copy, figure) != source_digest(SRC, figure)


def test_a_module_imported_anew_enters_the_digest(tmp_path):
    copy = _package_copy(tmp_path)
    entry = ["rodimpact.jobs.logs"]
    before = source_digest(copy, entry)
    assert not any(f.endswith("present/figures.py") for f in module_sources(copy, entry))
    with open(copy / "rodimpact/jobs/logs.py", "a", encoding="utf-8") as handle:
        handle.write("\nimport rodimpact.present.figures  # noqa: E402\n")
    assert any(f.endswith("present/figures.py") for f in module_sources(copy, entry))
    assert source_digest(copy, entry) != before


def _imports_by_ast(module: str, text: str, is_package: bool) -> set[str]:
    """What Python's own parser says ``text`` imports (the reference for the text scan)."""
    import ast

    package = module if is_package else module.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            anchor = package.split(".")
            base = (
                ".".join(anchor[: len(anchor) - (node.level - 1)] + ([node.module] if node.module else []))
                if node.level
                else node.module or ""
            )
            found.add(base)
            found.update(f"{base}.{alias.name}" for alias in node.names)
    return found


def test_the_text_scan_finds_what_the_parser_finds_in_every_package_file():
    """Every file of the package imports the same package modules by the text scan as by
    :mod:`ast` (the scan may also find a word after "import" at a docstring line's start, never a
    module of the package that is not imported), and so do the forms the package does not use
    yet: continued lines, comments in a parenthesised list, several names and aliases, relative
    imports from a package, imports inside a function."""
    files = sorted((SRC / "rodimpact").rglob("*.py"))
    assert len(files) > 100
    for path in files:
        module = ".".join(path.relative_to(SRC).with_suffix("").parts).removesuffix(".__init__")
        text = path.read_text(encoding="utf-8")
        is_package = path.name == "__init__.py"
        scanned, parsed = (
            {m for m in found if m.startswith("rodimpact")}
            for found in (imported_modules(module, text, is_package), _imports_by_ast(module, text, is_package))
        )
        assert scanned == parsed, (path, scanned ^ parsed)
    forms = (
        "import a.b as c, d\n"
        "from x.y import (p,  # a comment\n    q as r,\n)\n"
        "from .. import s\n"
        "from .t import u, \\\n    v\n"
        "def f():\n    import w.z\n    from . import k; import m\n"
    )
    scanned = imported_modules("pkg.sub.mod", forms)
    parsed = _imports_by_ast("pkg.sub.mod", forms, False)
    assert scanned == parsed, scanned ^ parsed
    assert imported_modules("pkg.sub", "from . import q\n", True) == _imports_by_ast(
        "pkg.sub", "from . import q\n", True
    )
