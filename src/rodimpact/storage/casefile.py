"""The case file's format: written by the workflow's first stage, read back by every run.

A case file (``results/cases/{case}.yaml``) is YAML: ``format`` (:data:`CASE_FILE_VERSION`),
``case_id``, ``config_sha256`` (:func:`rodimpact.storage.provenance.config_sha256` of the case),
``case`` (the resolved case) and ``derived`` (its scales and costs) or, for a sweep case,
``points`` (each point's values and derived scales); see :mod:`rodimpact.jobs.cases`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

import yaml

from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.faults import UnreadableInput
from rodimpact.storage.provenance import config_sha256, file_sha256

__all__ = ["CASE_FILE_VERSION", "case_file_reference", "read_case_file", "write_case_record"]

#: Format of the case file (``format`` at its top).
CASE_FILE_VERSION = 1
#: libyaml's safe loader where PyYAML has it (a sweep's case file is large), else PyYAML's own.
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def write_case_record(record: Mapping[str, Any], path: str | Path) -> None:
    """Write a case file's record as YAML (atomically), under a comment that says what it is."""
    header = (f"# The resolved case {record['case_id']!r} (from {record['case'].get('source_file', '?')}), with the\n"
              "# scales derived from it and the cost of each method: what its runs compute. Written by the\n"
              "# workflow (rule case_file); edit the case under config/cases, not this file.\n")
    with atomic_output(path) as tmp:
        tmp.write_text(header + yaml.safe_dump(dict(record), sort_keys=False, allow_unicode=True, width=100),
                       encoding="utf-8")


def read_case_file(path: str | Path) -> dict[str, Any]:
    """Read a case file, checking that its case still has the hash it was written with.

    Raises
    ------
    UnreadableInput
        The file is not a case file, or its case was edited after it was written (it is
        marked out of date: the next build remakes it).
    """
    try:
        record = yaml.load(Path(path).read_text(encoding="utf-8"), Loader=_LOADER)  # noqa: S506 (a safe loader)
    except (yaml.YAMLError, UnicodeDecodeError) as exc:
        raise UnreadableInput(path, f"not a readable case file ({type(exc).__name__})", mark=True) from None
    if not isinstance(record, dict) or record.get("format") != CASE_FILE_VERSION or "case" not in record:
        raise UnreadableInput(path, f"not a case file (format {CASE_FILE_VERSION})", mark=True)
    if config_sha256(record["case"]) != record.get("config_sha256"):
        raise UnreadableInput(path, "its case differs from the hash it was written with (edited by hand?)", mark=True)
    return record


def case_file_reference(path: str | Path) -> dict[str, str]:
    """What a run records of the case file it was made from: its path, its SHA-256 and the
    hash of the case it holds (``config_sha256``, which only a change of the case changes)."""
    record = read_case_file(path)
    return {"path": str(path), "sha256": file_sha256(path), "config_sha256": record["config_sha256"]}
