"""The case file's format: written by the workflow's first stage, read back by every run.

A case file (``results/cases/{name}.yaml``) is YAML: ``format`` (:data:`CASE_FILE_VERSION`),
``name`` (the group of runs its cases are batched in, or a sweep case's id) and ``cases``, a
list of records, one per case: ``case_id``, ``config_sha256``
(:func:`rodimpact.storage.provenance.config_sha256` of the case), ``case`` (the resolved case)
and ``derived`` (its scales and costs) or, for a sweep case, ``points`` (each point's values and
derived scales); see :mod:`rodimpact.jobs.cases`.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml

from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.faults import UnreadableInput
from rodimpact.storage.provenance import config_sha256, file_sha256

__all__ = ["CASE_FILE_VERSION", "case_file_reference", "case_record", "read_case_file", "write_case_records"]

#: Format of the case file (``format`` at its top).
CASE_FILE_VERSION = 2
#: libyaml's safe loader and dumper where PyYAML has them (a sweep's case file is large: 10,000
#: points write in 5 s with libyaml's emitter, 11 s with PyYAML's), else PyYAML's own; both
#: emitters write the same text (every case file of ``make paper`` compared).
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_DUMPER = getattr(yaml, "CSafeDumper", yaml.SafeDumper)


def write_case_records(name: str, records: list[Mapping[str, Any]], path: str | Path) -> None:
    """Write a case file (YAML, atomically): the records of the cases of ``name``, under a comment
    that says what it is."""
    sources = sorted({str(r["case"].get("source_file", "?")) for r in records})
    header = (
        f"# The resolved cases of {name!r} (from {', '.join(sources)}), with the scales derived\n"
        "# from each and the cost of each method: what their runs compute. Written by the\n"
        "# workflow (rule case_file); edit the cases under config/cases, not this file.\n"
    )
    document = {"format": CASE_FILE_VERSION, "name": name, "cases": [dict(r) for r in records]}
    with atomic_output(path) as tmp:
        tmp.write_text(
            header + yaml.dump(document, Dumper=_DUMPER, sort_keys=False, allow_unicode=True, width=100),
            encoding="utf-8",
        )


def read_case_file(path: str | Path) -> dict[str, Any]:
    """Read a case file, checking that each of its cases still has the hash it was written with.

    Raises
    ------
    UnreadableInput
        The file is not a case file, or one of its cases was edited after it was written (it is
        marked out of date: the next build remakes it).
    """
    try:
        document = yaml.load(Path(path).read_text(encoding="utf-8"), Loader=_LOADER)  # noqa: S506 (a safe loader)
    except (yaml.YAMLError, UnicodeDecodeError) as exc:
        raise UnreadableInput(path, f"not a readable case file ({type(exc).__name__})", mark=True) from None
    records = document.get("cases") if isinstance(document, dict) else None
    if (
        not isinstance(document, dict)
        or document.get("format") != CASE_FILE_VERSION
        or not isinstance(records, list)
        or not all(isinstance(r, dict) and "case" in r and "case_id" in r for r in records)
    ):
        raise UnreadableInput(path, f"not a case file (format {CASE_FILE_VERSION})", mark=True)
    for record in records:
        if config_sha256(record["case"]) != record.get("config_sha256"):
            raise UnreadableInput(
                path,
                f"its case {record.get('case_id')!r} differs from the hash it was written with (edited by hand?)",
                mark=True,
            )
    return document


def case_record(document: Mapping[str, Any], case_id: str) -> dict[str, Any]:
    """The record of ``case_id`` in a case file read by :func:`read_case_file`, or of the case it
    derives from (a study's run of it: ``{case}.map.{point}``, ``{sweep}.sweep.{point}``).

    Raises
    ------
    KeyError
        The file holds no such case.
    """
    records = {r["case_id"]: r for r in document["cases"]}
    if case_id in records:
        return records[case_id]
    bases = [c for c in records if case_id.startswith(f"{c}.")]
    if not bases:
        raise KeyError(f"case file {document.get('name')!r} holds no case {case_id!r}")
    return records[max(bases, key=len)]


def case_file_reference(path: str | Path, case_id: str, document: Mapping[str, Any] | None = None) -> dict[str, str]:
    """What a run of ``case_id`` records of the case file it was made from: its path, its SHA-256
    and the hash of its case in it (``config_sha256``, which only a change of that case changes).

    ``document`` is the file as :func:`read_case_file` read it, when the caller has it (a batch
    reads its case file once for all its runs); otherwise the file is read here."""
    record = case_record(read_case_file(path) if document is None else document, case_id)
    return {"path": str(path), "sha256": file_sha256(path), "config_sha256": record["config_sha256"]}
