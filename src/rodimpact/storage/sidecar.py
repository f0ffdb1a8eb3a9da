"""Provenance sidecars: what a table, figure or benchmark was made from (``*.provenance.json``)."""

from __future__ import annotations

import datetime as _dt
import json
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.provenance import code_version, file_sha256
from rodimpact.storage.runs import RunRecord

__all__ = ["provenance_record", "write_provenance"]


def provenance_record(records: Sequence[RunRecord], artifacts: Iterable[str | Path]) -> dict[str, Any]:
    """What an artifact was made from: every input run with its config hash and code."""
    return {
        "artifacts": [str(a) for a in artifacts],
        "created_utc": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "code_version": code_version(),
        "inputs": [
            {
                "path": str(r.path),
                "case_id": r.case_id,
                "method": r.method,
                "config_sha256": r.config_sha256,
                "data_sha256": r.data_sha256,
                "code_version": r.code_version,
            }
            for r in records
        ],
    }


def write_provenance(
    path: str | Path,
    records: Sequence[RunRecord],
    artifacts: Iterable[str | Path | None],
    files: Mapping[str, Iterable[str | Path]] | None = None,
) -> None:
    """Write :func:`provenance_record` as JSON, with the SHA-256 of each artifact as written
    (``sha256``: path -> hex digest; ``make provenance`` checks them). ``files`` names the inputs
    that are not runs (band files, curve files, case files, measured records), kind -> paths:
    ``input_files``, a list of ``{path, kind, sha256}``. An artifact given as None (an optional
    output not asked for) is left out."""
    artifacts = [str(a) for a in artifacts if a is not None]
    record = provenance_record(records, artifacts)
    if files is not None:
        record["input_files"] = [
            {"path": str(p), "kind": kind, "sha256": file_sha256(p)} for kind, paths in files.items() for p in paths
        ]
    record["sha256"] = {a: file_sha256(a) for a in artifacts}
    with atomic_output(path) as tmp:
        tmp.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
