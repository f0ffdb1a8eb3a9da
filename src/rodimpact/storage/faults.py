"""An input file a job cannot use, and how the next build remakes it.

A run, band or curve file that is truncated, corrupt or was changed after it was written is
refused by its reader with :class:`UnreadableInput`: one line naming the file and the cause.
The reader also marks the file out of date (:func:`mark_out_of_date`: its modification time
set to the epoch), so that snakemake's modification-time check reruns the job that makes it
on the next build; the message says so.
"""

from __future__ import annotations

import contextlib
import logging
import os
from pathlib import Path

__all__ = ["REBUILD_HINT", "StoredFileError", "UnreadableInput", "mark_out_of_date"]

logger = logging.getLogger(__name__)

#: What the user runs after an input was refused (the marked file is remade first).
REBUILD_HINT = "marked out of date: `make paper` (or the same snakemake command) remakes it"


def mark_out_of_date(path: str | Path) -> bool:
    """Set the file's modification time to the epoch (older than every input of its job);
    False when the file cannot be touched."""
    with contextlib.suppress(OSError):
        os.utime(path, (0, 0))
        logger.warning("%s: marked out of date (modification time set to the epoch)", path)
        return True
    return False


class UnreadableInput(ValueError):
    """An input file that cannot be used (``path``, ``reason``); ``str()`` is one line.

    ``marked`` says whether the file was marked out of date for the next build.
    """

    def __init__(self, path: str | Path, reason: str, *, mark: bool = False) -> None:
        self.path, self.reason = str(path), reason
        self.marked = mark_out_of_date(path) if mark and Path(path).is_file() else False
        hint = f"; {REBUILD_HINT}" if self.marked else ""
        super().__init__(f"{path}: {reason}{hint}")

    def __reduce__(self):
        return type(self), (self.path, self.reason)


class StoredFileError(UnreadableInput):
    """A file the workflow made (a prediction band, a contact-law curve) cannot be read, misses
    data or its data do not match their hash (``path``, ``reason``); a file that exists is
    marked out of date, so that the next build remakes it."""

    def __init__(self, path: str | Path, reason: str) -> None:
        super().__init__(path, reason, mark=True)
