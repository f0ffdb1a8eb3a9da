"""An input file a job cannot use, and how the next build remakes it.

A run, band or curve file that is truncated, corrupt or was changed after it was written is
refused by its reader with :class:`UnreadableInput`: one line naming the file and the cause.
The reader also marks the file out of date (:func:`mark_out_of_date`: its modification time
set to the epoch), so that snakemake's modification-time check reruns the job that makes it
on the next build; the message says so.

What snakemake does on its own
    A job reruns when an output is older than the job's script (its ``code`` trigger), whatever
    its inputs. For a rule whose output is a directory (a group's curves, a reading's bands),
    snakemake takes the modification time of the file ``.snakemake_timestamp`` it writes inside
    the directory when the job ends (:data:`DIRECTORY_TIMESTAMP`), not the times of the files in
    it.

Why that is not enough here
    A damaged file inside a directory output must rerun the job that wrote the directory: the
    directory's timestamp is marked too. (A file of runs is a rule's output itself: marking it
    is enough.)

If snakemake's internals change
    Should snakemake carry a directory's time elsewhere, a damaged file of a directory output is
    refused again on the next build instead of remade: ``tests/test_faults.py::
    test_a_damaged_file_of_a_directory_output_is_marked_with_its_directory`` fails.
"""

from __future__ import annotations

import contextlib
import logging
import os
from pathlib import Path

__all__ = ["DIRECTORY_TIMESTAMP", "REBUILD_HINT", "StoredFileError", "UnreadableInput", "mark_out_of_date"]

logger = logging.getLogger(__name__)

#: What the user runs after an input was refused (the marked file is remade first).
REBUILD_HINT = "marked out of date: `make paper` (or the same snakemake command) remakes it"
#: The file whose modification time snakemake takes for a directory output's.
DIRECTORY_TIMESTAMP = ".snakemake_timestamp"


def mark_out_of_date(path: str | Path) -> bool:
    """Set the file's modification time to the epoch (older than every input of its job), and so
    the timestamp of the directory output holding it, when it lies in one (a group's curve); False
    when the file cannot be touched."""
    with contextlib.suppress(OSError):
        os.utime(path, (0, 0))
        logger.warning("%s: marked out of date (modification time set to the epoch)", path)
        batch = Path(path).parent  # a file a reader refuses lies directly in its job's directory
        if (batch / DIRECTORY_TIMESTAMP).is_file():
            with contextlib.suppress(OSError):
                os.utime(batch / DIRECTORY_TIMESTAMP, (0, 0))
                logger.warning("%s: its batch %s marked out of date", path, batch)
        return True
    return False


class UnreadableInput(ValueError):
    """An input file that cannot be used (``path``, ``reason``); ``str()`` is one line.

    ``marked`` says whether the file was marked out of date for the next build: ``path``, or
    ``file`` when given (the file that holds what ``path`` names, a run in a file of runs).
    """

    def __init__(self, path: str | Path, reason: str, *, mark: bool = False, file: str | Path | None = None) -> None:
        self.path, self.reason = str(path), reason
        file = path if file is None else file
        self.marked = mark_out_of_date(file) if mark and Path(file).is_file() else False
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
