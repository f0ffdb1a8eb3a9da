"""A table: its frame, what each of its columns means to a reader, and its formats.

A table is declared once, as a :class:`Table`: its frame, every column at full precision under
its machine name (the CSV's header), and a :class:`Column` for each, saying what it is in words,
its unit and its format. The code that makes a column declares it (a column made per method
declares that method's words), so a column's meaning is data and nothing reads it back out of a
name. What a reader sees of a wide table is a list of :class:`Panel`: each a title and at most
:data:`MAX_COLUMNS` chosen columns, the columns that name a row repeated in each (:func:`panels`).

Every format is written from the declaration by pandas (:func:`write_table`):

- CSV: :meth:`pandas.DataFrame.to_csv`, every column at full precision (``%.10g``);
- Markdown: :meth:`pandas.DataFrame.to_markdown` (``tabulate``), every column a reader needs
  (each thing once, in words: :func:`for_people`), rounded, headers in words with units;
- HTML, for the report's captions: the panels, :meth:`pandas.io.formats.style.Styler.to_html`
  (a style block scoped to the table's id; nothing fetched), a long table scrolling in its own box;
- LaTeX, for a paper: the panels, :meth:`pandas.io.formats.style.Styler.to_latex` as ``table``
  floats with booktabs rules, each with its ``\\caption`` and ``\\label``, the label over the unit.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.runs import RunRecord
from rodimpact.storage.sidecar import write_provenance

__all__ = [
    "LATEX_CHAR_PT",
    "LATEX_COLUMN_SEP_PT",
    "MAX_COLUMNS",
    "Column",
    "Panel",
    "Table",
    "TableArtifact",
    "for_people",
    "header_lines",
    "html_tables",
    "latex_escape",
    "latex_tables",
    "latex_title",
    "latex_width_pt",
    "markdown_table",
    "panels",
    "write_artifact",
    "write_csv",
    "write_table",
]

#: The most columns a panel shows (a page's width of numbers).
MAX_COLUMNS = 8
#: For :func:`latex_width_pt`: the width of a character (a digit of Computer Modern at 10 pt)
#: and the space between two columns (twice ``\tabcolsep``), pt.
LATEX_CHAR_PT = 5.0
LATEX_COLUMN_SEP_PT = 12.0
#: A header line of a LaTeX panel is at most this many characters before it wraps in two.
_HEADER_LINE = 8
#: A table of more rows than this scrolls in its own box in the report, its header in view.
SCROLL_ROWS = 40


@dataclass(frozen=True)
class Column:
    """One column of a table: its machine name and how a reader sees it.

    Attributes
    ----------
    name : str
        The frame's column, the CSV's header (``measured_us``).
    label : str
        The header in words, without the unit ("Measured", "SEM error").
    unit : str
        The unit as printed ("µs", "%", "g"); empty for a pure number or a text.
    fmt : str
        A format spec for a number (``".2f"``: two decimals); empty for a text, a flag or an
        integer, shown as they are (a flag as yes or no).
    words : mapping, optional
        An id -> its words, for a column of ids (a method, a contact law): a reader sees the
        words; an id not in it is shown as it is.
    in_words : str, optional
        The column that says this one in words (``method`` -> ``method_label``): where both are
        in a table, a reader sees that one, under this one's place.
    said_by : tuple of str
        Columns that already say what this one does (the case id, when the ball and the reading
        have columns): where one of them is shown, this one is left out for a reader.
    """

    name: str
    label: str
    unit: str = ""
    fmt: str = ".2f"
    words: Mapping[str, str] | None = field(default=None, compare=False, hash=False)
    in_words: str | None = None
    said_by: tuple[str, ...] = ()

    @property
    def header(self) -> str:
        """The label and its unit in parentheses: ``Measured (µs)``."""
        return f"{self.label} ({self.unit})" if self.unit else self.label

    def text(self, value: Any) -> str:
        """A cell: the number in this column's format, an en dash for a missing value, yes or no
        for a flag, a text as it is."""
        if value is None or (isinstance(value, (float, np.floating)) and math.isnan(value)):
            return "–"
        if isinstance(value, (bool, np.bool_)):
            return "yes" if value else "no"
        if self.words and isinstance(value, str):
            return self.words.get(value, value)
        if self.fmt and isinstance(value, (int, float, np.integer, np.floating)):
            return format(float(value), self.fmt)
        return str(value)

    def named(self, name: str, label: str | None = None) -> Column:
        """The same column under another machine name (and label)."""
        return replace(self, name=name, label=self.label if label is None else label)


@dataclass(frozen=True)
class Panel:
    """One table as a reader sees it.

    Attributes
    ----------
    title : str
        What the table shows, plain text (the HTML caption; the LaTeX caption when
        ``latex_caption`` is empty).
    columns : tuple of str
        The frame's columns shown, in order (at most :data:`MAX_COLUMNS`).
    label : str
        The LaTeX label (``tab:...``); empty: none (the HTML does not use it).
    latex_caption : str
        The LaTeX caption, LaTeX source; empty: ``title``, escaped.
    drop : str
        Words dropped from the end of every header that has them, when the title says them once
        for all (" error").
    rows : tuple of int, optional
        The frame's rows shown (positions); None: every row.
    """

    title: str
    columns: tuple[str, ...]
    label: str = ""
    latex_caption: str = ""
    drop: str = ""
    rows: tuple[int, ...] | None = None


@dataclass(frozen=True, eq=False)
class Table:
    """A table: its frame, a :class:`Column` for each of its columns, and what a reader sees.

    Attributes
    ----------
    frame : DataFrame
        Every column at full precision, under its machine name.
    columns : tuple of Column
        One for each column of ``frame`` (any order; extra ones, for columns the frame does not
        have this time, are allowed).
    caption : str
        What the table is, in words (the Markdown's first paragraph).
    panels : tuple of Panel
        What the HTML and the LaTeX show (:func:`panels`).

    Raises
    ------
    ValueError
        A column of ``frame`` is not declared, or one is declared twice.
    """

    frame: pd.DataFrame
    columns: tuple[Column, ...]
    caption: str = ""
    panels: tuple[Panel, ...] = ()

    def __post_init__(self) -> None:
        names = [c.name for c in self.columns]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise ValueError(f"columns: declared twice: {', '.join(twice)}")
        undeclared = [str(c) for c in self.frame.columns if c not in names]
        if undeclared:
            raise ValueError(f"columns: the frame's {', '.join(undeclared)} not declared")
        object.__setattr__(self, "columns", tuple(self.columns))
        object.__setattr__(self, "panels", tuple(self.panels))

    def column(self, name: str) -> Column:
        """The declaration of the column ``name``."""
        for spec in self.columns:
            if spec.name == name:
                return spec
        raise KeyError(f"no column {name!r} declared; declared: {', '.join(c.name for c in self.columns)}")

    def header(self, name: str, panel: Panel | None = None) -> Column:
        """The column ``name`` as ``panel`` heads it (without the words its title says for all)."""
        spec = self.column(name)
        if panel is not None and panel.drop and spec.label.endswith(panel.drop) and spec.label != panel.drop:
            spec = replace(spec, label=spec.label[: -len(panel.drop)])
        return spec

    def cells(self, panel: Panel) -> pd.DataFrame:
        """The part of the frame ``panel`` shows: its rows, its columns."""
        shown = self.frame if panel.rows is None else self.frame.iloc[list(panel.rows)]
        return shown[list(panel.columns)]

    def numeric(self, name: str) -> bool:
        """Whether the column ``name`` holds numbers shown in a format (right-aligned)."""
        series = self.frame[name]
        return (
            bool(self.column(name).fmt)
            and pd.api.types.is_numeric_dtype(series)
            and not pd.api.types.is_bool_dtype(series)
        )

    def showing(self, shown: Iterable[Panel]) -> Table:
        """The same table with the panels ``shown``."""
        return replace(self, panels=tuple(shown))


def _in_words(table: Table, names: Sequence[str]) -> list[str]:
    """``names`` with each id whose words have a column in the frame replaced by it, once."""
    out: list[str] = []
    for name in names:
        words = table.column(name).in_words if any(c.name == name for c in table.columns) else None
        name = words if words and words in table.frame.columns else name
        if name not in out:
            out.append(name)
    return out


def _said(table: Table, name: str, shown: set[str]) -> bool:
    return any(other in shown for other in table.column(name).said_by)


def panels(
    table: Table,
    title: str,
    key: Sequence[str],
    values: Sequence[str],
    *,
    label: str = "",
    latex_caption: str = "",
    drop: str = "",
    by: str = "",
    max_columns: int = MAX_COLUMNS,
) -> list[Panel]:
    """The columns ``key`` + ``values`` of ``table`` as panels of at most ``max_columns``.

    Columns the frame lacks are skipped (a table's methods vary); an id whose words the frame
    has is shown in words, and a column another shown column already says is left out
    (:class:`Column`). When the values do not fit in one panel they are split evenly, the key
    columns repeated in each, the titles numbered ("..., part 1 of 2") and the labels suffixed
    (``-1``, ``-2``). With ``by`` (a column), the rows of each of its values (in the order first
    met) make their own panels, titled with it, and the column itself is not shown.

    Raises
    ------
    ValueError
        The key columns alone leave no room for a value.
    """
    frame = table.frame
    if by:
        # an empty table (no rows, so no columns: no calibrated reading, say) has no panels
        groups = list(dict.fromkeys(frame[by])) if by in frame.columns else []
        out = []
        for value in groups:
            rows = tuple(int(i) for i in (frame[by] == value).to_numpy().nonzero()[0])
            for panel in panels(
                table,
                f"{title}: {table.column(by).label.lower()} {value}",
                [c for c in key if c != by],
                [c for c in values if c != by],
                label=label,
                latex_caption=latex_caption,
                drop=drop,
                max_columns=max_columns,
            ):
                out.append(replace(panel, rows=rows))
        return out
    key = [c for c in _in_words(table, key) if c in frame.columns]
    values = [c for c in _in_words(table, values) if c in frame.columns and c not in key]
    shown = {*key, *values}
    key = [c for c in key if not _said(table, c, shown)]
    values = [c for c in values if not _said(table, c, shown)]
    room = max_columns - len(key)
    if room < 1:
        raise ValueError(f"{title!r}: {len(key)} key columns leave no room in {max_columns}")
    n = max(1, -(-len(values) // room))
    size = -(-len(values) // n) if values else 0
    chunks = [values[i * size : (i + 1) * size] for i in range(n)]
    if n == 1:
        return [Panel(title, (*key, *values), label, latex_caption, drop)]
    return [
        Panel(
            f"{title}, part {i} of {n}",
            (*key, *chunk),
            f"{label}-{i}" if label else "",
            f"{latex_caption} (part {i} of {n})" if latex_caption else "",
            drop,
        )
        for i, chunk in enumerate(chunks, start=1)
    ]


def for_people(table: Table) -> list[str]:
    """The columns a reader needs, in the frame's order: each thing once, in words. An id whose
    words have a column gives way to it, a column another column already says is left out, and
    so is a column with no value in any row."""
    frame = table.frame
    present = set(frame.columns)
    out = []
    for name in frame.columns:
        spec = table.column(name)
        if spec.in_words in present or any(o in present for o in spec.said_by):
            continue
        if len(frame) and frame[name].isna().all():
            continue
        out.append(name)
    return out


def _texts(table: Table, names: Sequence[str], frame: pd.DataFrame, panel: Panel | None = None) -> pd.DataFrame:
    """The cells of ``frame``'s columns ``names`` as their texts (:meth:`Column.text`)."""
    specs = [table.header(name, panel) for name in names]
    return pd.DataFrame(
        {i: [spec.text(v) for v in frame[name]] for i, (spec, name) in enumerate(zip(specs, names, strict=True))},
        index=range(len(frame)),
    )


def markdown_table(table: Table) -> str:
    """Every column a reader needs (:func:`for_people`), rounded, headers in words with units."""
    if table.frame.empty:
        return "The table has no rows."
    names = for_people(table)
    cells = _texts(table, names, table.frame)
    cells.columns = [table.column(name).header for name in names]
    align = ["right" if table.numeric(name) else "left" for name in names]
    return cells.to_markdown(index=False, disable_numparse=True, colalign=align)


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()[:40] or "table"


def html_tables(table: Table, name: str = "table") -> str:
    """The panels as HTML tables, for a report caption (:class:`pandas.io.formats.style.Styler`):
    each titled by its ``<caption>``, headers in words with their units, numbers right-aligned in
    their column's format; a table of more than :data:`SCROLL_ROWS` rows scrolls inside its own
    box, its header in view. ``name`` makes the tables' ids unique in a page."""
    if not table.panels:
        return "<p>The table has no rows.</p>\n"
    out = []
    for index, panel in enumerate(table.panels, start=1):
        specs = [table.header(c, panel) for c in panel.columns]
        cells = _texts(table, panel.columns, table.cells(panel), panel)
        cells.columns = [s.header for s in specs]
        right = [i for i, c in enumerate(panel.columns) if table.numeric(c)]
        styles = [
            {"selector": "", "props": "width:auto;margin:0;font-size:0.7rem;line-height:1.3;border-collapse:collapse;"},
            {
                "selector": "caption",
                "props": "caption-side:top;text-align:left;font-weight:600;padding-bottom:0.3rem;",
            },
            {
                "selector": "th",
                "props": "padding:0.12rem 0.25rem;vertical-align:bottom;text-align:left;position:sticky;top:0;"
                "background:#1e293b;border-bottom:1px solid #94a3b8;",
            },
            {"selector": "td", "props": "padding:0.12rem 0.25rem;white-space:nowrap;text-align:left;"},
            *({"selector": f"td.col{i}, th.col{i}", "props": "text-align:right;"} for i in right),
        ]
        styler = (
            cells.style.hide(axis="index")
            .set_caption(panel.title)
            .set_table_styles(styles)
            .set_uuid(f"{_slug(name)}-{index}")
        )
        box = "overflow:auto;max-height:36rem;" if len(cells) > SCROLL_ROWS else "overflow-x:auto;"
        body = styler.to_html(sparse_columns=False, cell_ids=False)
        out.append(f'<div style="{box}margin:0.5rem 0 1rem">\n{body}</div>')
    return "\n".join(out) + "\n"


#: Units as printed -> LaTeX (plain, no siunitx).
LATEX_UNITS = {"µs": r"$\mu$s", "µm": r"$\mu$m", "%": r"\%", "kg/s": "kg/s", "m/s": "m/s"}

_LATEX_SPECIAL = {
    "\\": r"\textbackslash{}",
    "&": r"\&",
    "%": r"\%",
    "$": r"\$",
    "#": r"\#",
    "_": r"\_",
    "{": r"\{",
    "}": r"\}",
    "~": r"\textasciitilde{}",
    "^": r"\textasciicircum{}",
    "–": "--",
    "µ": r"$\mu$",
    "−": "$-$",
    "²": r"$^2$",
    "³": r"$^3$",
    "·": r"$\cdot$",
    "×": r"$\times$",
}


def latex_escape(text: str) -> str:
    """Plain text as LaTeX source (the special characters, the en dash and µ)."""
    return "".join(_LATEX_SPECIAL.get(ch, ch) for ch in text)


def latex_title(title: str) -> str:
    """A title in LaTeX: escaped, with a tie before a number (``Table 2`` -> ``Table~2``)."""
    return re.sub(r" (?=\d)", "~", latex_escape(title))


def header_lines(label: str) -> tuple[str, str]:
    """A header label in one line, or two (split at the space that balances them) when longer
    than a column of numbers."""
    words = label.split(" ")
    if len(label) <= _HEADER_LINE or len(words) == 1:
        return label, ""
    splits = [(" ".join(words[:i]), " ".join(words[i:])) for i in range(1, len(words))]
    return min(splits, key=lambda pair: max(map(len, pair)))


def _latex_unit(unit: str) -> str:
    return f"({LATEX_UNITS.get(unit, latex_escape(unit))})" if unit else ""


def latex_width_pt(table: Table, panel: Panel) -> float:
    """An estimate of the panel's width as a LaTeX tabular at 10 pt, pt: per column its widest
    header line, unit or cell (:data:`LATEX_CHAR_PT` a character), plus the space between."""
    width = 0.0
    cells = table.cells(panel)
    for name in panel.columns:
        spec = table.header(name, panel)
        texts = [
            *header_lines(spec.label),
            f"({spec.unit})" if spec.unit else "",
            *(spec.text(v) for v in cells[name]),
        ]
        width += LATEX_CHAR_PT * max(map(len, texts)) + LATEX_COLUMN_SEP_PT
    return width


def latex_tables(table: Table) -> str:
    """The panels as LaTeX ``table`` floats (:meth:`pandas.io.formats.style.Styler.to_latex`):
    booktabs rules, the header's label (in one or two lines) over its unit, each with
    ``\\caption`` and ``\\label``. Needs ``\\usepackage{booktabs}``."""
    out = ["% Written by rodimpact (rodimpact.present.table); needs \\usepackage{booktabs}.", ""]
    for panel in table.panels:
        specs = [table.header(name, panel) for name in panel.columns]
        lines = [header_lines(s.label) for s in specs]
        levels = [[latex_escape(line[0]) for line in lines]]
        if any(line[1] for line in lines):
            levels.append([latex_escape(line[1]) for line in lines])
        if any(s.unit for s in specs):
            levels.append([_latex_unit(s.unit) for s in specs])
        cells = _texts(table, panel.columns, table.cells(panel), panel).map(latex_escape)
        cells.columns = pd.MultiIndex.from_arrays(levels) if len(levels) > 1 else levels[0]
        latex = cells.style.hide(axis="index").to_latex(
            hrules=True,
            caption=panel.latex_caption or latex_escape(panel.title),
            label=panel.label or None,
            position="tbp",
            position_float="centering",
            column_format="".join("r" if table.numeric(name) else "l" for name in panel.columns),
            sparse_columns=False,
        )
        out.append(latex)
    return "\n".join(out)


@dataclass(frozen=True, eq=False)
class TableArtifact:
    """A table as its job writes it (:func:`write_artifact`): the table, the runs it was made from,
    and its other input files by kind (band files, case files, curves, measured records), for its
    provenance sidecar."""

    table: Table
    records: Sequence[RunRecord] = ()
    files: Mapping[str, Sequence[str | Path]] | None = None


def write_artifact(
    artifact: TableArtifact,
    *,
    csv: str | Path,
    provenance: str | Path,
    md: str | Path | None = None,
    html: str | Path | None = None,
    tex: str | Path | None = None,
) -> None:
    """Write a table's files (:func:`write_table`) and its provenance sidecar, which names every
    run and file it was made from."""
    write_table(artifact.table, csv=csv, md=md, html=html, tex=tex)
    write_provenance(provenance, artifact.records, [csv, md, html, tex], artifact.files)


def write_csv(frame: pd.DataFrame, path: str | Path) -> None:
    """A frame that is data rather than a table for people (every level of a study, say): its
    CSV alone, every column at full precision (``%.10g``), written whole or not at all."""
    with atomic_output(path) as tmp:
        frame.to_csv(tmp, index=False, float_format="%.10g")


def write_table(
    table: Table,
    *,
    csv: str | Path,
    md: str | Path | None = None,
    html: str | Path | None = None,
    tex: str | Path | None = None,
) -> None:
    """Write a table, each file whole or not at all: the CSV with every column at full precision
    (machine names), and for people, each optional: Markdown (:func:`markdown_table`, after the
    caption), the panels as HTML tables for the report (:func:`html_tables`) and as LaTeX tables
    (:func:`latex_tables`). A table with no rows (no panels) says so in each format."""
    write_csv(table.frame, csv)
    if md is not None:
        _write_text(md, (f"{table.caption}\n\n" if table.caption else "") + markdown_table(table) + "\n")
    if html is not None:
        _write_text(html, html_tables(table, Path(html).stem))
    if tex is not None:
        _write_text(tex, latex_tables(table))


def _write_text(path: str | Path, text: str) -> None:
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
