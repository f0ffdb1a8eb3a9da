"""Several runs in one job: the points of a sweep, a row of the stability map, the levels of a
work-precision sweep. Each run is its own HDF5 file, written whole (atomically) with its own
provenance, as :func:`rodimpact.jobs.runner.run_to_file` writes a single run; a batch only
shares what every run of it would repeat: the process, its imports, the case file's record and
the code version.
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any, Mapping

from rodimpact.storage.casefile import case_file_reference
from rodimpact.storage.provenance import code_version
from rodimpact.jobs.runner import run_to_file
from rodimpact.jobs.timing import Timing

__all__ = ["run_batch"]

log = logging.getLogger(__name__)


def run_batch(runs: Mapping[str, Mapping[str, Any]], paths: Mapping[str, str | Path], *,
              case_file: str | Path | None = None, keep_failed: bool = False,
              timing: Mapping[str, Any] | None = None) -> list[Path]:
    """Solve every run of a batch and write each to its own file, one after another.

    Parameters
    ----------
    runs : mapping of str to mapping
        Output name -> run: ``case`` (a resolved case), ``method``, and optionally ``study``
        (stored in the run's config, ``run.study``) and ``level`` (a work-precision level).
    paths : mapping of str to path
        Output name -> the run's HDF5 file (the rule's named outputs); the same names as ``runs``.
    case_file : path, optional
        The case file every run of the batch was made from (``run.case_file`` of each).
    keep_failed : bool
        A study's runs: a failure is written as data (see :func:`~rodimpact.jobs.runner.run_to_file`);
        otherwise the first failure raises and the job fails (snakemake removes its files).
    timing : mapping, optional
        :class:`~rodimpact.jobs.timing.Timing` of timed runs (each run repeated).

    Returns
    -------
    list of Path
        The files written, in the order of ``runs``.

    Raises
    ------
    ValueError
        ``runs`` and ``paths`` name different outputs.
    """
    if set(runs) != set(paths):
        raise ValueError(f"runs and paths differ: runs {sorted(runs)}, paths {sorted(paths)}")
    reference = case_file_reference(case_file) if case_file is not None else None
    version = code_version()
    timed = Timing(**timing) if timing is not None else None
    written = []
    for name, run in runs.items():
        written.append(run_to_file(run["case"], run["method"], paths[name], level=run.get("level"),
                                   keep_failed=keep_failed, timing=timed, study=run.get("study"),
                                   case_file=reference, code_version=version))
    log.info("batch of %d runs written", len(written))
    return written
