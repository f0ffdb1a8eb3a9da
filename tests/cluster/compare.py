"""Whether two builds of the same configuration hold the same results: the files under
``results/``, every HDF5 dataset and attribute, every table (``results/tables/*.csv``), each but
for what records when and how long (listed below with the reason).
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any

import h5py
import numpy as np

#: HDF5 attributes that differ between two builds of the same results, by name, and why.
VOLATILE_ATTRIBUTES: dict[str, str] = {
    "created_utc": "when the file was written",
    "wall_time_s": "how long the solve took (the run's root attribute)",
    "solver_wall_time_s": "how long the solver ran (summary)",
    "wall_time_min_s": "the fastest of a timed solve's repeats (summary of a work-precision level)",
    "wall_time_median_s": "the median of a timed solve's repeats",
    "wall_time_max_s": "the slowest of a timed solve's repeats",
    "code_version": "names the commit of the repository that built the file: each build is made "
    "in a repository of its own (the provenance audit checks that it is a commit "
    "there, with no uncommitted change)",
    "data_sha256": "the digest of the run's config, series and summary, which holds the timings "
    "above (the provenance audit checks it against the file's content)",
}
#: Entries of a run's ``config_json`` that differ between two builds of the same results, and why.
VOLATILE_CONFIG_ENTRIES: dict[tuple[str, ...], str] = {
    ("run", "contact_curve", "sha256"): "the SHA-256 of the contact-law curve file's bytes "
    "(results/indentation/*/*.h5), which hold that file's "
    "created_utc and code_version; the curve's data are "
    "compared as a file of their own",
}
#: Derived from ``config_json``: compared when the two ``config_json`` are equal as written.
DERIVED_ATTRIBUTES: dict[str, str] = {"config_sha256": "the SHA-256 of config_json"}
#: Columns of results/tables/*.csv that differ between two builds, by table, and why.
TIMING_COLUMNS: dict[str, dict[str, str]] = {
    "work_precision.csv": {
        "wall_time_s": "the timed solve's wall time (the median of its repeats)",
        "wall_time_min_s": "the fastest repeat",
        "wall_time_max_s": "the slowest repeat",
    },
    "stability.csv": {"wall_time_s": "each stress run's solver wall time"},
}


def result_files(workdir: Path) -> set[str]:
    """The files under ``workdir/results``, relative to ``workdir``."""
    base = workdir / "results"
    return {str(p.relative_to(workdir)) for p in base.rglob("*") if p.is_file()}


def _plain(value: Any, h5: h5py.File) -> Any:
    """An attribute's value as plain data: object references as the names they point to, byte
    strings decoded, arrays of objects as lists."""
    if isinstance(value, h5py.Reference):
        return h5[value].name if value else None
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray):
        if value.dtype.names:
            return [tuple(_plain(row[name], h5) for name in value.dtype.names) for row in value.flat]
        if value.dtype.kind in "OSU":
            return [_plain(item, h5) for item in value.flat] + [("shape", value.shape)]
        return value
    if isinstance(value, np.generic):
        return value.item()
    return value


def _same(a: Any, b: Any) -> bool:
    """Equal as data: arrays element by element (NaN equal to NaN), sequences item by item."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
            return False
        return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"))
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def _config_without_volatile(text: str) -> Any:
    """A run's ``config_json`` parsed, without :data:`VOLATILE_CONFIG_ENTRIES`."""
    config = json.loads(text)
    for path in VOLATILE_CONFIG_ENTRIES:
        node = config
        for key in path[:-1]:
            node = node.get(key) if isinstance(node, dict) else None
        if isinstance(node, dict):
            node.pop(path[-1], None)
    return config


def _same_attribute(key: str, ref_obj: h5py.HLObject, new_obj: h5py.HLObject, ref: h5py.File, new: h5py.File) -> bool:
    """Whether attribute ``key`` of two objects holds the same data (see the module's tables)."""
    a, b = _plain(ref_obj.attrs[key], ref), _plain(new_obj.attrs[key], new)
    if key == "config_json" and isinstance(a, str) and isinstance(b, str):
        return a == b or _config_without_volatile(a) == _config_without_volatile(b)
    if key in DERIVED_ATTRIBUTES and "config_json" in ref_obj.attrs and "config_json" in new_obj.attrs:
        if _plain(ref_obj.attrs["config_json"], ref) != _plain(new_obj.attrs["config_json"], new):
            return True  # config_json compared without its volatile entries above
    return _same(a, b)


