"""A measured force history: the file read and checked (one error per fault, naming its key),
and its comparison with a computed force against answers known in closed form."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rodimpact.analysis.history_compare import compare_force_histories, threshold_crossings
from rodimpact.analysis.measured import MAX_ROWS, HistoryError, read_force_history


def _pulse(t: np.ndarray, duration: float = 50e-6, peak: float = 200.0) -> np.ndarray:
    """A half-sine contact force of ``duration`` s starting at t = 0 (zero outside)."""
    return np.where((t >= 0) & (t <= duration), peak * np.sin(np.pi * np.clip(t, 0, duration) / duration), 0.0)


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def test_units_from_the_header_or_declared_and_the_offset(tmp_path: Path) -> None:
    rows = "\n".join(f"{k},{0.1 * k}" for k in range(30))
    header = read_force_history(_write(tmp_path / "a.csv", "time_us,force_kN\n" + rows), {})
    declared = read_force_history(
        _write(tmp_path / "b.csv", "time,force\n" + rows),
        {"time_unit": "us", "force_unit": "kN", "time_offset_s": -2e-6, "note": "piezo"},
    )
    np.testing.assert_allclose(header.time_s, 1e-6 * np.arange(30), rtol=1e-12)
    np.testing.assert_allclose(header.force_N, 100.0 * np.arange(30), rtol=1e-12)
    np.testing.assert_allclose(declared.time_s, header.time_s - 2e-6, rtol=0, atol=1e-18)
    assert declared.note == "piezo"
    thinned = read_force_history(tmp_path / "a.csv", {"every": 3})
    np.testing.assert_allclose(thinned.time_s, 1e-6 * np.arange(0, 30, 3), rtol=1e-12)


@pytest.mark.parametrize(
    "name, text, spec, field, words",
    [
        ("missing.csv", None, {}, "file", "no such file"),
        ("noheader.csv", "0,1\n1,2\n", {}, "file", "header"),
        # a unit the header gives is the header's fault: its file, line and column
        ("unit.csv", "time_fortnight,force_N\n", {}, "file", "unit.csv line 1, column 1: unknown unit 'fortnight'"),
        ("lbf.csv", "time_s,force_lbf\n", {}, "file", "line 1, column 2: unknown unit 'lbf'"),
        ("nounit.csv", "time,force_N\n", {}, "time_unit", "names no unit"),
        ("clash.csv", "time_s,force_N\n", {"force_unit": "kN"}, "force_unit", "contradicts"),
        (
            "back.csv",
            "time_s,force_N\n" + "".join(f"{t},1\n" for t in [0, 1, 2, 3, 2.5, 5, 6, 7, 8]),
            {},
            "file",
            "line 6: the time must increase",
        ),
        (
            "nan.csv",
            "time_s,force_N\n" + "".join(f"{t},1\n" for t in range(8)) + "9,nan\n",
            {},
            "file",
            "line 10: not a finite number",
        ),
        ("text.csv", "time_s,force_N\n0,abc\n", {}, "file", "line 2: not a number"),
        ("short.csv", "time_s,force_N\n0,1\n1,2\n", {}, "file", "fewer than 8"),
        ("zero.csv", "time_s,force_N\n" + "".join(f"{t},0\n" for t in range(9)), {}, "file", "zero throughout"),
        # a thinning that leaves too few rows is the thinning's fault, not the file's
        (
            "thin.csv",
            "time_s,force_N\n" + "".join(f"{t},1\n" for t in range(20)),
            {"every": 5},
            "every",
            "keeps 4 of the 20 rows",
        ),
        # an offset that swamps the steps of the times is the offset's fault
        (
            "offset.csv",
            "time_us,force_N\n" + "".join(f"{t},1\n" for t in range(20)),
            {"time_offset_s": 1e300},
            "time_offset_s",
            "swamps the times",
        ),
    ],
)
def test_each_bad_file_is_one_error_naming_its_key(tmp_path: Path, name, text, spec, field, words) -> None:
    path = tmp_path / name if text is None else _write(tmp_path / name, text)
    with pytest.raises(HistoryError) as caught:
        read_force_history(path, spec)
    assert caught.value.field == field and words in str(caught.value), str(caught.value)
    assert "\n" not in str(caught.value)


def test_a_record_over_a_million_rows_needs_a_declared_thinning(tmp_path: Path) -> None:
    path = tmp_path / "long.csv"
    with open(path, "w", encoding="utf-8") as handle:
        handle.write("time_s,force_N\n")
        handle.write("".join(f"{k},1\n" for k in range(MAX_ROWS + 1)))
    with pytest.raises(HistoryError, match="declare every: 2"):
        read_force_history(path, {})
    assert len(read_force_history(path, {"every": 2}).time_s) == math.ceil((MAX_ROWS + 1) / 2)


def test_threshold_crossings_of_a_half_sine_are_closed_form() -> None:
    t = np.linspace(-10e-6, 60e-6, 70001)
    start, end = threshold_crossings(t, _pulse(t), 0.05)
    # sin(pi t / T) = 0.05: t = T asin(0.05) / pi, and T - that
    expected = 50e-6 * math.asin(0.05) / math.pi
    assert start == pytest.approx(expected, rel=1e-5) and end == pytest.approx(50e-6 - expected, rel=1e-7)
    with pytest.raises(ValueError, match="start and end below"):
        threshold_crossings(t[t > 1e-6], _pulse(t[t > 1e-6]), 0.05)


@pytest.mark.parametrize("tau, scale", [(37e-6, 1.0), (-4.5e-6, 1.25), (0.0, 0.8)])
def test_a_record_equal_to_the_run_shifted_and_scaled_is_aligned_exactly(tau: float, scale: float) -> None:
    """P_m(t) = s P(t - tau): the alignment finds -tau, the errors are |1 - s| / s in both norms,
    and the contact times read at the threshold agree."""
    t = np.linspace(-20e-6, 80e-6, 4001)
    model = _pulse(t)
    result = compare_force_histories(t + tau, scale * model, t, model, threshold=0.05)
    assert result.shift_s == pytest.approx(-tau, abs=1e-15)
    assert result.l2_error == pytest.approx(abs(1 - scale) / scale, abs=1e-9)
    assert result.max_error == pytest.approx(abs(1 - scale) / scale, abs=1e-9)
    assert result.measured_contact_time_s == pytest.approx(result.model_contact_time_s, rel=1e-9)
    assert result.measured_peak_N == pytest.approx(scale * result.model_peak_N, rel=1e-12)


def test_a_longer_contact_is_seen_in_the_norms_and_the_contact_time() -> None:
    """A measured pulse 10 % longer than the model's: its contact time is 10 % longer, and the
    L2 error is that of two half-sines of 50 and 55 us aligned at their 5 % rise."""
    t = np.linspace(-20e-6, 100e-6, 24001)
    result = compare_force_histories(t, _pulse(t, 55e-6), t, _pulse(t, 50e-6))
    assert result.measured_contact_time_s / result.model_contact_time_s == pytest.approx(1.1, rel=1e-4)
    shift = 55e-6 * math.asin(0.05) / math.pi - 50e-6 * math.asin(0.05) / math.pi
    fine = np.linspace(-20e-6, 100e-6, 2_400_001)
    diff = _pulse(fine) - _pulse(fine + shift, 55e-6)
    expected = math.sqrt(np.trapezoid(diff**2, fine) / np.trapezoid(_pulse(fine, 55e-6) ** 2, fine))
    assert result.l2_error == pytest.approx(expected, rel=1e-3)


def test_a_fifo_a_directory_and_a_dangling_link_are_refused_without_a_read(tmp_path: Path) -> None:
    """A FIFO would block a read for ever: it is refused by what it is, at once."""
    import os

    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    for path, words in (
        (fifo, "is a FIFO (named pipe), not a regular file"),
        (tmp_path, "is a directory, not a regular file"),
    ):
        with pytest.raises(HistoryError) as caught:
            read_force_history(path, {})
        assert caught.value.field == "file" and words in caught.value.reason, caught.value.reason
    dangling = tmp_path / "gone.csv"
    dangling.symlink_to(tmp_path / "nowhere.csv")
    with pytest.raises(HistoryError) as caught:
        read_force_history(dangling, {})
    assert "no such file (a link to nowhere)" in caught.value.reason


def test_a_bad_byte_and_a_huge_cell_are_named_by_line_and_column(tmp_path: Path) -> None:
    latin = tmp_path / "latin.csv"
    latin.write_bytes(b"time_s,force_N\n0,1\n1,2\n2,caf\xe9\n")
    with pytest.raises(HistoryError) as caught:
        read_force_history(latin, {})
    assert caught.value.reason == "latin.csv: is not utf-8: byte 0xe9 at line 4, column 6"
    huge = _write(tmp_path / "huge.csv", "time_s,force_N\n0," + "1" * 200_000 + "\n")
    with pytest.raises(HistoryError) as caught:
        read_force_history(huge, {})
    assert caught.value.reason == (
        "huge.csv line 2: a line of 200002 characters, more than the 256 a row of two numbers takes"
    )
    wide = _write(tmp_path / "wide.csv", "time_s,force_N\n0," + "1" * 100 + "\n")
    with pytest.raises(HistoryError) as caught:
        read_force_history(wide, {})
    assert caught.value.reason == (
        "wide.csv line 2, column 2: a cell of 100 characters, more than the 64 a number or a header takes"
    )
    assert len(str(caught.value)) < 200


def test_a_file_over_the_size_limit_is_refused_by_its_size(tmp_path: Path, monkeypatch) -> None:
    import rodimpact.analysis.measured as measured

    monkeypatch.setattr(measured, "MAX_HISTORY_BYTES", 100)
    big = _write(tmp_path / "big.csv", "time_s,force_N\n" + "".join(f"{t},1\n" for t in range(40)))
    with pytest.raises(HistoryError) as caught:
        read_force_history(big, {})
    assert caught.value.field == "file" and "more than the 100 allowed" in caught.value.reason
