"""The tables written for people: headers in words with units, chosen columns, a page's width.

A table is declared once (rodimpact.present.table.Table): its frame, every column at full
precision under its machine name (the CSV), and a Column for each, its words, unit and format,
which every format written for people reads (Markdown, HTML for the report, LaTeX for a paper).
Checked on Table 2 built from in-memory runs, on the declarations themselves, and on every
table for people the small configuration's build writes.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rodimpact.analysis.sweeps import SWEEP_PARAMETERS
from rodimpact.present.columns import COLUMNS, method_error, method_header, method_time
from rodimpact.present.readings import reading_table
from rodimpact.present.sweep_table import SWEPT
from rodimpact.present.table import (
    LATEX_CHAR_PT,
    MAX_COLUMNS,
    Column,
    Panel,
    Table,
    for_people,
    header_lines,
    latex_escape,
    latex_tables,
    latex_width_pt,
    panels,
    write_table,
)
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.runs import RunRecord

from helpers.copies import DotTestBuild

#: The widest table a one-column journal page takes: a 6 in text block, pt (1 in = 72.27 pt).
PAGE_WIDTH_PT = 6.0 * 72.27

#: Table 2 of the paper (diameter mm, mass g, measured µs, FEM µs, FEM error %, SEM µs, SEM error %).
ROWS = [
    (3.16, 0.13, 36.42, 31.20, 14.33, 15.32, 57.93),
    (4.75, 0.44, 46.83, 60.75, 29.72, 23.63, 49.54),
    (5.56, 0.71, 52.26, 78.09, 49.42, 27.90, 46.61),
    (6.34, 1.04, 60.05, 81.61, 35.90, 31.71, 47.19),
    (9.51, 3.51, 84.96, 106.21, 25.01, 47.94, 43.57),
    (12.73, 8.46, 111.10, 121.71, 9.54, 64.82, 41.66),
]


def _record(row: tuple, variant: str, method: str, contact_time_us: float) -> RunRecord:
    diameter, mass, measured, fem, fem_err, sem, sem_err = row
    case_id = f"ball_{diameter}mm-{variant}"
    config = {
        "id": case_id,
        "row": f"ball_{diameter}mm",
        "variant": variant,
        "impactor": {
            "radius_m": diameter / 2000,
            "mass_kg": mass / 1000,
            "velocity_m_s": 0.3225,
            "material": {"name": "steel"},
        },
        "rod": {"radius_m": 0.01, "length_m": 0.0301, "material": {"name": "aluminium_table1"}},
        "measured": {"contact_time_us": measured},
        "published": {
            "fem": {"contact_time_us": fem, "error_pct": fem_err},
            "sem": {"contact_time_us": sem, "error_pct": sem_err},
        },
    }
    return RunRecord(
        path=Path(f"{case_id}/{method}.h5"),
        case_id=case_id,
        method=method,
        config=config,
        config_sha256="",
        code_version="",
        library_versions={},
        wall_time_s=0.0,
        created_utc="",
        series={},
        units={},
        summary={"contact_time_s": contact_time_us * 1e-6},
    )


def _records(methods: tuple[str, ...], variant: str = "r10_l30") -> list[RunRecord]:
    """Each ball by each method, a contact time 0.6 + 0.01 i of the measured (i the method's index)."""
    return [_record(row, variant, m, row[2] * (0.6 + 0.01 * i)) for row in ROWS for i, m in enumerate(methods)]


@pytest.fixture(scope="module")
def table2(tmp_path_factory) -> dict:
    """Table 2 of three methods, written as CSV, Markdown, HTML and LaTeX."""
    out = tmp_path_factory.mktemp("table2")
    records = _records(("sem", "fem1d", "fem_axi"))
    table = reading_table(records, "r10_l30", "Table 2", "Belyaev, Shurpatov and Ma (2018)")
    paths = {ext: out / f"table2_r10_l30.{ext}" for ext in ("csv", "md", "html", "tex")}
    write_table(table, **paths)
    return {
        "table": table,
        "frame": table.frame,
        "records": records,
        **{ext: p.read_text(encoding="utf-8") for ext, p in paths.items()},
        "paths": paths,
    }


# ---------------------------------------------------------------------------------------------
# columns: declared once, with their words, units and formats
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("column, header", [
    (COLUMNS["measured_us"], "Measured (µs)"), (COLUMNS["published_sem_error_pct"], "Paper SEM error (%)"),
    (COLUMNS["mass_g"], "Mass (g)"), (COLUMNS["diameter_mm"], "Diameter (mm)"), (method_time("sem"), "SEM (µs)"),
    (method_error("fem_axi"), "FEM axisym. error (%)"), (method_time("sem_paper"), "SEM, explicit (µs)"),
    (method_time("fem1d", "film"), "FEM 1-D, film (µs)"),
    (method_error("sem", "no_film_calibrated"), "SEM, calibrated, no film error (%)"),
    (COLUMNS["velocity_m_s"], "Velocity (m/s)"), (COLUMNS["film_modulus_pa"], "Film modulus (Pa)"),
    (COLUMNS["row"], "Ball"),
])  # fmt: skip
def test_a_header_is_words_and_its_unit(column: Column, header: str) -> None:
    assert column.header == header


def test_columns_made_per_method_are_named_by_the_method() -> None:
    assert method_time("fem1d", "film").name == "fem1d_film_us"
    assert method_error("sem").name == "sem_error_pct"


def test_every_swept_parameter_has_its_column() -> None:
    """A sweep's table shows each swept parameter under its declared words: every parameter a
    sweep may vary is declared, and nothing else."""
    assert set(SWEPT) == set(SWEEP_PARAMETERS)
    assert all(column.name == name for name, column in SWEPT.items())


def test_every_method_has_a_short_header() -> None:
    headers = {m: method_header(m) for m in METHODS}
    assert all(METHODS[m].header for m in METHODS)
    assert len(set(headers.values())) == len(headers)
    # a column of numbers (six characters) is no wider for its method's header, in two lines
    assert all(max(map(len, header_lines(h))) <= 8 for h in headers.values()), headers
    assert method_header("not_a_method") == "not_a_method"


def test_cells_round_and_mark_what_is_missing() -> None:
    assert Column("t", "t", "µs").text(36.4249) == "36.42"
    assert Column("t", "t", "µs").text(np.float64(math.nan)) == "–"
    assert Column("f", "f").text(np.bool_(True)) == "yes" and Column("f", "f", fmt="").text(False) == "no"
    assert Column("n", "n", fmt="").text(np.int64(6)) == "6"
    assert COLUMNS["mass_g"].text(0.0041) == "0.0041" and COLUMNS["mass_g"].text(8.46) == "8.46"


def test_a_table_declares_every_column_once() -> None:
    frame = pd.DataFrame({"mass_g": [1.0], "sem_us": [2.0]})
    Table(frame, (COLUMNS["mass_g"], method_time("sem"), method_time("fem1d")))  # an extra one is allowed
    with pytest.raises(ValueError, match="sem_us not declared"):
        Table(frame, (COLUMNS["mass_g"],))
    with pytest.raises(ValueError, match="declared twice: mass_g"):
        Table(frame, (COLUMNS["mass_g"], method_time("sem"), COLUMNS["mass_g"]))


def test_latex_escapes_text_and_sets_units() -> None:
    assert (
        latex_escape("r10_l30: 28 µm, 3.1e-06 m², 2·3, 50% & #1")
        == r"r10\_l30: 28 $\mu$m, 3.1e-06 m$^2$, 2$\cdot$3, 50\% \& \#1"
    )


def test_long_labels_wrap_in_two_balanced_lines() -> None:
    assert header_lines("SEM") == ("SEM", "")
    assert header_lines("SEM vs paper SEM") == ("SEM vs", "paper SEM")
    assert header_lines("Continuum") == ("Continuum", "")  # one word is never split


# ---------------------------------------------------------------------------------------------
# panels
# ---------------------------------------------------------------------------------------------


def _numbers(names: list[str], rows: int = 2) -> Table:
    frame = pd.DataFrame({c: [1.0 + i for i in range(rows)] for c in names})
    return Table(frame, tuple(Column(c, c.upper(), "µs") for c in names))


def test_panels_split_evenly_and_repeat_the_key() -> None:
    table = _numbers(["mass_g", *(f"v{i}_us" for i in range(9))])
    shown = panels(table, "T", ["mass_g", "absent_us"], [f"v{i}_us" for i in range(9)], label="tab:t")
    assert [p.columns for p in shown] == [
        ("mass_g", "v0_us", "v1_us", "v2_us", "v3_us", "v4_us"),
        ("mass_g", "v5_us", "v6_us", "v7_us", "v8_us"),
    ]
    assert [p.label for p in shown] == ["tab:t-1", "tab:t-2"]
    assert [p.title for p in shown] == ["T, part 1 of 2", "T, part 2 of 2"]
    with pytest.raises(ValueError, match="no room"):
        panels(table, "T", [f"v{i}_us" for i in range(8)], ["mass_g"])


def test_panels_by_a_column_show_each_group_alone() -> None:
    frame = pd.DataFrame({"variant": ["a", "b", "a"], "row": ["x", "y", "z"], "force_N": [1.0, 2.0, 3.0]})
    table = Table(frame, (COLUMNS["variant"], COLUMNS["row"], Column("force_N", "Force", "N")))
    shown = panels(table, "Indentation", ["row"], ["force_N"], by="variant")
    assert [(p.title, p.columns, p.rows) for p in shown] == [
        ("Indentation: reading a", ("row", "force_N"), (0, 2)),
        ("Indentation: reading b", ("row", "force_N"), (1,)),
    ]
    assert list(table.cells(shown[0])["row"]) == ["x", "z"]


# ---------------------------------------------------------------------------------------------
# Table 2: CSV, HTML, LaTeX, Markdown
# ---------------------------------------------------------------------------------------------


def test_table2_csv_keeps_every_column_at_full_precision(table2: dict) -> None:
    back = pd.read_csv(table2["paths"]["csv"])
    frame = table2["frame"]
    assert list(back.columns) == list(frame.columns)
    assert {"measured_us", "sem_us", "fem_axi_error_pct", "sem_vs_published_sem_pct"} <= set(back.columns)
    numeric = frame.select_dtypes("number").columns
    np.testing.assert_allclose(back[numeric].to_numpy(float), frame[numeric].to_numpy(float), rtol=1e-9)
    assert back["sem_us"].iloc[0] == pytest.approx(36.42 * 0.6, rel=1e-9)  # not rounded to 21.85


class _Tables(HTMLParser):
    """Each <table>: its caption, header cells and body rows (texts)."""

    def __init__(self) -> None:
        super().__init__()
        self.tables: list[dict] = []
        self._where: str | None = None
        self.tags: set[str] = set()

    def handle_starttag(self, tag, attrs) -> None:
        self.tags.add(tag)
        if tag == "table":
            self.tables.append({"caption": "", "th": [], "rows": []})
        elif tag in ("caption", "th", "td"):
            self._where = tag
            if tag == "th":
                self.tables[-1]["th"].append("")
            elif tag == "td":
                self.tables[-1]["rows"][-1].append("")
        elif tag == "tr" and self._in_body:
            self.tables[-1]["rows"].append([])
        elif tag == "tbody":
            self._in_body = True
        elif tag == "br" and self._where == "th":
            self.tables[-1]["th"][-1] += " "

    _in_body = False

    def handle_endtag(self, tag) -> None:
        if tag in ("caption", "th", "td"):
            self._where = None
        elif tag == "tbody":
            self._in_body = False

    def handle_data(self, data) -> None:
        table = self.tables[-1] if self.tables else None
        if self._where == "caption":
            table["caption"] += data
        elif self._where == "th":
            table["th"][-1] += data
        elif self._where == "td":
            table["rows"][-1][-1] += data


def test_table2_html_is_two_tables_with_units(table2: dict) -> None:
    parser = _Tables()
    parser.feed(table2["html"])
    assert parser.tags <= {"div", "style", "table", "caption", "thead", "tbody", "tr", "th", "td"}
    times, errors = parser.tables
    assert times["th"] == [
        "Diameter (mm)",
        "Mass (g)",
        "Measured (µs)",
        "Paper FEM (µs)",
        "Paper SEM (µs)",
        "SEM (µs)",
        "FEM 1-D (µs)",
        "FEM axisym. (µs)",
    ]
    assert errors["th"] == [
        "Diameter (mm)",
        "Mass (g)",
        "Paper FEM (%)",
        "Paper SEM (%)",
        "SEM (%)",
        "FEM 1-D (%)",
        "FEM axisym. (%)",
        "SEM vs paper SEM (%)",
    ]
    assert len(times["rows"]) == len(errors["rows"]) == 6
    assert times["rows"][0] == ["3.16", "0.13", "36.42", "31.20", "15.32", "21.85", "22.22", "22.58"]
    assert errors["rows"][-1][2:5] == ["9.54", "41.66", "40.00"]  # |0.6 t - t| / t
    assert "url(" not in table2["html"] and "<script" not in table2["html"]


def _environments(tex: str) -> list[str]:
    """The environments of a LaTeX text, checked to nest and close; their names in order of opening."""
    stack, opened = [], []
    for kind, name in re.findall(r"\\(begin|end)\{([^}]*)\}", tex):
        if kind == "begin":
            stack.append(name)
            opened.append(name)
        else:
            assert stack and stack.pop() == name, f"\\end{{{name}}} closes nothing open"
    assert not stack, f"unclosed: {stack}"
    return opened


def _braces_balance(tex: str) -> bool:
    depth = 0
    for ch in re.sub(r"\\[{}%&$#_]", "", tex):
        depth += {"{": 1, "}": -1}.get(ch, 0)
        if depth < 0:
            return False
    return depth == 0


def _tabulars(tex: str) -> list[tuple[str, list[str], list[str]]]:
    """Each tabular: its column spec, its header lines, its body lines."""
    out = []
    for spec, body in re.findall(r"\\begin\{tabular\}\{([^}]*)\}(.*?)\\end\{tabular\}", tex, re.S):
        head, _, rows = body.partition(r"\midrule")
        lines = lambda part: [ln.strip() for ln in part.splitlines() if ln.strip().endswith(r"\\")]  # noqa: E731
        out.append((spec, lines(head), lines(rows)))
    return out


def _check_latex(tex: str, table: Table, shown: list[Panel] | tuple[Panel, ...]) -> None:
    assert _environments(tex) == ["table", "tabular"] * len(shown)
    assert _braces_balance(tex)
    floats = re.findall(r"\\begin\{table\}.*?\\end\{table\}", tex, re.S)
    labels = [re.findall(r"\\label\{([^}]*)\}", f) for f in floats]
    assert all(len(lab) == 1 and lab[0].startswith("tab:") for lab in labels), labels
    assert len({lab[0] for lab in labels}) == len(floats)
    assert all(len(re.findall(r"\\caption\{", f)) == 1 for f in floats)
    for (spec, head, body), panel in zip(_tabulars(tex), shown):
        assert len(spec) == len(panel.columns) <= MAX_COLUMNS
        for line in head + body:
            assert line.count("&") == len(spec) - 1, line
        header = " ".join(head)
        assert "\\_" not in header, header  # no machine name in a header
        assert latex_width_pt(table, panel) <= PAGE_WIDTH_PT, (panel.title, latex_width_pt(table, panel))
    assert not re.search(r"\bus\b|\bum\b", tex), "a unit written as us or um"
    assert "booktabs" in tex.splitlines()[0]


def test_table2_latex_is_journal_ready(table2: dict) -> None:
    tex, table = table2["tex"], table2["table"]
    _check_latex(tex, table, table.panels)
    assert r"\label{tab:table2-r10-l30-times}" in tex and r"\label{tab:table2-r10-l30-errors}" in tex
    assert r"\ref{tab:table2-r10-l30-times}" in tex
    (_, head, body), _ = _tabulars(tex)[0], None
    assert head[-1] == r"(mm) & (g) & ($\mu$s) & ($\mu$s) & ($\mu$s) & ($\mu$s) & ($\mu$s) & ($\mu$s) \\"
    assert body[0] == r"3.16 & 0.13 & 36.42 & 31.20 & 15.32 & 21.85 & 22.22 & 22.58 \\"
    caption = re.search(r"\\caption\{(.*)\}\n", tex).group(1)
    assert "0.3225~m/s" in caption and r"\texttt{r10\_l30}" in caption and "radius 10 mm" in caption


def test_table2_of_four_methods_splits_within_a_page() -> None:
    records = _records(("sem", "sem_paper", "fem1d", "fem_axi"), variant="r1_l30")
    table = reading_table(records, "r1_l30", "Table 2")
    shown = table.panels
    assert len(shown) == 4  # the times and the errors, each in two parts
    assert all(p.columns[:2] == ("diameter_mm", "mass_g") for p in shown)
    _check_latex(latex_tables(table), table, shown)


def test_table2_markdown_has_every_column_in_words(table2: dict) -> None:
    """Every column with a value, each once: the case id gives way to its ball's (the row's)."""
    table = table2["table"]
    header = table2["md"].splitlines()[2]
    cells = [c.strip() for c in header.strip("|").split("|")]
    assert cells == [table.column(c).header for c in for_people(table)]
    assert "Measured (µs)" in cells and not any("_" in c for c in cells)
    assert "ball_3.16mm" in table2["md"] and "Case" not in cells


def test_a_table_for_people_says_each_thing_once_in_words() -> None:
    """An id with its words in another column gives way to it, under the id's header; an id
    another column says is left out, and so is a column without a value; a column of method or
    law ids is shown in their words."""
    names = ["case_id", "row", "method", "method_label", "contact_law", "measured_us"]
    frame = pd.DataFrame({n: ["x"] if n != "measured_us" else [1.0] for n in names})
    table = Table(frame, tuple(COLUMNS[n] for n in names))
    assert for_people(table) == ["row", "method_label", "measured_us"]
    blank = Table(frame.assign(measured_us=math.nan), table.columns)
    assert for_people(blank) == ["row", "method_label"]
    assert COLUMNS["method_label"].header == COLUMNS["method"].header == "Method"
    assert COLUMNS["method"].text("fem_axi") == "FEM, axisymmetric continuum"
    assert COLUMNS["contact_law"].text("hertz_film") == "Hertz with a thin film (approximation)"
    assert COLUMNS["method"].text("my_method") == "my_method"  # an id it does not know: as it is
    panel = panels(table, "t", ["case_id", "row", "method"], ["method_label"])[0]
    assert panel.columns == ("row", "method_label")


def test_the_width_estimate_counts_the_widest_line() -> None:
    table = Table(pd.DataFrame({"measured_us": [36.42, 111.1]}), (COLUMNS["measured_us"],))
    panel = Panel("t", ("measured_us",))
    assert latex_width_pt(table, panel) == pytest.approx(LATEX_CHAR_PT * len("Measured") + 12.0)


@pytest.mark.skipif(
    shutil.which("pdflatex") is None and not os.environ.get("RODIMPACT_REQUIRE_TOOLS"),
    reason="pdflatex is not installed (make latex); CI sets RODIMPACT_REQUIRE_TOOLS and needs it",
)
def test_table2_latex_compiles(table2: dict, tmp_path: Path) -> None:
    document = tmp_path / "t.tex"
    document.write_text(
        "\\documentclass{article}\n\\usepackage{booktabs}\n\\setlength{\\textwidth}{6in}\n"
        "\\begin{document}\n\\input{" + str(table2["paths"]["tex"]) + "}\n\\end{document}\n"
    )
    run = subprocess.run(
        ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", document.name],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert run.returncode == 0, run.stdout[-2000:]
    assert "Overfull \\hbox" not in (tmp_path / "t.log").read_text(errors="replace")


def test_a_table_with_no_rows_says_so(tmp_path: Path) -> None:
    """A configuration with no calibrated reading has no indentation points: the table is
    written, its header alone in the CSV, and says so in Markdown and HTML."""
    from rodimpact.present.film_tables import INDENTATION_COLUMNS, film_indentation_table

    table = film_indentation_table([])
    assert table.panels == ()
    paths = {ext: tmp_path / f"t.{ext}" for ext in ("csv", "md", "html")}
    write_table(table, **paths)
    assert paths["csv"].read_text(encoding="utf-8").strip() == ",".join(INDENTATION_COLUMNS)
    assert paths["md"].read_text(encoding="utf-8").endswith("\n\nThe table has no rows.\n")
    assert "no rows" in paths["html"].read_text(encoding="utf-8")


class _Headers(HTMLParser):
    """The header cells' texts of every HTML table."""

    def __init__(self) -> None:
        super().__init__()
        self.headers: list[str] = []
        self._in = False

    def handle_starttag(self, tag, attrs) -> None:
        self._in = tag == "th"
        if self._in:
            self.headers.append("")

    def handle_endtag(self, tag) -> None:
        self._in = False if tag == "th" else self._in

    def handle_data(self, data) -> None:
        if self._in:
            self.headers[-1] += data


@pytest.mark.workflow
def test_every_table_the_build_writes_is_headed_in_words(dottest: DotTestBuild) -> None:
    """Every table for people the small configuration's build writes (HTML and Markdown): no
    header is a machine name, and every header of the HTML is words (with its unit in parentheses)."""
    tables = sorted((dottest.workdir / "results" / "tables").glob("*.html"))
    assert len(tables) >= 10, tables
    for path in tables:
        parser = _Headers()
        parser.feed(path.read_text(encoding="utf-8"))
        for header in parser.headers:
            assert "_" not in header and not header[:1].islower(), (path.name, header)
        markdown = path.with_suffix(".md")
        if markdown.exists():
            lines = [ln for ln in markdown.read_text(encoding="utf-8").splitlines() if ln.startswith("|")]
            for header in (c.strip() for c in lines[0].strip("|").split("|")) if lines else ():
                assert "_" not in header, (markdown.name, header)
