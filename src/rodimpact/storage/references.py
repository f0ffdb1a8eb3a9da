"""How a run is named: its own file, or ``{file}#{name}`` for a run in a file of runs.

No HDF5 here (the workflow names every sweep point's run when it is parsed); the files
themselves are :mod:`rodimpact.storage.runs`'.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["RUN_SEPARATOR", "can_name_a_run", "run_reference", "split_reference"]

#: Between a file of runs and the name of one of its runs, in a run's reference.
RUN_SEPARATOR = "#"


def run_reference(path: str | Path, name: str) -> str:
    """The reference of the run ``name`` in the file of runs ``path``: ``"{path}#{name}"``."""
    return f"{path}{RUN_SEPARATOR}{name}"


def can_name_a_run(name: object) -> bool:
    """Whether ``name`` can name a run in a file of runs: a non-empty str, without ``/`` (an HDF5
    path) or :data:`RUN_SEPARATOR`, and not ``.`` or ``..``."""
    return (
        isinstance(name, str)
        and bool(name)
        and "/" not in name
        and RUN_SEPARATOR not in name
        and name not in (".", "..")
    )


def split_reference(reference: str | Path) -> tuple[Path, str | None]:
    """A run's file and its name in a file of runs (None for a run file of its own)."""
    path, separator, name = str(reference).partition(RUN_SEPARATOR)
    return Path(path), (name if separator else None)
