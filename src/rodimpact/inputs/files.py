"""Reading a user's file safely: one regular file, bounded, decoded, or one clear line.

Every file the configuration names (config.yaml, the materials, the case files, a case's force
history) comes from many hands. What can go wrong, and what happens instead:

* a FIFO, a device or a directory in place of a file: opening it may block for ever (a FIFO
  waits for a writer) or read without end; :func:`regular_file` looks at what the path is
  (after its links) and refuses anything but a regular file, without opening it;
* a link: resolved first, so that a check of where the file lies sees its target;
* a huge file: refused by its size before it is read (:data:`MAX_FILE_BYTES`, or the caller's
  limit), the limit named;
* a byte that is not of the declared encoding: named by its line and column, not a traceback;
* a value quoted in a message: at most :data:`QUOTE_CHARS` characters of it, with its length
  (:func:`quoted`), so that one line stays one line.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

__all__ = [
    "KINDS",
    "MAX_FILE_BYTES",
    "QUOTE_CHARS",
    "InputFileError",
    "quoted",
    "read_bytes",
    "read_text",
    "regular_file",
]

#: What can be wrong with an input file (:attr:`InputFileError.kind`).
KINDS = ("missing", "unreadable", "not_regular", "too_large", "encoding")

#: The largest file read, bytes, unless the caller says otherwise: far above any configuration
#: or force history, far below what would exhaust a machine.
MAX_FILE_BYTES = 64 * 1024 * 1024
#: The characters of a value a message quotes.
QUOTE_CHARS = 100

_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


class InputFileError(ValueError):
    """A file that cannot be read as an input: ``path`` and ``reason`` kept as data.

    Parameters
    ----------
    path : Path
        The file as the configuration names it (before its links are resolved).
    reason : str
        What is wrong, in one line, without the path.
    kind : str
        One of :data:`KINDS`: what is wrong, for a caller that treats one kind apart (a
        missing file, say).
    """

    def __init__(self, path: Path, reason: str, kind: str) -> None:
        if kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
        super().__init__(f"{path}: {reason}")
        self.path, self.reason, self.kind = Path(path), reason, kind


def quoted(value: object, limit: int = QUOTE_CHARS) -> str:
    """``repr(value)``, or its first ``limit`` characters and its length when it is longer."""
    text = repr(value)
    if len(text) <= limit:
        return text
    return f"{text[:limit]}... ({len(text)} characters)"


def regular_file(path: str | Path) -> Path:
    """The file ``path`` names, its links resolved, when it is a regular file; never opened.

    Raises
    ------
    InputFileError
        No such file (or a dangling link), or not a regular file (a directory, a FIFO, a
        device, a socket), named by what it is.
    """
    path = Path(path)
    try:
        resolved = path.resolve(strict=True)
        mode = os.stat(resolved).st_mode
    except FileNotFoundError:
        raise InputFileError(
            path, "no such file" + (" (a link to nowhere)" if path.is_symlink() else ""), "missing"
        ) from None
    except (OSError, RuntimeError) as error:  # a loop of links (RuntimeError: no strerror), no permission
        raise InputFileError(
            path, f"cannot be read: {getattr(error, 'strerror', None) or error}", "unreadable"
        ) from None
    if not stat.S_ISREG(mode):
        kind = next((words for test, words in _KINDS if test(mode)), "not a regular file")
        raise InputFileError(path, f"is {kind}, not a regular file", "not_regular")
    return resolved


def read_bytes(path: str | Path, *, limit: int = MAX_FILE_BYTES) -> bytes:
    """The bytes of the regular file ``path`` (:func:`regular_file`), at most ``limit`` of them.

    The file is opened without blocking (a file that turned into a FIFO since it was looked at
    still returns at once) and read up to ``limit + 1`` bytes: the size is checked on what was
    read, not only on what the directory said.

    Raises
    ------
    InputFileError
        As :func:`regular_file`, or larger than ``limit`` (the limit named).
    """
    resolved = regular_file(path)
    size = os.stat(resolved).st_size
    if size > limit:
        raise InputFileError(Path(path), f"is {size} bytes, more than the {limit} allowed", "too_large")
    try:
        descriptor = os.open(resolved, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as error:
        raise InputFileError(Path(path), f"cannot be read: {error.strerror or error}", "unreadable") from None
    with os.fdopen(descriptor, "rb") as handle:
        data = handle.read(limit + 1)
    if len(data) > limit:
        raise InputFileError(Path(path), f"is more than the {limit} bytes allowed", "too_large")
    return data


def read_text(path: str | Path, *, encoding: str = "utf-8", limit: int = MAX_FILE_BYTES) -> str:
    """The text of the regular file ``path``: :func:`read_bytes`, decoded.

    Raises
    ------
    InputFileError
        As :func:`read_bytes`, or a byte that is not ``encoding`` (its line, its column and its
        value named).
    """
    data = read_bytes(path, limit=limit)
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as error:
        before = data[: error.start]
        line = before.count(b"\n") + 1
        column = error.start - (before.rfind(b"\n") + 1) + 1
        raise InputFileError(
            Path(path), f"is not {encoding}: byte 0x{data[error.start]:02x} at line {line}, column {column}", "encoding"
        ) from None
