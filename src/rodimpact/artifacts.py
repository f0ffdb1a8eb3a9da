"""One function per artifact of the workflow: read HDF5 runs, write tables and figures.

The workflow's scripts call these and nothing else; tests call them directly.
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Sequence

from .figures import plot_contact_force, plot_station_displacement, plot_table2_contact_time, save_figure
from .store import read_run
from .tables import (
    comparison_frame,
    convergence_frame,
    load_records,
    provenance_record,
    table2_frame,
    variants_summary,
    write_provenance,
    write_table,
)

__all__ = ["make_comparison", "make_convergence", "make_fig2", "make_fig4", "make_fig_table2", "make_table2",
           "make_table2_variants"]

log = logging.getLogger(__name__)

TABLE2_CAPTION = ("Table 2: contact time of steel balls on the aluminium rod at 0.3225 m/s, "
                  "rod geometry variant {variant}. Times in us; errors |model - measured| / measured in %.")


def _by_variant(runs: Sequence[str | Path], variants: Sequence[str]):
    records = load_records(runs)
    grouped = {v: [r for r in records if r.config.get("variant") == v] for v in variants}
    return records, {v: table2_frame(recs) for v, recs in grouped.items() if recs}


def make_table2(runs: Sequence[str | Path], variant: str, *, csv: str | Path, md: str | Path,
                tex: str | Path, provenance: str | Path) -> None:
    """Table 2 for one geometry variant, with its provenance sidecar."""
    records = load_records(runs)
    wrong = sorted({r.case_id for r in records if r.config.get("variant") != variant})
    if wrong:
        raise ValueError(f"runs: cases {wrong} do not belong to variant {variant!r}")
    frame = table2_frame(records)
    write_table(frame, csv=csv, md=md, tex=tex, caption=TABLE2_CAPTION.format(variant=variant))
    write_provenance(provenance, records, [csv, md, tex])
    log.info("table 2 (%s): %d rows from %d runs", variant, len(frame), len(records))


def make_table2_variants(runs: Sequence[str | Path], variants: Sequence[str], *, csv: str | Path,
                         md: str | Path, provenance: str | Path) -> None:
    """Per variant and method, the mean and max error against the measurements."""
    records, frames = _by_variant(runs, variants)
    summary = variants_summary(frames)
    write_table(summary, csv=csv, md=md, caption="Error against the measured contact times, per rod "
                "geometry variant and method, next to the paper's own errors (%).")
    write_provenance(provenance, records, [csv, md])


def _one_case(records: Sequence, what: str) -> str:
    """The single case id of ``records`` (a figure of one case)."""
    cases = sorted({r.case_id for r in records})
    if len(cases) != 1:
        raise ValueError(f"runs: {what} shows one case, got {cases}")
    return cases[0]


def _table_artifact(runs: Sequence[str | Path], build, *, csv: str | Path, md: str | Path,
                    provenance: str | Path, caption: str, digits: int) -> None:
    """Read the runs, build a frame from them, write it as CSV and Markdown with provenance."""
    records = load_records(runs)
    write_table(build(records), csv=csv, md=md, digits=digits, caption=caption)
    write_provenance(provenance, records, [csv, md])


def make_fig2(runs: Sequence[str | Path], *, pdf: str | Path, png: str | Path) -> None:
    """Fig. 2: contact force against time for one case, every method stored."""
    records = [read_run(p) for p in runs]
    case = _one_case(records, "Fig. 2")
    fig = plot_contact_force(records, title=f"Contact force, case {case!r} (Fig. 2 of the paper)")
    save_figure(fig, pdf=pdf, png=png, provenance=provenance_record(records, [pdf, png]),
                title="Fig. 2: contact force against time")


def make_fig4(runs: Sequence[str | Path], fraction: float, *, pdf: str | Path, png: str | Path) -> None:
    """Fig. 4: displacement of the cross-section at ``fraction`` of the rod length, every
    stored run of one case that recorded stations."""
    records = [read_run(p) for p in runs]
    records = [r for r in records if "station_displacement" in r.series]
    case = _one_case(records, "Fig. 4 (runs with station histories)")
    fig = plot_station_displacement(records, fraction, title=(
        f"Displacement at {fraction:g} of the rod length, case {case!r} (Fig. 4 of the paper)"))
    save_figure(fig, pdf=pdf, png=png, provenance=provenance_record(records, [pdf, png]),
                title="Fig. 4: displacement of a cross-section of the rod against time")


def make_fig_table2(runs: Sequence[str | Path], variants: Sequence[str], *, pdf: str | Path,
                    png: str | Path) -> None:
    """Contact time against ball mass per geometry variant."""
    records, frames = _by_variant(runs, variants)
    fig = plot_table2_contact_time(frames)
    save_figure(fig, pdf=pdf, png=png, provenance=provenance_record(records, [pdf, png]),
                title="Table 2: contact time against ball mass")


def make_comparison(runs: Sequence[str | Path], *, csv: str | Path, md: str | Path,
                    provenance: str | Path) -> None:
    """Fig. 2's numbers: contact time and each maximum per method, differences from the SEM,
    and the paper's 11 % and 9 % beside them."""
    _table_artifact(runs, comparison_frame, csv=csv, md=md, provenance=provenance, digits=3, caption=(
        "Fig. 2, case 'model': contact time (us) and force maxima (kN) of the first contact per "
        "method; differences from our SEM (%), next to the paper's FEM-SEM differences (%)."))


def make_convergence(runs: Sequence[str | Path], *, csv: str | Path, md: str | Path,
                     provenance: str | Path) -> None:
    """A convergence study over numerics levels."""
    _table_artifact(runs, convergence_frame, csv=csv, md=md, provenance=provenance, digits=4, caption=(
        "Convergence study: contact time and first force maximum per level, and their change "
        "from the finest level (%)."))
