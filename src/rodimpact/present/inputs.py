"""What an artifact reads besides its own table: the stored runs' summaries, the cases of case
files, and the one case a figure of one case shows."""

from __future__ import annotations

import multiprocessing
from collections.abc import Iterable, Sequence
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

from rodimpact.storage.casefile import read_case_file
from rodimpact.storage.runs import RunRecord, read_summary

__all__ = ["RUNS_PER_READER", "cases_in", "load_records", "one_case"]

#: The fewest runs worth a reading process of their own: a process costs tens of ms to fork and
#: its records the trip back; a run costs about 4 ms to read and check.
RUNS_PER_READER = 500


def _read(paths: Sequence[str | Path]) -> list[RunRecord]:
    return [read_summary(p) for p in paths]


def load_records(paths: Iterable[str | Path], workers: int = 1) -> list[RunRecord]:
    """The summaries (and verified configs) of stored runs, in the order of ``paths``.

    Each run is read and checked against its digest (:func:`~rodimpact.storage.runs.read_summary`),
    about 4 ms a run. With ``workers`` above one (a job's threads) and at least
    :data:`RUNS_PER_READER` runs a reader, the runs are read by as many forked processes, each a
    consecutive slice (a sweep's runs lie in their parts' files in order), and returned in order.
    """
    paths = list(paths)
    readers = min(workers, len(paths) // RUNS_PER_READER)
    if readers < 2:
        return _read(paths)
    size = -(-len(paths) // (4 * readers))  # four slices a reader: one slow file does not hold the rest
    slices = [paths[start : start + size] for start in range(0, len(paths), size)]
    # forked, not spawned: a snakemake script is no importable __main__, and no HDF5 file is open yet
    with ProcessPoolExecutor(readers, mp_context=multiprocessing.get_context("fork")) as pool:
        return [record for part in pool.map(_read, slices) for record in part]


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
