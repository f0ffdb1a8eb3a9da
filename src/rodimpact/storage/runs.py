"""HDF5 storage of one solver run with provenance, written atomically.

HDF5 schema of one run (``schema_version`` 1)
---------------------------------------------
One file per run (one case solved by one method); SI units throughout::

    /                          root group
      @case_id           str    case identifier, config["id"]
      @method            str    solver method, e.g. "sem"
      @config_json       str    canonical JSON of the fully resolved case + numerics
      @config_sha256     str    hex SHA-256 of config_json (UTF-8)
      @code_version      str    "{version}+g{commit}[.dirty]" or "{version}+unknown"
      @library_versions  str    canonical JSON {"python": ..., "numpy": ..., ...}
      @wall_time_s       float  solver wall-clock time (s)
      @created_utc       str    ISO 8601 UTC time, e.g. "2018-05-01T12:00:00+00:00"
      @schema_version    int    1
      @data_sha256       str    provenance.data_sha256 of config, method, series and summary
      time                    float64 (n,)    s    always present
      contact_force           float64 (n,)    N    optional
      approach                float64 (n,)    m    optional
      impactor_displacement   float64 (n,)    m    optional
      impactor_velocity       float64 (n,)    m/s  optional
      rod_end_displacement    float64 (n,)    m    optional
      <other name>            float64 (n,) or (n, k), e.g. 2-D station histories
        every dataset: @units (str), @description (str) and @long_name (the description,
        the name netCDF/CF readers show); first dimension n = len(time), attached to
        ``time`` as its HDF5 dimension scale (labelled "time"; a second dimension is
        labelled "station"); gzip level 4 + shuffle when larger than 4096 elements
      summary/                 group, attributes only
        @contact_time_s        float       duration of contact (s)
        @peak_force_N          float (p,)  contact force maxima, possibly empty (N)
        @peak_time_s           float (p,)  times of those maxima (s)
        @rebound_velocity_m_s  float       impactor velocity after separation (m/s)
        @energy_error          float       energy balance error reported by the solver (-)
        @<other name>          float, int, bool or str scalar, or 1-D numeric array
                               (e.g. contact_start_s, contact_end_s, n_contacts,
                               success, status, message, n_steps)
      field/                   group, the strain over the rod on its own grid, when recorded
                               (:mod:`rodimpact.storage.runfield`: time (m,), x (k,), strain (m, k))

A file of runs (``layout`` ``"runs"``)
-------------------------------------
Several runs of one job in one file (the points of one part of a sweep, :mod:`rodimpact.jobs.parts`)::

    /                          root group
      @layout            str    "runs"
      @schema_version    int    1
      @runs              int    the number of runs
      <name>/                  one group per run, named by the run (a sweep point's name),
                               laid out as a run file's root above: its own attributes,
                               provenance and digest, series, summary and field

A run in such a file is named by the reference ``"{file}#{name}"`` (:func:`run_reference`):
:func:`read_run` and :func:`read_summary` take it where they take a run file's path, and
:func:`run_references` lists a file's runs. One file per job instead of one per run is what a
cluster's file system handles best (docs/storage.md).

Writes go through :func:`rodimpact.storage.atomic.atomic_output` (a temporary file beside the
target, fsynced and moved onto it with :func:`os.replace`); a failed write leaves no
temporary file and the target unchanged. A file of runs is written the same way, once every
run of it is in (:func:`write_runs`): it appears whole or not at all.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import logging
import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from dataclasses import field as dataclass_field
from datetime import UTC, datetime
from numbers import Real
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from rodimpact.storage import provenance
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.faults import UnreadableInput
from rodimpact.storage.references import RUN_SEPARATOR, can_name_a_run, run_reference, split_reference
from rodimpact.storage.runcheck import (
    REQUIRED_SUMMARY,
    SUMMARY_GROUP,
    all_str,
    check_config,
    check_series,
    check_summary,
)
from rodimpact.storage.runfield import check_field, digest_entries, read_field, write_field

logger = logging.getLogger(__name__)

__all__ = ["REQUIRED_SUMMARY", "RUNS_LAYOUT", "RUN_SEPARATOR", "SCHEMA_VERSION", "CorruptRun", "RunRecord"]
__all__ += ["RunsWriter", "StoreError", "read_run", "read_summary", "run_reference", "run_references"]
__all__ += ["split_reference", "write_run", "write_runs"]

SCHEMA_VERSION = 1
#: The ``layout`` attribute of a file of runs.
RUNS_LAYOUT = "runs"
_STR_ATTRS = tuple("case_id method config_json config_sha256 code_version library_versions created_utc".split())
_ROOT_ATTRS = (*_STR_ATTRS, "wall_time_s", "schema_version")
_COMPRESS_MIN_ELEMENTS = 4096
_COMPRESSION = {"compression": "gzip", "compression_opts": 4, "shuffle": True}


class StoreError(RuntimeError):
    """A file is not a valid rodimpact run file (missing data, hash mismatch, ...)."""


class CorruptRun(StoreError, UnreadableInput):
    """A run file that cannot be read, or whose content no longer matches its digest
    (``path``, ``reason``); the reader marks it out of date (:mod:`rodimpact.storage.faults`)."""

    def __init__(self, path: str | Path, reason: str) -> None:
        UnreadableInput.__init__(self, path, reason, mark=True, file=split_reference(path)[0])


@dataclass(frozen=True)
class RunRecord:
    """Contents of one stored run; fields mirror the HDF5 schema above (``wall_time_s`` in s).

    ``config``/``library_versions`` are parsed JSON. ``series`` maps name to a float64 array
    (n,) or (n, k), ``units``/``descriptions`` keyed alike (all empty from :func:`read_summary`).
    ``summary``: Python float/int/bool/str scalars and 1-D numpy arrays. ``field``: the
    space-time field (``time`` (m,), ``x`` (k,), ``strain`` (m, k); empty when the run has
    none, and from :func:`read_summary`), its units in ``field_units``.
    """

    path: Path
    case_id: str
    method: str
    config: dict
    config_sha256: str
    code_version: str
    library_versions: dict
    wall_time_s: float
    created_utc: str
    series: dict[str, np.ndarray]
    units: dict[str, str]
    summary: dict[str, Any]
    descriptions: dict[str, str] = dataclass_field(default_factory=dict)
    data_sha256: str = ""  # empty: written before the digest was stored
    field: dict[str, np.ndarray] = dataclass_field(default_factory=dict)
    field_units: dict[str, str] = dataclass_field(default_factory=dict)


def _write_summary(h5: h5py.File, summary: Mapping[str, Any]) -> None:
    h5.create_group(SUMMARY_GROUP, track_order=True).attrs.update(summary)


@dataclass(frozen=True)
class _CheckedRun:
    """A run's content, checked and ready to write: root attributes, series, field, summary."""

    attrs: dict[str, Any]
    series: list
    field: list
    summary: dict[str, Any]


