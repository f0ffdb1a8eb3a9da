"""Whole-or-nothing file output: write beside the target, then rename onto it."""

from __future__ import annotations

import contextlib
import glob
import logging
import os
import re
import secrets
from pathlib import Path
from typing import Iterator

__all__ = ["atomic_output", "remove_stale_temporaries"]

logger = logging.getLogger(__name__)


def _fsync_file(path: Path) -> None:
    """Flush a file's data to the disk."""
    with open(path, "rb+") as handle:
        os.fsync(handle.fileno())


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
    with contextlib.suppress(OSError):  # make the rename durable where supported
        fd = os.open(target.parent, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