def _objects(h5: h5py.File) -> dict[str, h5py.HLObject]:
    """Every group and dataset of a file by its path, the root included."""
    found: dict[str, h5py.HLObject] = {"/": h5}

    def add(name: str, obj: h5py.HLObject) -> None:
        found["/" + name] = obj

    h5.visititems(add)
    return found


def compare_h5(reference: Path, built: Path) -> list[str]:
    """How ``built`` differs from ``reference`` (empty: the same): the objects, every dataset's
    values (shape, type, every element) and every attribute of every object, except
    :data:`VOLATILE_ATTRIBUTES` (and ``config_json`` without :data:`VOLATILE_CONFIG_ENTRIES`)."""
    problems = []
    with h5py.File(reference, "r") as ref, h5py.File(built, "r") as new:
        ref_objects, new_objects = _objects(ref), _objects(new)
        if set(ref_objects) != set(new_objects):
            return [
                f"objects differ: only in the reference {sorted(set(ref_objects) - set(new_objects))}, "
                f"only in the build {sorted(set(new_objects) - set(ref_objects))}"
            ]
        for name, ref_obj in ref_objects.items():
            new_obj = new_objects[name]
            if isinstance(ref_obj, h5py.Dataset):
                if not isinstance(new_obj, h5py.Dataset):
                    problems.append(f"{name}: a dataset in the reference only")
                    continue
                if not _same(_plain(ref_obj[()], ref), _plain(new_obj[()], new)):
                    problems.append(f"{name}: values differ")
            keys = set(ref_obj.attrs) | set(new_obj.attrs)
            for key in sorted(keys - set(VOLATILE_ATTRIBUTES)):
                if key not in ref_obj.attrs or key not in new_obj.attrs:
                    problems.append(f"{name} @{key}: in one file only")
                elif not _same_attribute(key, ref_obj, new_obj, ref, new):
                    problems.append(f"{name} @{key}: {_short(ref_obj.attrs[key])} != {_short(new_obj.attrs[key])}")
    return problems


def _short(value: Any) -> str:
    """A value on one line of at most 80 characters."""
    text = " ".join(str(value).split())
    return text if len(text) <= 80 else text[:77] + "..."


def _rows(path: Path) -> tuple[list[str], list[list[str]]]:
    """A CSV file's header and rows, as written."""
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    return (rows[0], rows[1:]) if rows else ([], [])


def compare_table(reference: Path, built: Path) -> list[str]:
    """How the CSV table ``built`` differs from ``reference``: its header, its number of rows,
    and every cell as written, except the table's :data:`TIMING_COLUMNS`."""
    ref_header, ref_rows = _rows(reference)
    new_header, new_rows = _rows(built)
    if ref_header != new_header:
        return [f"header differs: {ref_header} != {new_header}"]
    if len(ref_rows) != len(new_rows):
        return [f"{len(new_rows)} rows, the reference has {len(ref_rows)}"]
    skipped = TIMING_COLUMNS.get(reference.name, {})
    problems = []
    for number, (ref_row, new_row) in enumerate(zip(ref_rows, new_rows), start=2):
        for column, ref_cell, new_cell in zip(ref_header, ref_row, new_row):
            if column not in skipped and ref_cell != new_cell:
                problems.append(f"line {number}, {column}: {ref_cell!r} != {new_cell!r}")
    return problems


def compare_builds(reference: Path, built: Path) -> tuple[dict[str, int], list[str]]:
    """Compare two working directories' ``results/`` (``.test`` of two copies): the same files,
    the same HDF5 contents, the same tables. Returns what was compared (counts by kind) and the
    differences, one line each (empty: the same)."""
    ref_files, new_files = result_files(reference), result_files(built)
    problems = [f"{path}: only in the reference build" for path in sorted(ref_files - new_files)]
    problems += [f"{path}: only in the SLURM build" for path in sorted(new_files - ref_files)]
    common = sorted(ref_files & new_files)
    counts = {"files": len(common), "hdf5": 0, "datasets": 0, "tables": 0}
    for path in common:
        if path.endswith(".h5"):
            counts["hdf5"] += 1
            with h5py.File(built / path, "r") as h5:
                counts["datasets"] += sum(isinstance(obj, h5py.Dataset) for obj in _objects(h5).values())
            problems += [f"{path}: {p}" for p in compare_h5(reference / path, built / path)]
        elif path.startswith("results/tables/") and path.endswith(".csv"):
            counts["tables"] += 1
            problems += [f"{path}: {p}" for p in compare_table(reference / path, built / path)]
    return counts, problems
