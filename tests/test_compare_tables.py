"""``rodimpact.tools.compare_tables``: two builds' tables equal within rtol, or not, and why."""

from __future__ import annotations

from pathlib import Path

from rodimpact.tools.compare_tables import compare_tables, main


def _tables(root: Path, value: float, wall: float, md_value: str) -> Path:
    root.mkdir()
    (root / "t.csv").write_text(f"case_id,contact_time_s,wall_time_s\nmodel,{value!r},{wall!r}\n", encoding="utf-8")
    (root / "t.md").write_text(f"| case | time |\n|---|---|\n| model | {md_value} |\n", encoding="utf-8")
    return root


def test_equal_within_rtol_timing_columns_aside(tmp_path):
    before = _tables(tmp_path / "a", 5.648872613e-4, 1.0, "564.887")
    after = _tables(tmp_path / "b", 5.648872613e-4 * (1 + 3e-10), 9.0, "564.887")
    results = {r.name: r for r in compare_tables(before, after, rtol=1e-9)}
    assert results["t.csv"].same and 2e-10 < results["t.csv"].largest < 4e-10
    assert results["t.md"].same
    assert main([str(before), str(after)]) == 0


def test_a_difference_beyond_rtol_is_named(tmp_path, capsys):
    before = _tables(tmp_path / "a", 5.648872613e-4, 1.0, "564.887")
    after = _tables(tmp_path / "b", 5.648872613e-4 * (1 + 1e-6), 1.0, "564.888")
    results = {r.name: r for r in compare_tables(before, after, rtol=1e-9)}
    assert results["t.csv"].problems == ("column 'contact_time_s': relative difference 1e-06",)
    assert not results["t.md"].same
    assert main([str(before), str(after)]) == 1
    assert "2 files, 2 differ beyond rtol 1e-09" in capsys.readouterr().out


def test_a_file_on_one_side_only_differs(tmp_path):
    before = _tables(tmp_path / "a", 1.0, 1.0, "1")
    after = _tables(tmp_path / "b", 1.0, 1.0, "1")
    (after / "extra.csv").write_text("x\n1\n", encoding="utf-8")
    results = {r.name: r for r in compare_tables(before, after)}
    assert not results["extra.csv"].same


def test_a_percentage_is_compared_in_points_and_timing_cells_are_left_out(tmp_path):
    """-0.0478680 % against -0.0478681 %: 1e-7 points, 2e-6 relative; the percentage of two
    times agreeing to 1e-9 moves by about 1e-7 points, so it is the same at rtol 1e-9. A
    Markdown table's wall-time cell may differ."""
    before, after = tmp_path / "a", tmp_path / "b"
    for root, pct, wall in ((before, -0.0478680, "0.025"), (after, -0.0478681, "0.150")):
        root.mkdir()
        (root / "t.csv").write_text(f"row,model_form_pct\nr1,{pct!r}\n", encoding="utf-8")
        (root / "t.md").write_text(f"| Case | Wall time (s) |\n|---|---|\n| model | {wall} |\n", encoding="utf-8")
    results = {r.name: r for r in compare_tables(before, after, rtol=1e-9)}
    assert results["t.csv"].same and results["t.md"].same
    results = {r.name: r for r in compare_tables(before, after, rtol=1e-10)}
    assert results["t.csv"].problems == ("column 'model_form_pct': 1e-07 percentage points per 100",)
