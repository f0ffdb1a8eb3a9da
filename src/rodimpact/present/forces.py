"""The contact force handed on: each run's P(t) as CSV, and its closed form as JSON.

For a run ``results/runs/{group}/{method}/part{k}.h5#{case}`` the workflow writes

* ``results/forces/{set}/{case}/{method}.csv``: ``time_s,contact_force_N`` at every stored sample, SI
  units, under ``#`` lines that carry the provenance (the run file, its case's and content's
  hashes, the code that made the run and the code that exported it);
* ``results/forces/{set}/{case}/{method}.json``: the Chebyshev closed form of
  :mod:`rodimpact.analysis.force_fit` (formula, intervals, coefficients) with its error
  measured against every sample of the CSV, and the same provenance.

One job exports a whole case set (:func:`export_forces_into`): its directory appears whole or not
at all, with one provenance sidecar beside it.

A figure draws the closed form over the computed force for one case (``model``;
:func:`rodimpact.present.figure_artifacts.make_fig_force_fit`).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from rodimpact.analysis.force_fit import DEFAULT_REL_TOL, ForceFit, fit_force
from rodimpact.storage.atomic import atomic_directory, atomic_output
from rodimpact.storage.provenance import code_version
from rodimpact.storage.runs import RunRecord, read_run
from rodimpact.storage.sidecar import write_provenance

__all__ = ["export_forces", "export_forces_into", "force_fit_of", "read_force_json"]


def force_fit_of(record: RunRecord, rel_tol: float = DEFAULT_REL_TOL) -> ForceFit:
    """The closed form of a stored run's contact force (its contact intervals from the summary)."""
    starts = np.atleast_1d(np.asarray(record.summary.get("contact_start_s", []), dtype=float))
    ends = np.atleast_1d(np.asarray(record.summary.get("contact_end_s", []), dtype=float))
    intervals = [(float(a), float(b)) for a, b in zip(starts, ends) if np.isfinite(a) and np.isfinite(b)]
    return fit_force(record.series["time"], record.series["contact_force"], intervals, rel_tol)


def _provenance(record: RunRecord) -> dict[str, Any]:
    return {
        "case_id": record.case_id,
        "method": record.method,
        "source": str(record.path),
        "config_sha256": record.config_sha256,
        "data_sha256": record.data_sha256,
        "run_code_version": record.code_version,
        "exported_by": f"rodimpact {code_version()}",
    }


def _write_csv(path: str | Path, record: RunRecord, provenance: dict[str, Any]) -> None:
    header = [
        f"# contact force P(t) of case {record.case_id!r} computed by method {record.method!r}",
        *(f"# {key}: {value}" for key, value in provenance.items()),
        "# columns: time_s (s, from the first contact), contact_force_N (N)",
    ]
    t, force = record.series["time"], record.series["contact_force"]
    with atomic_output(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as handle:
            handle.write("\n".join(header) + "\ntime_s,contact_force_N\n")
            np.savetxt(handle, np.column_stack([t, force]), delimiter=",", fmt="%.17g")


def read_force_json(path: str | Path) -> ForceFit:
    """The closed form stored in an exported JSON file."""
    from rodimpact.analysis.force_fit import ContactPiece

    data = json.loads(Path(path).read_text(encoding="utf-8"))["fit"]
    pieces = tuple(
        ContactPiece(p["t0_s"], p["t1_s"], tuple(p["coefficients_N"]), p["max_abs_error_N"]) for p in data["intervals"]
    )
    return ForceFit(pieces, data["peak_force_N"], data["max_abs_error_N"], data["rel_tol"])


def export_forces(
    runs: Sequence[str | Path],
    csvs: Sequence[str | Path],
    jsons: Sequence[str | Path],
    *,
    provenance: str | Path | None,
    rel_tol: float = DEFAULT_REL_TOL,
) -> list[RunRecord]:
    """Write each run's force as CSV and its closed form as JSON (``runs[i]`` to ``csvs[i]``,
    ``jsons[i]``), and one provenance sidecar listing them all (none when ``provenance`` is None);
    the runs read."""
    if not len(runs) == len(csvs) == len(jsons):
        raise ValueError(f"runs, csvs and jsons must be of one length, got {len(runs)}, {len(csvs)}, {len(jsons)}")
    records = []
    for run, csv, json_path in zip(runs, csvs, jsons):
        record = read_run(run)
        records.append(record)
        meta = _provenance(record)
        _write_csv(csv, record, meta)
        fit = force_fit_of(record, rel_tol)
        with atomic_output(json_path) as tmp:
            tmp.write_text(json.dumps({**meta, "fit": fit.to_mapping()}, indent=1) + "\n", encoding="utf-8")
    if provenance is not None:
        write_provenance(provenance, records, [*csvs, *jsons])
    return records


def export_forces_into(
    runs: Sequence[str | Path],
    names: Sequence[str],
    directory: str | Path,
    *,
    provenance: str | Path,
    rel_tol: float = DEFAULT_REL_TOL,
) -> None:
    """:func:`export_forces` of every run of a case set into ``directory``: ``runs[i]`` to
    ``directory/{names[i]}.csv`` and ``.json`` (``names[i]`` is ``{case}/{method}``), the
    directory written whole or not at all (:func:`~rodimpact.storage.atomic.atomic_directory`),
    then the provenance sidecar listing the files where they are."""
    if len(runs) != len(names):
        raise ValueError(f"runs and names must be of one length, got {len(runs)} and {len(names)}")
    directory = Path(directory)
    with atomic_directory(directory) as tmp:
        records = export_forces(
            runs,
            [tmp / f"{name}.csv" for name in names],
            [tmp / f"{name}.json" for name in names],
            provenance=None,
            rel_tol=rel_tol,
        )
    write_provenance(provenance, records, [directory / f"{name}.{ext}" for ext in ("csv", "json") for name in names])
