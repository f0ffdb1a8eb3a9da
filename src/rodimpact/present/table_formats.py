"""A table's frame written for people: HTML for the report, LaTeX for a paper, Markdown.

A frame keeps every column at full precision under its machine name (the CSV). What a reader
sees is a list of :class:`Panel`: each a title and at most :data:`MAX_COLUMNS` chosen columns,
the columns that identify a row repeated in each (:func:`panels`). Headers, units and rounding
come from :mod:`rodimpact.present.columns`.

- :func:`html_tables`: the panels as HTML ``<table>`` elements, for a report caption (no
  script, no style sheet, nothing fetched: inline styles only);
- :func:`latex_tables`: the panels as LaTeX ``table`` floats with booktabs rules, each with its
  ``\\caption`` and ``\\label``, units in a header row (``$\\mu$s``), no package but booktabs;
- :func:`markdown_table`: every column, rounded, headers in words with units;
- :func:`latex_width_pt`: an estimate of a LaTeX panel's width, to keep it within a page.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass, replace

import pandas as pd

from rodimpact.present.columns import LATEX_UNITS, SAID_BY, WORDS_FOR, Column, column, words_only

__all__ = [
    "LATEX_CHAR_PT",
    "LATEX_COLUMN_SEP_PT",
    "MAX_COLUMNS",
    "Panel",
    "header_lines",
    "html_tables",
    "latex_escape",
    "latex_tables",
    "latex_width_pt",
    "markdown_table",
    "panels",
]

#: The most columns a panel shows (a page's width of numbers).
MAX_COLUMNS = 8

#: For :func:`latex_width_pt`: the width of a character (a digit of Computer Modern at 10 pt)
#: and the space between two columns (twice ``\tabcolsep``), pt.
LATEX_CHAR_PT = 5.0
LATEX_COLUMN_SEP_PT = 12.0

#: A header line of a LaTeX panel is at most this many characters before it wraps in two.
_HEADER_LINE = 8


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
        Words dropped from the end of the header of every ``*_error_pct`` column, when the title
        says them once for all (" error").
    rows : tuple of int, optional
        The frame's rows shown (positions); None: every row.
    """

    title: str
    columns: tuple[str, ...]
    label: str = ""
    latex_caption: str = ""
    drop: str = ""
    rows: tuple[int, ...] | None = None

    def cells(self, frame: pd.DataFrame) -> pd.DataFrame:
        """The part of ``frame`` this panel shows: its rows, its columns."""
        shown = frame if self.rows is None else frame.iloc[list(self.rows)]
        return shown[list(self.columns)]

    def header(self, name: str) -> Column:
        """The column ``name`` as this panel heads it."""
        spec = column(name)
        if self.drop and name.endswith("_error_pct") and spec.label.endswith(self.drop):
            spec = replace(spec, label=spec.label[: -len(self.drop)])
        return spec


