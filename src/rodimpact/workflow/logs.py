"""Logging set-up for the workflow's scripts (the library itself only logs)."""

from __future__ import annotations

import contextlib
import logging
import sys
from pathlib import Path
from typing import Iterator

__all__ = ["script_logging"]


@contextlib.contextmanager
def script_logging(log_path: str | Path, level: int = logging.INFO) -> Iterator[logging.Logger]:
    """Send log records to ``log_path`` and stderr; log any exception before re-raising it."""
    Path(log_path).parent.mkdir(parents=True, exist_ok=True)
    handlers: list[logging.Handler] = [logging.FileHandler(log_path, mode="w", encoding="utf-8"),
                                       logging.StreamHandler(sys.stderr)]
    logging.basicConfig(level=level, handlers=handlers, force=True,
                        format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    logging.getLogger("skfem").setLevel(logging.WARNING)  # per-assembly chatter
    logger = logging.getLogger(f"{__package__}.script")  # loggers are named after their module
    try:
        yield logger
    except BaseException:
        logger.exception("failed")
        raise
    finally:
        for handler in handlers:
            handler.flush()
