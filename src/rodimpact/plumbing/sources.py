"""Which source files a piece of the workflow runs, from the static import graph, and their digest.

Snakemake does not see the modules a script imports. Each rule passes, as a ``params`` entry,
the digest of the package files its entry modules import (transitively): snakemake reruns a
job whose params changed (its default rerun triggers), so a change to the code a rule runs
reruns it, and a change to unrelated code (a figure, a benchmark) does not. One value per job
instead of some sixty input files keeps planning cheap: snakemake looks every input of every
job up against every rule's outputs.

What snakemake does on its own
    For a ``script:`` rule it records the script's own source (rerun trigger ``code``), not
    the modules the script imports; its ``params`` trigger compares the ``repr`` of each param
    with the one recorded when the job last ran.

Why that is not enough here
    The science lives in ``src/rodimpact``, which the scripts import.

If snakemake's internals change
    Should snakemake stop rerunning on changed params, a code change reruns nothing:
    ``tests/test_workflow_changes.py::test_a_methods_code_change_reruns_only_its_runs`` fails.
"""

from __future__ import annotations

import hashlib
import os
import re
from collections.abc import Iterable
from pathlib import Path

__all__ = ["imported_modules", "module_sources", "source_digest"]

PACKAGE = "rodimpact"

#: (file, modification time, size) -> the package modules it imports: each file is read once
#: per process, however many rules ask for its closure.
_PARSED: dict[tuple[str, int, int], frozenset[str]] = {}


def _module_file(src: str, module: str) -> str | None:
    """The file of ``module`` under the directory ``src`` (paths as strings: a cold dry run looks
    up some two thousand modules, and a :class:`~pathlib.Path` costs more than the look-up)."""
    base = os.path.join(src, *module.split("."))
    for candidate in (base + ".py", os.path.join(base, "__init__.py")):
        if os.path.isfile(candidate):
            return candidate
    return None


def _parents(module: str) -> list[str]:
    parts = module.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts))]


#: ``from X import Y`` (X with its leading dots; Y a parenthesised list or the rest of the
#: line, with backslash continuations), and ``import X, Y as Z``, at any indent (an import inside
#: a function counts) or after a semicolon. Scanning the text is ten times faster than parsing it (a cold dry run
#: reads every package file); ``tests/test_sources.py`` checks that it finds exactly what
#: :mod:`ast` finds in every file of the package. An import-like line in a docstring can only
#: add a module, never hide one.
_FROM = re.compile(r"(?:^|;)[ \t]*from[ \t]+(\.*)([\w.]*)[ \t]+import[ \t]+(\([^)]*\)|(?:[^\n#;\\]|\\\n)+)", re.M)
_IMPORT = re.compile(r"(?:^|;)[ \t]*import[ \t]+((?:[^\n#;\\]|\\\n)+)", re.M)


def _names(text: str) -> list[str]:
    """The names of an import's list (``a, b as c`` -> ``['a', 'b']``), comments dropped."""
    names = []
    for part in re.sub(r"#[^\n]*", "", text).replace("\\\n", " ").strip().strip("()").split(","):
        part = part.strip()
        if part:
            names.append(part.split()[0])
    return names


def imported_modules(module: str, text: str, is_package: bool = False) -> set[str]:
    """Every module the source ``text`` of ``module`` imports, absolute and relative (resolved
    against the module's package; ``is_package`` for an ``__init__.py``); for a name imported
    from a module, also the module's submodule of that name, which it may be."""
    package = module if is_package else module.rpartition(".")[0]
    found: set[str] = set()
    for match in _IMPORT.finditer(text):
        found.update(_names(match.group(1)))
    for match in _FROM.finditer(text):
        dots, name, what = match.groups()
        if dots:
            anchor = package.split(".")
            base = ".".join(anchor[: len(anchor) - (len(dots) - 1)] + ([name] if name else []))
        else:
            base = name
        found.add(base)
        found.update(f"{base}.{alias}" for alias in _names(what))
    return found


def _imports(src: str, module: str, path: str) -> frozenset[str]:
    """Package modules imported by ``module`` (file ``path``)."""
    stat = os.stat(path)
    key = (os.path.abspath(path), stat.st_mtime_ns, stat.st_size)
    if key in _PARSED:
        return _PARSED[key]
    with open(path, encoding="utf-8") as stream:
        found = imported_modules(module, stream.read(), os.path.basename(path) == "__init__.py")
    result = frozenset(m for m in found if (m == PACKAGE or m.startswith(PACKAGE + ".")) and _module_file(src, m))
    _PARSED[key] = result
    return result


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

    Raises
    ------
    ModuleNotFoundError
        An entry module is not a file under ``src``.
    """
    src = str(Path(src))  # normalised once, as a Path would give each file
    todo = list(entry_modules)
    seen: set[str] = set()
    files: set[str] = set()
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
    return sorted(files)


def source_digest(src: str | Path, entry_modules: Iterable[str]) -> str:
    """SHA-256 (hex) of the sources :func:`module_sources` finds: each file's path below ``src``
    and its bytes. Another checkout of the same code has the same digest; a change to any of
    those files, or a module added to or dropped from the closure, changes it."""
    src = str(Path(src))
    sha = hashlib.sha256()
    for name in module_sources(src, entry_modules):
        with open(name, "rb") as stream:
            data = stream.read()
        for part in (Path(os.path.relpath(name, src)).as_posix().encode(), data):
            sha.update(len(part).to_bytes(8, "little"))
            sha.update(part)
    return sha.hexdigest()
