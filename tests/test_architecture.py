"""The architecture, checked: packages by concern, imports only downwards, no cycles, and a
configuration check that loads no solver.

The layers, lowest first (a package may import its own modules and the layers below it):
(settings, inputs) < contact < model < analysis < solvers < (config, storage) < present < jobs < plumbing < tools.
config and storage share a rank: siblings, neither imports the other. Every import counts,
inside functions too, read from the source with :mod:`ast`.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "rodimpact"
#: The layers, lowest first; the packages of one set share a rank and import none of each other.
LAYERS: tuple[frozenset[str], ...] = tuple(
    frozenset(rank)
    for rank in (
        {"settings", "inputs"},
        {"contact"},
        {"model"},
        {"analysis"},
        {"solvers"},
        {"config", "storage"},
        {"present"},
        {"jobs"},
        {"plumbing"},
        {"tools"},
    )
)
#: Each top-level package's rank (its index in :data:`LAYERS`).
RANK = {package: rank for rank, packages in enumerate(LAYERS) for package in packages}


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path) -> list[tuple[str, int]]:
    """Every rodimpact module ``path`` imports (absolute or relative, at any depth), with its line."""
    module = _module_name(path)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            found.append((base, node.lineno))
            found += [
                (f"{base}.{alias.name}", node.lineno) for alias in node.names if _is_module(f"{base}.{alias.name}")
            ]
    return [(name, line) for name, line in found if name == "rodimpact" or name.startswith("rodimpact.")]


def _is_module(name: str) -> bool:
    base = SRC.joinpath(*name.split("."))
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def _package(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in RANK else None


def _modules() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def test_every_module_lives_in_a_package_of_a_concern():
    # _version.py: the version from the git tags, standard library only (below every layer)
    loose = [p.name for p in PACKAGE.glob("*.py") if p.name not in ("__init__.py", "_version.py")]
    assert loose == []
    version_imports = {
        n.module for n in ast.walk(ast.parse((PACKAGE / "_version.py").read_text())) if isinstance(n, ast.ImportFrom)
    } | {
        a.name
        for n in ast.walk(ast.parse((PACKAGE / "_version.py").read_text()))
        if isinstance(n, ast.Import)
        for a in n.names
    }
    assert not any(m.startswith("rodimpact") for m in version_imports if m), version_imports
    assert sorted(p.name for p in PACKAGE.iterdir() if p.is_dir() and p.name != "__pycache__") == sorted(RANK)


def test_every_package_says_what_lives_there_and_what_it_may_import():
    for init in PACKAGE.rglob("__init__.py"):
        if init.parent == PACKAGE:
            continue
        doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))) or ""
        assert "What lives here" in doc and "may import" in doc, init


def test_the_layers_hold_every_package_once():
    assert sum(len(rank) for rank in LAYERS) == len(RANK)


def test_the_package_docstring_names_the_layers_in_order():
    """src/rodimpact/__init__.py lists the layers as this test's LAYERS, lowest first."""
    text = ast.get_docstring(ast.parse((PACKAGE / "__init__.py").read_text(encoding="utf-8"))) or ""
    items = [part for part in re.split(r"\n(?=\d+\. )|\n\n", text) if re.match(r"\d+\. ", part)]
    ranks = [frozenset(re.findall(r":mod:`rodimpact\.(\w+)`", item)) for item in items]
    assert tuple(ranks) == LAYERS


def _named_modules(init: Path) -> set[str]:
    """The module names ``init``'s docstring names as ``:mod:`.name```."""
    doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))) or ""
    return set(re.findall(r":mod:`\.(\w+)`", doc))


def test_every_package_docstring_names_every_module_in_it():
    """Each package's ``__init__.py`` names each of its modules and subpackages as ``:mod:`.name```."""
    missing = {}
    for init in sorted(PACKAGE.rglob("__init__.py")):
        if init.parent == PACKAGE:
            continue
        members = {p.stem for p in init.parent.glob("*.py") if p.name != "__init__.py"}
        members |= {p.name for p in init.parent.iterdir() if (p / "__init__.py").is_file()}
        if absent := sorted(members - _named_modules(init)):
            missing[str(init.relative_to(SRC))] = absent
    assert missing == {}


def test_imports_run_only_downwards():
    """A package imports its own modules and the ranks below its own: never a higher rank, nor a
    sibling of the same rank (config and storage)."""
    wrong = []
    for path in _modules():
        own = _package(_module_name(path))
        for name, line in _imports(path):
            target = _package(name)
            if own is None or target is None or target == own:
                continue
            if RANK[target] > RANK[own]:
                wrong.append(f"{path.relative_to(SRC)}:{line} imports {name} ({target} is above {own})")
            elif RANK[target] == RANK[own]:
                wrong.append(f"{path.relative_to(SRC)}:{line} imports {name} ({target} is a sibling of {own})")
    assert wrong == []