def _check_run(
    config: Mapping[str, Any],
    method: str,
    series: Mapping[str, tuple[np.ndarray, str, str]],
    summary: Mapping[str, Any],
    wall_time_s: float,
    code_version: str | None,
    field: Mapping[str, tuple[np.ndarray, str, str]] | None,
) -> _CheckedRun:
    """The checks of :func:`write_run` (its errors), and the root attributes with the digests."""
    for name, arg in (("config", config), ("series", series), ("summary", summary)):
        if not isinstance(arg, Mapping):
            raise TypeError(f"{name} must be a mapping, got {type(arg).__name__}")
    case_id, config_json = check_config(config)
    if not isinstance(method, str) or not method:
        raise ValueError(f"method must be a non-empty str, got {method!r}")
    checked_series = check_series(series)
    checked_field = check_field(field)
    checked_summary = check_summary(summary)
    real = isinstance(wall_time_s, Real) and not isinstance(wall_time_s, bool)
    if not (real and math.isfinite(wall_time_s) and wall_time_s >= 0):
        raise ValueError(f"wall_time_s must be a finite number >= 0, got {wall_time_s!r}")
    code_version = provenance.code_version() if code_version is None else code_version
    if not isinstance(code_version, str) or not code_version:
        raise ValueError(f"code_version must be a non-empty str, got {code_version!r}")
    attrs: dict[str, Any] = {
        "case_id": case_id,
        "method": method,
        "config_json": config_json,
        "config_sha256": hashlib.sha256(config_json.encode("utf-8")).hexdigest(),
        "code_version": code_version,
        "library_versions": provenance.canonical_json(provenance.library_versions()),
        "wall_time_s": np.float64(wall_time_s),
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "schema_version": np.int64(SCHEMA_VERSION),
        "data_sha256": provenance.data_sha256(
            config_json,
            method,
            {**{n: (a, u, d) for n, a, u, d in checked_series}, **digest_entries(checked_field)},
            checked_summary,
        ),
    }
    return _CheckedRun(attrs, checked_series, checked_field, checked_summary)


