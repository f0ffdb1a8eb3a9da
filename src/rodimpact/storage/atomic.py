"""Whole-or-nothing output: write beside the target, then rename onto it; a file
(:func:`atomic_output`) or a directory of files (:func:`atomic_directory`, a batch's runs)."""

from __future__ import annotations

import contextlib
import glob
import logging
import os
import re
import secrets
import shutil
from collections.abc import Iterator
from pathlib import Path

__all__ = ["atomic_directory", "atomic_output", "remove_stale_temporaries"]

logger = logging.getLogger(__name__)


def _fsync_file(path: Path) -> None:
    """Flush a file's data to the disk."""
    with open(path, "rb+") as handle:
        os.fsync(handle.fileno())


def _fsync_directory(path: Path) -> None:
    """Flush a directory's entries (a rename in it) to the disk, where the system allows."""
    with contextlib.suppress(OSError):
        fd = os.open(path, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def _temporary_name(target: Path) -> re.Pattern[str]:
    return re.compile(re.escape(target.stem) + r"\.tmp-[0-9a-f]{8}" + re.escape(target.suffix))


def remove_stale_temporaries(path: str | Path) -> list[Path]:
    """Remove the temporary files an interrupted write of ``path`` left beside it (a writer
    killed before its rename); the removed paths. One writer at a time per target (snakemake's
    lock and its job graph), so none of them belongs to a live write."""
    target = Path(path)
    if not target.parent.is_dir():
        return []
    pattern = _temporary_name(target)
    removed = [p for p in target.parent.glob(f"{glob.escape(target.stem)}.tmp-*") if pattern.fullmatch(p.name)]
    for stale in removed:
        with contextlib.suppress(FileNotFoundError):
            stale.unlink()
            logger.warning("removed %s, left by an interrupted write of %s", stale, target)
    return removed


@contextlib.contextmanager
def atomic_output(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success it replaces ``path`` atomically.

    First, the temporary files an earlier, interrupted write of ``path`` left are removed.

    On any exception the temporary file is removed and ``path`` is left as it was. The
    temporary name keeps the suffix (``x.tmp-<hex>.png``) so writers that infer the
    format from the extension work. The file is fsynced before the rename, and the
    directory after it where the system allows, so that the rename survives a power cut.
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target)
    tmp = target.with_name(f"{target.stem}.tmp-{secrets.token_hex(4)}{target.suffix}")
    try:
        yield tmp
        _fsync_file(tmp)
        os.replace(tmp, target)
    finally:
        if tmp.exists():
            tmp.unlink()
    _fsync_directory(target.parent)  # make the rename durable where supported


def _remove_stale_directories(target: Path) -> None:
    """Remove the temporary directories an interrupted :func:`atomic_directory` of ``target`` left."""
    pattern = re.compile(re.escape(f".{target.name}.tmp-") + r"[0-9a-f]{8}")
    for stale in target.parent.glob(f".{glob.escape(target.name)}.tmp-*"):
        if pattern.fullmatch(stale.name) and stale.is_dir():
            shutil.rmtree(stale, ignore_errors=True)
            logger.warning("removed %s, left by an interrupted write of %s", stale, target)


@contextlib.contextmanager
def atomic_directory(path: str | Path) -> Iterator[Path]:
    """Yield a temporary directory beside ``path`` (``.<name>.tmp-<hex>``); on success it is renamed
    onto ``path``, which must not exist or be empty: the directory appears whole or not at all.

    First, the temporary directories an earlier, interrupted write of ``path`` left are removed.
    On any exception the temporary directory is removed and ``path`` is left as it was. The files
    written into it are fsynced by their own writers (:func:`atomic_output`).
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    _remove_stale_directories(target)
    tmp = target.with_name(f".{target.name}.tmp-{secrets.token_hex(4)}")
    tmp.mkdir()
    try:
        yield tmp
        os.replace(tmp, target)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    _fsync_directory(target.parent)  # make the rename durable where supported
