"""What the artifact writers share: a set's runs read and grouped by variant, the one case a
figure shows, the files an artifact wrote (for its provenance), a figure saved with its sidecar,
and a case in words for a title.

The writers are in :mod:`.table_artifacts`, :mod:`.figure_artifacts`, :mod:`.study_artifacts`
and :mod:`.sensor_artifacts`; the names with a leading underscore are theirs alone.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rodimpact.present.tables import load_records, table2_frame
from rodimpact.storage.casefile import read_case_file
from rodimpact.storage.sidecar import provenance_record, write_provenance

__all__ = ["case_in_words"]


def _cases_in(case_files: Sequence[str | Path]) -> dict[str, Any]:
    """Case id -> resolved case, of every case of the case files."""
    return {record["case_id"]: record["case"] for path in case_files for record in read_case_file(path)["cases"]}


def _by_variant(runs: Sequence[str | Path], variants: Sequence[str]):
    records = load_records(runs)
    grouped = {v: [r for r in records if r.config.get("variant") == v] for v in variants}
    return records, {v: table2_frame(recs) for v, recs in grouped.items() if recs}


def _outputs(*paths: str | Path | None) -> list[str | Path]:
    return [p for p in paths if p is not None]


def _one_case(records: Sequence, what: str) -> str:
    """The single case id of ``records`` (a figure of one case)."""
    cases = sorted({r.case_id for r in records})
    if len(cases) != 1:
        raise ValueError(f"runs: {what} shows one case, got {cases}")
    return cases[0]


def _save_figure(
    fig, records: Sequence, *, pdf: str | Path, png: str | Path, provenance: str | Path, title: str
) -> None:
    """Save a figure (its provenance in the PDF/PNG metadata) and its provenance sidecar."""
    from rodimpact.present.figures import save_figure

    save_figure(fig, pdf=pdf, png=png, provenance=provenance_record(records, [pdf, png]), title=title)
    write_provenance(provenance, records, [pdf, png])


def case_in_words(config: Mapping[str, Any]) -> str:
    """A case in words for a title: its ``description`` and its rod (mm), e.g. ``Table 2 row 1:
    steel ball, diameter 3.16 mm, mass 0.13 g; rod radius 1 mm, length 30.1 mm``."""
    rod = config.get("rod") or {}
    if rod.get("radius_m") is not None:
        words = f"rod radius {1000 * float(rod['radius_m']):.3g} mm, length {1000 * float(rod['length_m']):.3g} mm"
    else:
        words = (
            f"rod length {1000 * float(rod['length_m']):.3g} mm, cross-section {1e6 * float(rod['area_m2']):.3g} mm²"
        )
    description = str(config.get("description") or "").strip()
    return f"{description}; {words}" if description else words[0].upper() + words[1:]
