"""Which source files a piece of the workflow depends on, from the static import graph.

Snakemake does not see the modules a script imports. The rules list, as inputs, the
package files their entry modules import (transitively), so a change to the code a rule
runs reruns it, and a change to unrelated code (a figure, a benchmark) does not.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Iterable

__all__ = ["module_sources"]

PACKAGE = "rodimpact"


def _module_file(src: Path, module: str) -> Path | None:
    base = src.joinpath(*module.split("."))
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _parents(module: str) -> list[str]:
    parts = module.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts))]


def _imports(src: Path, module: str, path: Path) -> set[str]:
    """Package modules imported by ``module`` (file ``path``): absolute and relative."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join(anchor + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            found.add(base)
            # "from pkg import name" may import a submodule called name
            found.update(f"{base}.{alias.name}" for alias in node.names)
    return {m for m in found if (m == PACKAGE or m.startswith(PACKAGE + ".")) and _module_file(src, m)}


def module_sources(src: str | Path, entry_modules: Iterable[str]) -> list[str]:
    """Source files of ``entry_modules`` and every package module they import, transitively.

    Parameters
    ----------
    src : path
        The directory holding the ``rodimpact`` package (the project's ``src/``).
    entry_modules : iterable of str
        Dotted module names, e.g. ``["rodimpact.jobs.runner"]``.

    Returns
    -------
    list of str
        Sorted paths (as given by ``src``), package ``__init__.py`` files included.
    """
    src = Path(src)
    todo = list(entry_modules)
    seen: set[str] = set()
    files: set[Path] = set()
    while todo:
        module = todo.pop()
        if module in seen:
            continue
        seen.add(module)
        path = _module_file(src, module)
        if path is None:
            raise ModuleNotFoundError(f"entry_modules: no module {module!r} under {src}")
        files.add(path)
        todo.extend(_parents(module))
        todo.extend(_imports(src, module, path) - seen)
    return sorted(str(p) for p in files)
