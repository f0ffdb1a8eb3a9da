"""Logging set-up for the workflow's scripts (the library itself only logs)."""

from __future__ import annotations

import contextlib
import logging
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path

from rodimpact.storage.faults import UnreadableInput

__all__ = ["script_logging"]


#: Errors the user or the machine causes (an input refused by its reader, a full disk, a file
#: system error): one line in the log and on stderr, no traceback.
ONE_LINE_ERRORS: tuple[type[BaseException], ...] = (UnreadableInput, OSError)


def one_line(error: BaseException, outputs: Sequence[str] = ()) -> str:
    """The error in one line (a message over several lines, as HDF5's, joined); an OS error
    names its file, else the job's outputs."""
    text = " ".join(str(error).split()) or type(error).__name__
    if isinstance(error, OSError):
        where = error.filename or ", ".join(map(str, outputs)) or "the job's outputs"
        cause = " ".join(str(error.strerror).split()) if error.strerror else text
        return f"{where}: {cause}"
    return text


@contextlib.contextmanager
def script_logging(
    log_path: str | Path, level: int = logging.INFO, outputs: Sequence[str] = ()
) -> Iterator[logging.Logger]:
    """Send log records to ``log_path`` and stderr; log any exception before re-raising it.

    An error of :data:`ONE_LINE_ERRORS` is logged as one line (naming ``outputs``, the job's
    targets, when it names no file) and ends the script with exit status 1, without a
    traceback; any other exception is logged with its traceback and raised.
    """
    Path(log_path).parent.mkdir(parents=True, exist_ok=True)
    handlers: list[logging.Handler] = [
        logging.FileHandler(log_path, mode="w", encoding="utf-8"),
        logging.StreamHandler(sys.stderr),
    ]
    logging.basicConfig(
        level=level, handlers=handlers, force=True, format="%(asctime)s %(levelname)s %(name)s: %(message)s"
    )
    logging.getLogger("skfem").setLevel(logging.WARNING)  # per-assembly chatter
    logger = logging.getLogger(f"{__package__}.script")  # loggers are named after their module
    # errors raised while objects are freed (h5py's handles of a file whose write failed) go
    # to the log file only: the failure itself is reported once, below
    previous_hook = sys.unraisablehook
    sys.unraisablehook = lambda raised: handlers[0].handle(
        logger.makeRecord(
            logger.name,
            logging.DEBUG,
            __file__,
            0,
            "ignored while freeing %r: %s",
            (raised.object, raised.exc_value),
            None,
        )
    )
    try:
        yield logger
    except ONE_LINE_ERRORS as error:
        logger.error("failed: %s", one_line(error, outputs))
        raise SystemExit(1) from None
    except BaseException:
        logger.exception("failed")
        raise
    finally:
        sys.unraisablehook = previous_hook
        for handler in handlers:
            handler.flush()