def test_there_are_no_import_cycles():
    graph = {_module_name(p): {n for n, _ in _imports(p) if _is_module(n)} - {_module_name(p)} for p in _modules()}
    state: dict[str, int] = {}
    cycles = []

    def visit(node: str, stack: list[str]) -> None:
        state[node] = 1
        for nxt in sorted(graph.get(node, ())):
            if nxt.startswith(node + ".") or node.startswith(nxt + "."):
                continue  # a package and its own modules
            if state.get(nxt) == 1:
                cycles.append(" -> ".join(stack[stack.index(nxt) :] + [nxt]) if nxt in stack else f"{node} -> {nxt}")
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = 2

    for module in sorted(graph):
        if module not in state:
            visit(module, [module])
    assert cycles == []


def test_the_configuration_check_loads_no_solver_no_mesh_and_no_plotting():
    """What snakemake imports to check the configuration before any job: the registry and the
    options, never a solver, scikit-fem or matplotlib."""
    code = (
        "import sys, rodimpact.config.load, rodimpact.jobs.resources, rodimpact.tools.bench_plan; "
        "print('\\n'.join(sorted(sys.modules)))"
    )
    loaded = set(
        subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
    )
    assert not {m for m in loaded if m.split(".")[0] in ("skfem", "matplotlib")}
    solvers = {
        m for m in loaded if m.endswith((".solver", ".stepper", ".history", ".bar", ".meshes", ".axisym", ".axibody"))
    }
    assert solvers == set()
    assert "rodimpact.solvers.registry" in loaded


def test_the_rule_files_import_no_tables_no_solvers_and_no_checker():
    """What the Snakefile and the rule files import as they are parsed (the package modules at
    their top; the configuration checker's own imports wait until it runs, inside
    ``checked_project``): no jsonschema, no pandas, no scipy, no h5py. Every dry run, and every job
    a cluster starts, pays for what they import. (Running the rule files does load pandas: each
    sweep's ``Paramspace``, snakemake's, wraps a DataFrame; snakemake loads jsonschema on its own,
    and its SLURM plugin pandas, before the Snakefile is read.)"""
    workflow = SRC.parent / "workflow"
    files = [SRC.parent / "Snakefile", *sorted((workflow / "rules").glob("*.smk"))]
    found = (re.findall(r"^(?:from|import) (rodimpact[\w.]*)", f.read_text(encoding="utf-8"), re.M) for f in files)
    modules = sorted({m for names in found for m in names})
    assert {"rodimpact.config.calibration", "rodimpact.jobs.resources", "rodimpact.plumbing.targets"} <= set(modules)
    code = f"import sys; [__import__(m) for m in {modules!r}]; print('\\n'.join(sorted(sys.modules)))"
    loaded = set(
        subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
    )
    heavy = {"jsonschema", "referencing", "pandas", "scipy", "h5py", "skfem", "matplotlib"}
    assert {m.split(".")[0] for m in loaded} & heavy == set()


def _literal_strings(node: ast.AST) -> set[str]:
    items = node.keys if isinstance(node, ast.Dict) else getattr(node, "elts", [])
    return {item.value for item in items if isinstance(item, ast.Constant) and isinstance(item.value, str)}


def test_no_module_writes_out_the_list_of_methods():
    """The methods are declared once, in the registry; nothing else holds a list of them (a
    tuple, list, set or dict literal naming every method)."""
    sys.path.insert(0, str(SRC))
    from rodimpact.solvers.registry import METHODS

    holders = []
    for path in _modules():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.Tuple, ast.List, ast.Set, ast.Dict)) and set(METHODS) <= _literal_strings(node):
                holders.append(f"{path.relative_to(SRC)}:{node.lineno}")
    for path in sorted((SRC.parent / "workflow").rglob("*.smk")) + sorted((SRC.parent / "workflow").rglob("*.yaml")):
        text = path.read_text(encoding="utf-8")
        if (
            all(f"{name}" in text for name in METHODS)
            and "fem_axi" in text
            and "sem_paper" in text
            and any(f"[{', '.join(METHODS)}]" in line or f"{', '.join(METHODS)}" in line for line in text.splitlines())
        ):
            holders.append(str(path.relative_to(SRC.parent)))
    assert holders == []


def test_no_law_name_appears_outside_the_contact_package():
    """Each contact law declares itself in rodimpact.contact (name, settings, needs, methods,
    conflicts); nothing else compares or spells a law's name: no string literal equal to a
    law's name in a module outside rodimpact/contact/, and no quoted law name in the rules,
    the scripts or the schemas."""
    sys.path.insert(0, str(SRC))
    from rodimpact.contact.laws import LAWS

    contact = PACKAGE / "contact"
    spelled = []
    for path in _modules():
        if contact in path.parents:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in LAWS:
                spelled.append(f"{path.relative_to(SRC)}:{node.lineno} {node.value!r}")
    quoted = re.compile("|".join(rf"""(["'`]){re.escape(name)}\1""" for name in LAWS))
    workflow = SRC.parent / "workflow"
    for path in sorted(workflow.rglob("*.smk")) + sorted(workflow.rglob("*.py")) + sorted(workflow.rglob("*.yaml")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if quoted.search(line):
                spelled.append(f"{path.relative_to(SRC.parent)}:{number} {line.strip()}")
    assert spelled == []
