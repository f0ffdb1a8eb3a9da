"""A case set's comparison with its measurements, written: its table, its figure, and one
figure per measured force history (:mod:`.compare`, :mod:`.compare_figures`), from the set's
stored runs and measured files only."""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rodimpact.analysis.history_compare import DEFAULT_THRESHOLD
from rodimpact.analysis.measured import read_force_history
from rodimpact.present.compare import compare_frame, compare_summary, history_comparison, x_axis
from rodimpact.present.film_tables import write_provenance_with_files
from rodimpact.present.table_formats import markdown_table, panels
from rodimpact.present.tables import write_table
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.runs import read_run

__all__ = ["make_compare_figure", "make_compare_table", "make_history_figure"]

log = logging.getLogger(__name__)

_CAPTION = (
    "Measured against computed, per case, method and quantity: the measured value and its source, the "
    "computed value, and the error (computed − measured) / |measured| in %. A measured force history adds "
    "the contact time read from both signals at the history's threshold, and the L2 and max-norm errors "
    "of the computed force after the two are aligned where each first rises through that fraction of its "
    'peak (config/README.md, "Comparing with your experiment").'
)


def _histories(records) -> dict[str, tuple[Any, float]]:
    """Case id -> (its measured history, its threshold), for the cases that give one."""
    out = {}
    for record in records:
        spec = (record.config.get("measured") or {}).get("force_history")
        if spec and record.case_id not in out:
            out[record.case_id] = (
                read_force_history(spec["path"], spec),
                float(spec.get("threshold", DEFAULT_THRESHOLD)),
            )
    return out


def _history_files(records) -> list[str]:
    return sorted({spec["path"] for r in records if (spec := (r.config.get("measured") or {}).get("force_history"))})


def make_compare_table(
    runs: Sequence[str | Path],
    set_name: str,
    *,
    csv: str | Path,
    summary: str | Path,
    md: str | Path,
    html: str | Path,
    tex: str | Path,
    provenance: str | Path,
) -> None:
    """The set's comparison table (:func:`~rodimpact.present.compare.compare_frame`) and its
    summary per method and quantity (:func:`~rodimpact.present.compare.compare_summary`)."""
    records = [read_run(p) for p in runs]
    frame = compare_frame(records, _histories(records))
    totals = compare_summary(frame)
    views = panels(
        frame,
        f"Set {set_name} against its measurements",
        ["row", "quantity_words", "unit"],
        # a warning column only where a measurement is flagged (compare.rigid_wall_warnings)
        ["method_label", "measured", "computed", "error_pct", *(["warning"] if frame["warning"].notna().any() else [])],
        by="variant" if frame["variant"].notna().any() else "",
    )
    write_table(frame, csv=csv, html=html, tex=tex, views=views)
    with atomic_output(summary) as tmp:
        totals.to_csv(tmp, index=False, float_format="%.10g")
    with atomic_output(md) as tmp:
        tmp.write_text(
            f"{_CAPTION}\n\n{markdown_table(frame)}\n\nPer method and quantity: the cases compared, the "
            f"mean and the largest |error|, and the mean signed error (%).\n\n"
            f"{markdown_table(totals)}\n",
            encoding="utf-8",
        )
    write_provenance_with_files(
        provenance, records, [csv, summary, md, html, tex], {"measured force history": _history_files(records)}
    )
    log.info("set %s: %d comparisons of %d runs", set_name, len(frame), len(records))


def make_compare_figure(
    runs: Sequence[str | Path],
    set_name: str,
    title: str,
    *,
    pdf: str | Path,
    png: str | Path,
    provenance: str | Path,
    descriptions: Mapping[str, str] | None = None,
    x: str | None = None,
) -> None:
    """The set's figure (:func:`~rodimpact.present.compare_figures.plot_compare_set`), against
    ``x`` (the set's ``compare.x``) or what varies along the set
    (:func:`~rodimpact.present.compare.x_axis`)."""
    from rodimpact.present.compare_figures import plot_compare_set
    from rodimpact.present.figures import save_figure
    from rodimpact.storage.sidecar import provenance_record

    records = [read_run(p) for p in runs]
    frame = compare_frame(records, _histories(records))
    column, x_label = x_axis(frame, x)
    save_figure(
        plot_compare_set(frame, title, x=column, x_label=x_label, descriptions=descriptions),
        pdf=pdf,
        png=png,
        provenance=provenance_record(records, [pdf, png]),
        title=f"Set {set_name} against its measurements",
    )
    write_provenance_with_files(provenance, records, [pdf, png], {"measured force history": _history_files(records)})


def make_history_figure(
    runs: Sequence[str | Path], *, pdf: str | Path, png: str | Path, provenance: str | Path
) -> None:
    """One case's measured force history against each method's (every run of ``runs`` is of
    that case; :func:`~rodimpact.present.compare_figures.plot_history_overlay`).

    Raises
    ------
    ValueError
        The runs are of several cases, or their case has no measured history.
    """
    from rodimpact.present.compare_figures import plot_history_overlay
    from rodimpact.present.figures import save_figure
    from rodimpact.storage.sidecar import provenance_record

    records = [read_run(p) for p in runs]
    cases = {r.case_id for r in records}
    histories = _histories(records)
    if len(cases) != 1 or not histories:
        raise ValueError(f"runs: one case with a measured force history expected, got {sorted(cases)}")
    ((case_id, (history, threshold)),) = histories.items()
    comparisons = [(r.method, history_comparison(r, history, threshold)) for r in records]
    description = str(records[0].config.get("description") or case_id)
    save_figure(
        plot_history_overlay(comparisons, description, history.note),
        pdf=pdf,
        png=png,
        provenance=provenance_record(records, [pdf, png]),
        title=f"{case_id}: measured and computed force",
    )
    write_provenance_with_files(provenance, records, [pdf, png], {"measured force history": _history_files(records)})
