"""What an artifact reads besides its own table: the stored runs' summaries, the cases of case
files, and the one case a figure of one case shows."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from rodimpact.storage.casefile import read_case_file
from rodimpact.storage.runs import RunRecord, read_summary

__all__ = ["cases_in", "load_records", "one_case"]


def load_records(paths: Iterable[str | Path]) -> list[RunRecord]:
    """The summaries (and verified configs) of stored runs."""
    return [read_summary(p) for p in paths]


def cases_in(case_files: Sequence[str | Path]) -> dict[str, Any]:
    """Case id -> resolved case, of every case of the case files."""
    return {record["case_id"]: record["case"] for path in case_files for record in read_case_file(path)["cases"]}


def one_case(records: Sequence[RunRecord], what: str) -> str:
    """The single case id of ``records``, for ``what`` (a figure of one case).

    Raises
    ------
    ValueError
        The records are of no case or of several.
    """
    cases = sorted({r.case_id for r in records})
    if len(cases) != 1:
        raise ValueError(f"runs: {what} shows one case, got {cases}")
    return cases[0]
