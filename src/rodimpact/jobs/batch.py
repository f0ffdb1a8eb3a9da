"""Several runs in one job: one part of a batch (a group's cases, the levels of a work-precision
sweep, a stress set's cases, the stability map's points or a sweep's points, by one method). Each
run is stored with its own provenance, as :func:`rodimpact.jobs.runner.run_to_file` stores a
single run; a batch only shares what every run of it would repeat: the process, its imports, the
case file's record and the code version. A batch writes every run into one file of runs
(:func:`run_batch_file`, what the workflow's solver rules do: one file per job, not per run), or
each run to its own HDF5 file (:func:`run_batch`).

A run whose contact law is calibrated by a curve (a sweep point of a ``tabulated`` law) has no
case of its own for the workflow's curve rule to compute it: its ``curve`` entry names the rule
and its settings, and the batch computes the curve of the point's own bodies before the run
(:data:`CURVE_BUILDERS`); the run stores the curve's summary (``run.contact_curve``).
"""

from __future__ import annotations

import importlib
import logging
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

from rodimpact.jobs.runner import SolvedRun, solve_run
from rodimpact.jobs.timing import Timing
from rodimpact.storage.casefile import case_file_reference, read_case_file
from rodimpact.storage.provenance import code_version
from rodimpact.storage.references import can_name_a_run
from rodimpact.storage.runs import write_run, write_runs

__all__ = ["CURVE_BUILDERS", "run_batch", "run_batch_file"]

log = logging.getLogger(__name__)

#: A law's curve rule (``needs.curve_rule``) -> the module and function that compute its curve
#: in a job, ``(case, settings) -> ContactCurve`` (imported by the batches that need one: the
#: continuum's modules cost a batch of SEM runs more than its runs).
CURVE_BUILDERS = {"indentation": ("rodimpact.jobs.indentation", "indentation_curve")}


def _solved(
    runs: Mapping[str, Mapping[str, Any]],
    case_file: str | Path | None,
    keep_failed: bool,
    timing: Mapping[str, Any] | None,
) -> Iterator[tuple[str, SolvedRun]]:
    """Each run of the batch solved, one after another, with its name (as :func:`run_batch`)."""
    references: dict[tuple[str, str], dict[str, str]] = {}
    documents: dict[str, dict[str, Any]] = {}  # each case file read once (a sweep's runs share one)
    version = code_version()
    timed = Timing(**timing) if timing is not None else None
    for name, run in runs.items():
        curve = run.get("contact_curve")  # the curve file of a law calibrated by a rule's curve
        if run.get("curve") is not None:
            rule = run["curve"].get("rule")
            if rule not in CURVE_BUILDERS:
                raise ValueError(f"runs: {name}: no curve rule {rule!r} in a batch; known: {', '.join(CURVE_BUILDERS)}")
            module, function = CURVE_BUILDERS[rule]
            curve = getattr(importlib.import_module(module), function)(run["case"], run["curve"].get("settings"))
        source = run.get("case_file", case_file)
        key = (str(source), str(run["case"]["id"]))
        if source is not None and key not in references:
            if key[0] not in documents:
                documents[key[0]] = read_case_file(source)
            references[key] = case_file_reference(source, run["case"]["id"], documents[key[0]])
        yield (
            name,
            solve_run(
                run["case"],
                run["method"],
                level=run.get("level"),
                keep_failed=keep_failed,
                timing=timed,
                study=run.get("study"),
                case_file=None if source is None else references[key],
                contact_curve=curve,
                code_version=version,
            ),
        )


def run_batch(
    runs: Mapping[str, Mapping[str, Any]],
    paths: Mapping[str, str | Path],
    *,
    case_file: str | Path | None = None,
    keep_failed: bool = False,
    timing: Mapping[str, Any] | None = None,
) -> list[Path]:
    """Solve every run of a batch and write each to its own file, one after another.

    Parameters
    ----------
    runs : mapping of str to mapping
        Output name -> run: ``case`` (a resolved case), ``method``, and optionally ``study``
        (stored in the run's config, ``run.study``), ``level`` (a work-precision level) and
        ``curve`` (``{"rule": ..., "settings": ...}``: the law's curve, computed here first),
        ``contact_curve`` (the file of the law's curve, when a rule computed it) and
        ``case_file`` (the case file of this run, when it is not the batch's ``case_file``).
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
        ``runs`` and ``paths`` name different outputs, or a run's ``curve`` names no rule of
        :data:`CURVE_BUILDERS`.
    """
    if set(runs) != set(paths):
        raise ValueError(f"runs and paths differ: runs {sorted(runs)}, paths {sorted(paths)}")
    written = [
        write_run(paths[name], **solved.arguments()) for name, solved in _solved(runs, case_file, keep_failed, timing)
    ]
    log.info("batch of %d runs written", len(written))
    return written


def run_batch_file(runs: Mapping[str, Mapping[str, Any]], path: str | Path, **options: Any) -> list[str]:
    """:func:`run_batch` with every run written into one file of runs ``path``
    (:func:`rodimpact.storage.runs.write_runs`), each as a group named by its run, with its
    own provenance and digest. The file appears when every run is in it, or not at all.
    ``options`` as for :func:`run_batch`; returns the runs' references (``path#name``).

    Raises
    ------
    ValueError
        A run's name cannot name a group (empty, with ``/`` or ``#``), or as :func:`run_batch`.
    """
    if not runs:
        raise ValueError(f"runs: no run to write to {path}")
    bad = [name for name in runs if not can_name_a_run(name)]
    if bad:
        raise ValueError(f"runs: {bad[0]!r} cannot name a run in the file of runs {path}")
    options = {"case_file": None, "keep_failed": False, "timing": None, **options}
    with write_runs(path) as writer:
        written = [writer.add(name, **solved.arguments()) for name, solved in _solved(runs, **options)]
    log.info("batch of %d runs written to %s", len(written), path)
    return written
