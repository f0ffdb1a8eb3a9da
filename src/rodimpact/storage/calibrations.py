"""A calibration as an HDF5 file: the output of the workflow's ``calibrate`` rule, which its
table and figure read.

Layout: root attributes ``set``, ``method``, ``status``, ``message``, ``success``,
``identifiable``, ``warnings_json``, ``evaluations``, ``dof``, ``s2``, ``condition_number``,
``parameters_json`` (each constant's path, unit, source and grid, empty without one),
``observations_json`` (each measurement's case id, quantity, unit and whether it is an error norm:
ids and units, no words), ``loo_json`` (the
held-out cases and their statuses, each row's status), ``applied_json`` (each measurement of
the cases predicted at the fitted constants, as ``observations_json``), the provenance
(``code_version``, ``library_versions``, ``config_json``: the block and the cases,
``created_utc``) and ``data_sha256`` over every dataset (checked on read); datasets:

- per constant (p,): ``low``, ``high``, ``start``, ``values``, ``standard_errors``, ``at_bound``;
  ``covariance``, ``correlation`` (p, p);
- per measurement (n,): ``measured``, ``scale``, ``start_predicted`` (the model at the
  start), ``predicted``, ``residuals``, ``held_out_predicted``, ``held_out_error_pct``,
  ``in_sample_error_pct``;
- per applied measurement (a,), empty without any: ``applied_measured``,
  ``applied_start_predicted``, ``applied_predicted``, ``applied_standard_errors``,
  ``applied_error_pct``;
- per held-out case (k, p): ``loo_values``.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import h5py
import numpy as np
from numpy.typing import NDArray

from rodimpact.storage import provenance
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.faults import StoredFileError

__all__ = ["StoredCalibration", "read_calibration", "write_calibration"]

#: The scalar attributes a calibration file holds besides its JSON ones and its provenance.
_SCALARS = (
    "set",
    "method",
    "status",
    "message",
    "success",
    "identifiable",
    "evaluations",
    "dof",
    "s2",
    "condition_number",
)
#: Its JSON attributes.
_JSON = ("warnings", "parameters", "observations", "loo", "applied")


@dataclass(frozen=True)
class StoredCalibration:
    """A calibration as stored (module docstring): ``scalars`` by name, ``described`` the JSON
    attributes by name (without ``_json``), ``arrays`` the datasets by name, and, as read, the
    ``config`` it was made from (the block and the cases: ``config_json``)."""

    scalars: Mapping[str, Any]
    described: Mapping[str, Any]
    arrays: Mapping[str, NDArray[Any]]
    config: Mapping[str, Any] = field(default_factory=dict)


def _sha256(scalars: Mapping[str, Any], described: Mapping[str, Any], arrays: Mapping[str, NDArray[Any]]) -> str:
    # plain json.dumps, not canonical_json: a calibration's s2 is NaN when n = p
    text = json.dumps({"scalars": dict(scalars), "described": dict(described)}, sort_keys=True)
    digest = hashlib.sha256(text.encode())
    for name, array in sorted(arrays.items()):
        digest.update(name.encode() + b"\0" + np.ascontiguousarray(array, "<f8").tobytes())
    return digest.hexdigest()


def _plain(value: Any) -> Any:
    if isinstance(value, np.generic):
        return value.item()
    return value


def write_calibration(path: str | Path, calibration: StoredCalibration, *, config: Any) -> Path:
    """Write a calibration atomically (layout in the module docstring).

    Parameters
    ----------
    path : path
        The file.
    calibration : StoredCalibration
        Its scalars (every name of the layout), its described attributes and its datasets.
    config : any
        The block and the cases it was made from (stored as ``config_json``).
    """
    path = Path(path)
    scalars = {name: _plain(calibration.scalars[name]) for name in _SCALARS}
    described = {name: calibration.described[name] for name in _JSON}
    arrays = {name: np.asarray(array, float) for name, array in calibration.arrays.items()}
    with atomic_output(path) as tmp, h5py.File(tmp, "x", track_order=True) as h5:
        h5.attrs.update(scalars)
        h5.attrs.update({f"{name}_json": json.dumps(value) for name, value in described.items()})
        h5.attrs.update(
            {
                "code_version": provenance.code_version(),
                "library_versions": provenance.canonical_json(provenance.library_versions()),
                "config_json": provenance.canonical_json(config),
                "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
                "data_sha256": _sha256(scalars, described, arrays),
            }
        )
        for name, array in arrays.items():
            h5.create_dataset(name, data=array)
    return path


def read_calibration(path: str | Path) -> StoredCalibration:
    """A calibration file, checked against its hash.

    Raises
    ------
    StoredFileError
        The file cannot be read, or its data do not match ``data_sha256``.
    """
    try:
        with h5py.File(path, "r") as h5:
            scalars = {name: _plain(h5.attrs[name]) for name in _SCALARS}
            scalars = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in scalars.items()}
            described = {name: json.loads(str(h5.attrs[f"{name}_json"])) for name in _JSON}
            arrays = {name: dataset[()] for name, dataset in h5.items()}
            expected = str(h5.attrs["data_sha256"])
            config = json.loads(str(h5.attrs["config_json"]))
    except (OSError, KeyError, ValueError) as error:
        raise StoredFileError(path, f"not a readable calibration file ({error})") from None
    if _sha256(scalars, described, arrays) != expected:
        raise StoredFileError(path, "the data do not match their data_sha256 (edited or corrupt)")
    return StoredCalibration(scalars, described, arrays, config)