def panels(
    frame: pd.DataFrame,
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
    """The columns ``key`` + ``values`` of ``frame`` as panels of at most ``max_columns``.

    Columns the frame lacks are skipped (a table's methods vary). When the values do not fit in
    one panel they are split evenly, the key columns repeated in each, the titles numbered
    ("..., part 1 of 2") and the labels suffixed (``-1``, ``-2``). With ``by`` (a column), the
    rows of each of its values (in the order first met) make their own panels, titled with it,
    and the column itself is not shown.

    Raises
    ------
    ValueError
        The key columns alone leave no room for a value.
    """
    if by:
        # an empty table (no rows, so no columns: no calibrated reading, say) has no panels
        groups = list(dict.fromkeys(frame[by])) if by in frame.columns else []
        out = []
        for value in groups:
            rows = tuple(int(i) for i in (frame[by] == value).to_numpy().nonzero()[0])
            for panel in panels(
                frame,
                f"{title}: {column(by).label.lower()} {value}",
                [c for c in key if c != by],
                [c for c in values if c != by],
                label=label,
                latex_caption=latex_caption,
                drop=drop,
                max_columns=max_columns,
            ):
                out.append(Panel(panel.title, panel.columns, panel.label, panel.latex_caption, panel.drop, rows))
        return out
    key, values = _in_words(key, frame), _in_words(values, frame)
    key = [c for c in key if c in frame.columns]
    values = [c for c in values if c in frame.columns and c not in key]
    shown = {*key, *values}
    key = [c for c in key if not any(o in shown for o in SAID_BY.get(c, ()))]
    values = [c for c in values if not any(o in shown for o in SAID_BY.get(c, ()))]
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


def _in_words(names: Sequence[str], frame: pd.DataFrame) -> list[str]:
    """``names`` with each id that has a column of its words in ``frame`` replaced by it, once."""
    out: list[str] = []
    for name in names:
        words = WORDS_FOR.get(name)
        name = words if words and words in frame.columns else name
        if name not in out:
            out.append(name)
    return out


def _numeric(frame: pd.DataFrame, name: str) -> bool:
    return (
        bool(column(name).fmt)
        and pd.api.types.is_numeric_dtype(frame[name])
        and not pd.api.types.is_bool_dtype(frame[name])
    )


def html_tables(
    frame: pd.DataFrame, shown: Sequence[Panel], *, scroll_rows: int = 40, max_height_rem: float = 36.0
) -> str:
    """The panels as HTML tables (each with its title as ``<caption>``), for a report caption.

    Numbers are right-aligned in their column's format. A table of more than ``scroll_rows``
    rows scrolls inside a box ``max_height_rem`` high, its header (label, then unit) in view.
    """
    cell = "padding:0.12rem 0.25rem;white-space:nowrap;"
    head = (
        "padding:0.12rem 0.25rem;vertical-align:bottom;position:sticky;top:0;background:#1e293b;"
        "border-bottom:1px solid #94a3b8;"
    )
    if not shown:
        return "<p>The table has no rows.</p>\n"
    out = []
    for panel in shown:
        specs = [panel.header(name) for name in panel.columns]
        align = ["right" if _numeric(frame, name) else "left" for name in panel.columns]
        long = len(panel.cells(frame)) > scroll_rows
        box = f"overflow:auto;max-height:{max_height_rem:g}rem;" if long else "overflow-x:auto;"
        rows = [
            "<tr>"
            + "".join(
                f'<th scope="col" style="{head}text-align:{a}">{html.escape(s.label)}'
                + (f'<br><span style="font-weight:normal">({html.escape(s.unit)})</span>' if s.unit else "")
                + "</th>"
                for s, a in zip(specs, align)
            )
            + "</tr>"
        ]
        body = []
        for values in panel.cells(frame).itertuples(index=False):
            body.append(
                "<tr>"
                + "".join(
                    f'<td style="{cell}text-align:{a}">{html.escape(s.text(v))}</td>'
                    for s, a, v in zip(specs, align, values)
                )
                + "</tr>"
            )
        out.append(
            f'<div style="{box}margin:0.5rem 0 1rem">\n'
            '<table style="width:auto;margin:0;font-size:0.7rem;line-height:1.3;border-collapse:collapse">\n'
            f'<caption style="caption-side:top;text-align:left;font-weight:600;padding-bottom:0.3rem">'
            f"{html.escape(panel.title)}</caption>\n"
            f"<thead>{rows[0]}</thead>\n<tbody>\n" + "\n".join(body) + "\n</tbody>\n</table>\n</div>"
        )
    return "\n".join(out) + "\n"


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


def latex_width_pt(frame: pd.DataFrame, panel: Panel) -> float:
    """An estimate of the panel's width as a LaTeX tabular at 10 pt, pt: per column its widest
    header line, unit or cell (:data:`LATEX_CHAR_PT` a character), plus the space between."""
    width = 0.0
    for name in panel.columns:
        spec = panel.header(name)
        texts = [
            *header_lines(spec.label),
            f"({spec.unit})" if spec.unit else "",
            *(spec.text(v) for v in panel.cells(frame)[name]),
        ]
        width += LATEX_CHAR_PT * max(map(len, texts)) + LATEX_COLUMN_SEP_PT
    return width


def latex_tables(frame: pd.DataFrame, shown: Sequence[Panel]) -> str:
    """The panels as LaTeX ``table`` floats: booktabs rules, the header's label (in one or two
    lines) over its unit, each with ``\\caption`` and ``\\label``. Needs ``\\usepackage{booktabs}``."""
    out = ["% Written by rodimpact (rodimpact.present.table_formats); needs \\usepackage{booktabs}."]
    for panel in shown:
        specs = [panel.header(name) for name in panel.columns]
        align = "".join("r" if _numeric(frame, name) else "l" for name in panel.columns)
        lines = [header_lines(s.label) for s in specs]
        header = [" & ".join(latex_escape(line[0]) for line in lines) + r" \\"]
        if any(line[1] for line in lines):
            header.append(" & ".join(latex_escape(line[1]) for line in lines) + r" \\")
        if any(s.unit for s in specs):
            header.append(" & ".join(_latex_unit(s.unit) for s in specs) + r" \\")
        body = [
            " & ".join(latex_escape(s.text(v)) for s, v in zip(specs, values)) + r" \\"
            for values in panel.cells(frame).itertuples(index=False)
        ]
        caption = panel.latex_caption or latex_escape(panel.title)
        out += [r"\begin{table}[tbp]", r"\centering", rf"\caption{{{caption}}}"]
        if panel.label:
            out.append(rf"\label{{{panel.label}}}")
        out += [
            rf"\begin{{tabular}}{{{align}}}",
            r"\toprule",
            *header,
            r"\midrule",
            *body,
            r"\bottomrule",
            r"\end{tabular}",
            r"\end{table}",
            "",
        ]
    return "\n".join(out)


def markdown_table(frame: pd.DataFrame) -> str:
    """The frame's columns for people (:func:`~rodimpact.present.columns.words_only`: each thing
    once, in words, no column without a value), headers in words with units, each column in its
    format."""
    if frame.columns.empty:
        return "The table has no rows."
    empty = [name for name in frame.columns if len(frame) and frame[name].isna().all()]
    frame = frame[words_only(frame.columns, empty)]
    specs = [column(name) for name in frame.columns]
    rows = [[spec.text(v) for spec, v in zip(specs, values)] for values in frame.itertuples(index=False)]
    cells = pd.DataFrame(rows, columns=[spec.header for spec in specs])
    align = ["right" if _numeric(frame, name) else "left" for name in frame.columns]
    return cells.to_markdown(index=False, disable_numparse=True, colalign=align)
