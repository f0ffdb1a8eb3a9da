"""No module imports another's private name: a name that starts with ``_`` is its module's own.

A name another module needs is that module's public API (no underscore, a docstring, in
``__all__``), or the two modules hold one idea and are one module. Checked with :mod:`ast` over
every module under ``src/rodimpact``, for each way a module can reach another's name:

- ``from rodimpact.x import _name`` (absolute or relative, at any depth, inside functions too);
- ``import rodimpact.x`` or ``from rodimpact import x`` followed by ``x._name``;
- a ``"rodimpact.x:_name"`` string, the form the method registry loads a function by.

Dunder names (``__version__``, ``__all__``) are not private.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "rodimpact"

_DOTTED_FUNCTION = re.compile(r"^(rodimpact(?:\.\w+)+):(\w+)$")


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_module(name: str) -> bool:
    base = SRC.joinpath(*name.split("."))
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def _is_private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _base(node: ast.ImportFrom, module: str, is_package: bool) -> str:
    """The absolute name of the module ``node`` imports from."""
    if not node.level:
        return node.module or ""
    package = module if is_package else module.rpartition(".")[0]
    parts = package.split(".")
    anchor = parts[: len(parts) - node.level + 1]
    return ".".join(anchor + ([node.module] if node.module else []))


def _dotted(node: ast.expr) -> list[str] | None:
    """``a.b.c`` as ``["a", "b", "c"]``; None when it does not start with a plain name."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    return [node.id, *reversed(parts)]


def private_uses(module: str, source: str, *, is_package: bool = False) -> list[str]:
    """Every private name of another rodimpact module that ``source`` (the text of ``module``)
    reaches, as ``"line N: owner._name"``."""
    tree = ast.parse(source)
    found: list[str] = []
    modules: dict[str, str] = {}  # a local name bound to a rodimpact module -> that module
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = _base(node, module, is_package)
            if not (base == "rodimpact" or base.startswith("rodimpact.")):
                continue
            for alias in node.names:
                if _is_private(alias.name) and base != module:
                    found.append(f"line {node.lineno}: {base}.{alias.name}")
                if _is_module(f"{base}.{alias.name}"):
                    modules[alias.asname or alias.name] = f"{base}.{alias.name}"
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == "rodimpact" or alias.name.startswith("rodimpact."):
                    if alias.asname:
                        modules[alias.asname] = alias.name
                    else:
                        modules["rodimpact"] = "rodimpact"
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            match = _DOTTED_FUNCTION.match(node.value)
            if match and _is_private(match[2]) and match[1] != module:
                found.append(f"line {node.lineno}: {match[1]}.{match[2]} (named in a string)")
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Attribute) and _is_private(node.attr)):
            continue
        chain = _dotted(node.value)
        if chain is None or chain[0] not in modules:
            continue
        owner = modules[chain[0]]
        for part in chain[1:]:  # rodimpact.x.y._name: the longest prefix that is a module
            if not _is_module(f"{owner}.{part}"):
                break
            owner = f"{owner}.{part}"
        else:
            if owner != module:
                found.append(f"line {node.lineno}: {owner}.{node.attr}")
    return found


def _checked_modules() -> list[Path]:
    return [path for path in sorted(PACKAGE.rglob("*.py"))]


@pytest.mark.parametrize(
    ("source", "found"),
    [
        ("from rodimpact.contact.law import _check_positive", "rodimpact.contact.law._check_positive"),
        ("from .law import ContactLaw, _check_positive", "rodimpact.contact.law._check_positive"),
        ("def f():\n    from ..model.problem import _x", "rodimpact.model.problem._x"),
        ("import rodimpact.contact.law as law\nlaw._check_positive(c=1.0)", "rodimpact.contact.law._check_positive"),
        ("import rodimpact.contact.law\nrodimpact.contact.law._rigid(1)", "rodimpact.contact.law._rigid"),
        ("from rodimpact.contact import law\nlaw._check_positive(c=1.0)", "rodimpact.contact.law._check_positive"),
        ('SOLVER = "rodimpact.solvers.fem_axi.solver:_solve"', "rodimpact.solvers.fem_axi.solver._solve"),
    ],
)
def test_the_check_finds_each_way_of_reaching_a_private_name(source, found):
    uses = private_uses("rodimpact.contact.spring", source)
    assert len(uses) == 1 and f": {found}" in uses[0], uses


@pytest.mark.parametrize(
    "source",
    [
        "from rodimpact.contact.law import ContactLaw, check_positive",
        "from rodimpact.solvers.fem_axi.layers import positive as _positive",  # a public name kept local
        "import rodimpact\nrodimpact.__version__",
        "from rodimpact.contact import law\nlaw.ContactLaw.__init__",
        "import numpy as np\nnp._NoValue",
        "from rodimpact.contact.spring import _own",  # the module's own name
        "x = self._cache",
    ],
)
def test_the_check_lets_public_names_and_a_modules_own_pass(source):
    assert private_uses("rodimpact.contact.spring", source) == []


def test_no_module_imports_another_modules_private_name():
    offences = []
    for path in _checked_modules():
        module = _module_name(path)
        uses = private_uses(module, path.read_text(encoding="utf-8"), is_package=path.name == "__init__.py")
        offences += [f"{path.relative_to(SRC)} {use}" for use in uses]
    assert not offences, "private names of other modules imported:\n" + "\n".join(offences)