def _write_checked(group: h5py.Group, run: _CheckedRun) -> None:
    """Write a checked run into ``group`` (a file's root, or a run's group in a file of runs)."""
    group.attrs.update(run.attrs)
    for name, array, units, description in run.series:
        big = array.size > _COMPRESS_MIN_ELEMENTS
        dataset = group.create_dataset(name, data=array, **(_COMPRESSION if big else {}))
        dataset.attrs.update({"units": units, "description": description, "long_name": description})
    _attach_time_scale(group)
    write_field(group, run.field)
    _write_summary(group, run.summary)


def write_run(
    path: str | Path,
    *,
    config: Mapping[str, Any],
    method: str,
    series: Mapping[str, tuple[np.ndarray, str, str]],
    summary: Mapping[str, Any],
    wall_time_s: float,
    code_version: str | None = None,
    field: Mapping[str, tuple[np.ndarray, str, str]] | None = None,
) -> Path:
    """Write one solver run to an HDF5 file atomically (schema in the module docstring).

    Parameters
    ----------
    path : str or Path
        Target file; its parent directory is created if needed.
    config : mapping
        Fully resolved case + numerics, plain JSON data; must contain ``"id"``.
    method : str
        Solver method name.
    series : mapping of str to (array, units, description)
        Must contain ``"time"`` (shape (n,), s); other arrays have shape (n,) or (n, k).
    summary : mapping of str to scalar, str or 1-D array
        Must contain ``contact_time_s`` (s), ``peak_force_N`` (N, shape (p,)),
        ``peak_time_s`` (s, shape (p,)), ``rebound_velocity_m_s`` (m/s), ``energy_error``.
    wall_time_s : float
        Solver wall-clock time (s), finite and non-negative.
    code_version : str, optional
        Defaults to :func:`rodimpact.storage.provenance.code_version`.
    field : mapping of str to (array, units, description), optional
        The space-time field (:mod:`rodimpact.storage.runfield`): ``time`` (m,) s, ``x`` (k,) m and
        2-D datasets (m, k), written to the group ``field``; none by default.

    Returns
    -------
    Path
        The written file.

    Raises
    ------
    ValueError, TypeError
        Invalid argument (named in the message); nothing is written.
    OSError
        Writing failed; the target is unchanged and no temporary file remains.
    """
    path = Path(path)
    run = _check_run(config, method, series, summary, wall_time_s, code_version, field)
    with atomic_output(path) as tmp:
        with h5py.File(tmp, "x", track_order=True) as h5:
            _write_checked(h5, run)
            h5.flush()
    logger.info("wrote run %s/%s to %s (%d bytes)", run.attrs["case_id"], method, path, path.stat().st_size)
    return path


class RunsWriter:
    """The open file of runs of :func:`write_runs`: :meth:`add` writes one run into it."""

    def __init__(self, h5: h5py.File, path: Path) -> None:
        self._h5, self.path, self.names = h5, path, []

    def add(
        self,
        name: str,
        *,
        config: Mapping[str, Any],
        method: str,
        series: Mapping[str, tuple[np.ndarray, str, str]],
        summary: Mapping[str, Any],
        wall_time_s: float,
        code_version: str | None = None,
        field: Mapping[str, tuple[np.ndarray, str, str]] | None = None,
    ) -> str:
        """Write the run ``name`` (parameters as :func:`write_run`'s); returns its reference.

        Raises
        ------
        ValueError, TypeError
            Invalid argument, or ``name`` is empty, holds ``/`` or :data:`RUN_SEPARATOR`, or is
            taken; nothing of the run is written.
        """
        if not can_name_a_run(name):
            raise ValueError(f"name: {name!r} cannot name a run in a file of runs")
        if name in self._h5:
            raise ValueError(f"name: {self.path} already holds a run {name!r}")
        run = _check_run(config, method, series, summary, wall_time_s, code_version, field)
        _write_checked(self._h5.create_group(name, track_order=True), run)
        self.names.append(name)
        return run_reference(self.path, name)


