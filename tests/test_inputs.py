"""``rodimpact.inputs.files``: a user's file read safely, or one line that says why not."""

from __future__ import annotations

import os
import signal
from pathlib import Path

import pytest

from rodimpact.inputs.files import InputFileError, quoted, read_bytes, read_text, regular_file


def _refused(path: Path, **options) -> InputFileError:
    with pytest.raises(InputFileError) as caught:
        read_text(path, **options)
    assert "\n" not in str(caught.value)
    return caught.value


def test_only_a_regular_file_is_read_and_links_are_followed(tmp_path: Path) -> None:
    real = tmp_path / "real.yaml"
    real.write_text("a: 1\n", encoding="utf-8")
    link = tmp_path / "link.yaml"
    link.symlink_to(real)
    assert regular_file(link) == real.resolve() and read_text(link) == "a: 1\n"
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    signal.alarm(20)  # a read of the FIFO would block: the test must not hang
    try:
        error = _refused(fifo)
    finally:
        signal.alarm(0)
    assert (error.kind, error.reason) == ("not_regular", "is a FIFO (named pipe), not a regular file")
    assert _refused(tmp_path).kind == "not_regular"
    dangling = tmp_path / "gone.yaml"
    dangling.symlink_to(tmp_path / "nowhere")
    assert (_refused(dangling).kind, _refused(dangling).reason) == ("missing", "no such file (a link to nowhere)")
    loop = tmp_path / "loop.yaml"
    loop.symlink_to(loop)
    assert _refused(loop).kind == "unreadable"


def test_the_size_is_bounded_and_a_bad_byte_named(tmp_path: Path) -> None:
    path = tmp_path / "x.csv"
    path.write_bytes(b"0123456789")
    assert read_bytes(path, limit=10) == b"0123456789"
    error = _refused(path, limit=9)
    assert (error.kind, error.reason) == ("too_large", "is 10 bytes, more than the 9 allowed")
    path.write_bytes(b"ok\nline two \xff here\n")
    error = _refused(path)
    assert (error.kind, error.reason) == ("encoding", "is not utf-8: byte 0xff at line 2, column 10")


def test_a_long_value_is_quoted_in_part_with_its_length() -> None:
    assert quoted("short") == "'short'"
    long = quoted("x" * 500)
    assert long == "'" + "x" * 99 + "... (502 characters)" and len(long) < 130
