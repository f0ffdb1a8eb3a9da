"""Whether a figure is fit for a journal, as a test can tell: every axis labelled with its unit
(or named as a relative quantity), nothing drawn outside the canvas, at most one legend per axes
and every legend inside the figure, short legends in readable type, and titles, labels and
legends in words (no internal ids, no version strings, Greek letters set in mathtext)."""

from __future__ import annotations

import re

import matplotlib.figure
import matplotlib.legend

#: A unit in parentheses at the end of an axis label.
UNIT = re.compile(r"\((?:µs|ms|s|kN|N|m|mm|µm|g|kg|kg/s|Pa|GPa|J|%|[^()]*% of[^()]*)\)\s*$")
#: A dimensionless quantity, named as such.
DIMENSIONLESS = re.compile(r"^relative\b")
MATH = re.compile(r"\$[^$]*\$")
#: A version or machine string (code, kernel) in a title.
VERSION = re.compile(r"\d+\.\d+\.\d+|\+g[0-9a-f]{6}|\bLinux\b|\bCPUs?\b")
#: An internal id (words joined by an underscore) outside mathtext.
IDENTIFIER = re.compile(r"\w_\w")
#: A Greek letter or root spelled out instead of set in mathtext.
BARE_GREEK = re.compile(r"\b(alpha|beta|rho|mu|nu|sigma|sqrt)\b")
#: Smallest type in a legend (pt) and most entries in one legend.
MIN_LEGEND_PT, MAX_LEGEND_ENTRIES = 6.5, 16


def _inside(box, canvas) -> bool:
    return box.x0 >= -1 and box.y0 >= -1 and box.x1 <= canvas.x1 + 1 and box.y1 <= canvas.y1 + 1


def assert_words(text: str) -> None:
    """A title, label or legend entry in words: no id, no version string, Greek in mathtext."""
    plain = MATH.sub("", text)
    assert not IDENTIFIER.search(plain), text
    assert not VERSION.search(plain), text
    assert not BARE_GREEK.search(plain), text


def assert_journal_ready(fig: matplotlib.figure.Figure) -> None:
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    canvas = fig.bbox
    tight = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)
    assert _inside(tight, canvas), tight
    texts = [fig._suptitle.get_text()] if fig._suptitle is not None else []
    legends = list(fig.legends)
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        for label in (ax.get_xlabel(), ax.get_ylabel()):
            if label:
                assert UNIT.search(label) or DIMENSIONLESS.search(label), label
                texts.append(label)
        texts.append(ax.get_title())
        own = [child for child in ax.get_children() if isinstance(child, matplotlib.legend.Legend)]
        assert len(own) <= 1
        legends += own
    for legend in legends:
        assert _inside(legend.get_window_extent(renderer), canvas)
        entries = legend.get_texts()
        assert len(entries) <= MAX_LEGEND_ENTRIES, [t.get_text() for t in entries]
        assert all(t.get_fontsize() >= MIN_LEGEND_PT for t in entries)
        texts += [t.get_text() for t in entries]
    for text in texts:
        assert_words(text)
    assert any(ax.get_xlabel() for ax in fig.axes)