@contextlib.contextmanager
def write_runs(path: str | Path) -> Iterator[RunsWriter]:
    """Write a file of runs (schema in the module docstring) atomically: the runs added in the
    ``with`` block appear together when it ends, or (on an exception) nothing does.

    Parameters
    ----------
    path : str or Path
        Target file; its parent directory is created if needed.

    Yields
    ------
    RunsWriter
        ``add(name, **run)`` writes each run, as :func:`write_run` takes it.
    """
    path = Path(path)
    with atomic_output(path) as tmp:
        with h5py.File(tmp, "x", track_order=True) as h5:
            writer = RunsWriter(h5, path)
            yield writer
            h5.attrs.update({"layout": RUNS_LAYOUT, "schema_version": np.int64(SCHEMA_VERSION)})
            h5.attrs["runs"] = np.int64(len(writer.names))
            h5.flush()
    logger.info("wrote %d runs to %s (%d bytes)", len(writer.names), path, path.stat().st_size)


def run_references(path: str | Path) -> list[str]:
    """The runs a file holds: ``[path]`` for a run file, the reference of each run in a file
    of runs (in the order written).

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist.
    CorruptRun
        The file is not HDF5, or cannot be read.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"path does not exist or is not a file: {path}")
    if not h5py.is_hdf5(path):
        raise CorruptRun(path, "not an HDF5 file (truncated, or not a rodimpact run file)")
    try:
        with h5py.File(path, "r") as h5:
            if _attr_value(h5.attrs.get("layout")) != RUNS_LAYOUT:
                return [str(path)]
            return [run_reference(path, name) for name, item in h5.items() if isinstance(item, h5py.Group)]
    except (OSError, KeyError, ValueError, TypeError, RuntimeError) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise CorruptRun(path, f"unreadable run file ({reason})") from None


def _attach_time_scale(h5: h5py.Group) -> None:
    """Make ``time`` the dimension scale of every series' first dimension (netCDF-4 readers,
    xarray and HDFView then plot each series against time)."""
    time = h5["time"]
    time.make_scale("time")
    for name, dataset in h5.items():
        if isinstance(dataset, h5py.Dataset) and name != "time":
            dataset.dims[0].attach_scale(time)
            dataset.dims[0].label = "time"
            if dataset.ndim == 2:
                dataset.dims[1].label = "station"


def _attr_value(value: Any) -> Any:
    """Convert an h5py attribute value to a Python scalar or 1-D numpy array."""
    if isinstance(value, np.ndarray) and value.ndim > 0:
        return np.array(value)
    if isinstance(value, (np.generic, np.ndarray)):
        value = value.item()
    return value.decode("utf-8") if isinstance(value, bytes) else value


def _read_series(h5: h5py.Group, path: Path) -> tuple[dict, dict, dict]:
    """Read all root datasets: ``(series, units, descriptions)``."""
    datasets = {name: obj for name, obj in h5.items() if isinstance(obj, h5py.Dataset)}
    n_time = h5["time"].shape[0] if h5["time"].ndim == 1 else -1
    for name, obj in datasets.items():
        if not all_str(tuple(_attr_value(obj.attrs.get(a)) for a in ("units", "description"))):
            raise StoreError(f"{path}: dataset {name!r} lacks a str units or description")
        if obj.ndim not in (1, 2) or obj.shape[0] != n_time:
            raise StoreError(f"{path}: dataset {name!r} has shape {obj.shape}, n = {n_time}")
    return (
        {name: np.asarray(obj[()], dtype=np.float64) for name, obj in datasets.items()},
        {name: _attr_value(obj.attrs["units"]) for name, obj in datasets.items()},
        {name: _attr_value(obj.attrs["description"]) for name, obj in datasets.items()},
    )


def _read_record(reference: str | Path, *, verify: bool, with_series: bool) -> RunRecord:
    file, name = split_reference(reference)
    path = Path(str(reference))  # the run's own name: its file, or file#name
    if not file.is_file():
        raise FileNotFoundError(f"path does not exist or is not a file: {file}")
    if not h5py.is_hdf5(file):
        raise CorruptRun(file, "not an HDF5 file (truncated, or not a rodimpact run file)")
    try:
        with h5py.File(file, "r") as h5:
            if name is not None and not isinstance(h5.get(name), h5py.Group):
                raise CorruptRun(path, f"no run {name!r} in the file of runs {file}")
            group = h5 if name is None else h5[name]
            attrs, summary, series, units, descriptions, field = _read_parts(group, path, verify, with_series)
    except StoreError:
        raise
    except (OSError, KeyError, ValueError, TypeError, RuntimeError) as exc:  # HDF5's errors of a damaged file
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise CorruptRun(path, f"unreadable run file ({reason})") from None
    try:
        config = json.loads(attrs["config_json"])
        libraries = json.loads(attrs["library_versions"])
    except json.JSONDecodeError as exc:
        raise CorruptRun(path, f"config_json or library_versions is not JSON: {exc}") from None
    if verify:
        digest = hashlib.sha256(attrs["config_json"].encode("utf-8")).hexdigest()
        if digest != attrs["config_sha256"]:
            raise CorruptRun(path, "config_sha256 mismatch; config_json was modified")
        if not isinstance(config, dict) or config.get("id") != attrs["case_id"]:
            raise CorruptRun(path, f"case_id {attrs['case_id']!r} does not match config['id']")
        if attrs.get("data_sha256"):
            content = {name: (values, units[name], descriptions[name]) for name, values in series.items()}
            content.update(digest_entries(field))
            if provenance.data_sha256(attrs["config_json"], attrs["method"], content, summary) != attrs["data_sha256"]:
                raise CorruptRun(path, "its content differs from its data_sha256 (changed after it was written)")
    if not with_series:
        series, units, descriptions, field = {}, {}, {}, []
    logger.debug("read run %s (series=%s)", path, with_series)
    return RunRecord(
        path, attrs["case_id"], attrs["method"], config, attrs["config_sha256"],
        attrs["code_version"], libraries, float(attrs["wall_time_s"]), attrs["created_utc"],
        series, units, summary, descriptions, str(attrs.get("data_sha256", "")),
        {name: values for name, values, _, _ in field}, {name: units for name, _, units, _ in field},
    )  # fmt: skip


def _read_parts(
    h5: h5py.Group, path: Path, verify: bool, with_series: bool
) -> tuple[dict, dict, dict, dict, dict, list]:
    """The root attributes, the summary and (when asked for, or to verify the content) the series
    and the field."""
    attrs = {key: _attr_value(h5.attrs[key]) for key in (*_ROOT_ATTRS, "data_sha256") if key in h5.attrs}
    if missing := [key for key in _ROOT_ATTRS if key not in attrs]:
        raise CorruptRun(path, f"not a rodimpact run file: missing root attrs {missing}")
    if attrs["schema_version"] != SCHEMA_VERSION:
        raise StoreError(f"{path}: unsupported schema_version {attrs['schema_version']!r}")
    if [key for key in _STR_ATTRS if not isinstance(attrs[key], str)]:
        raise CorruptRun(path, f"root attributes {list(_STR_ATTRS)} must all be str")
    if not isinstance(h5.get("time"), h5py.Dataset):
        raise CorruptRun(path, "missing required dataset 'time'")
    if not isinstance(h5.get(SUMMARY_GROUP), h5py.Group):
        raise CorruptRun(path, f"missing required group '{SUMMARY_GROUP}'")
    summary = {key: _attr_value(value) for key, value in h5[SUMMARY_GROUP].attrs.items()}
    if missing := [key for key in REQUIRED_SUMMARY if key not in summary]:
        raise CorruptRun(path, f"missing required summary attributes {missing}")
    needed = with_series or (verify and bool(attrs.get("data_sha256")))
    series, units, descriptions = _read_series(h5, path) if needed else ({}, {}, {})
    return attrs, summary, series, units, descriptions, read_field(h5, path) if needed else []


def read_run(path: str | Path, *, verify: bool = True) -> RunRecord:
    """Read a run file written by :func:`write_run`, or one run of a file of runs.

    Parameters
    ----------
    path : str or Path
        Run file, or the reference ``"{file}#{name}"`` of a run in a file of runs
        (:func:`run_reference`); the record's ``path`` is what was given.
    verify : bool, default True
        Recompute the SHA-256 of the stored ``config_json`` and compare it with
        ``config_sha256``, check ``case_id`` against ``config["id"]``, and recompute the
        content digest (``data_sha256``: config, method, every series and the summary).

    Returns
    -------
    RunRecord
        Provenance, summary, and all series (float64, shape (n,) or (n, k)).

    Raises
    ------
    FileNotFoundError
        If the file does not exist.
    CorruptRun
        The file is truncated, unreadable or not a run file (or holds no run of the name),
        or its content was changed after it was written (verification fails): it is marked
        out of date.
    StoreError
        The file is a run file of another schema version.
    """
    return _read_record(path, verify=verify, with_series=True)


def read_summary(path: str | Path, *, verify: bool = True) -> RunRecord:
    """:func:`read_run` (same parameters and exceptions) that returns no series.

    The returned :class:`RunRecord` has empty ``series``, ``units`` and ``descriptions``.
    With ``verify`` the series are still read, for the content digest.
    """
    return _read_record(path, verify=verify, with_series=False)
