"""Contact-law curves P(alpha) as HDF5 files: the output of the workflow's ``indentation`` rule.

A curve file holds, for one case, the static indentation of its ball (a hemispherical cap
with a rigid back), film and rod by the continuum model, and the force-approach curve the
1-D methods take as their ``tabulated`` contact law. Layout (all lengths m, forces N):

- datasets ``approach_m``, ``force_N``, ``contact_radius_m``, ``displacement_m`` (the rigid
  back's displacement), and where given ``law_approach_m`` (the analytic law's approach at
  the same forces), each shape (n,) with ``units`` and ``description`` attributes;
- where a material of the case yields, the unloading curves: ``unloading_curve`` (each point's
  curve), ``unloading_approach_m``, ``unloading_force_N``, each shape (u,), every curve from
  its largest approach (a point of the loading curve) down to its last point with force and
  beyond; the summary then holds ``elastic_limit_m``;
- root attributes ``case_id``, ``config_json`` (the resolved case), ``config_sha256``,
  ``code_version``, ``library_versions``, ``created_utc``, ``data_sha256`` (of the
  datasets, checked on every read) and the scalar results in ``summary_json``.

The file is written atomically; :func:`read_contact_curve` refuses a file whose data do not
match their hash.
"""

from __future__ import annotations

import hashlib
import json
import logging
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

__all__ = ["CURVE_DATASETS", "UNLOADING_DATASETS", "ContactCurve", "read_contact_curve", "write_contact_curve"]

log = logging.getLogger(__name__)

#: dataset -> (units, description); the first four are required.
CURVE_DATASETS: dict[str, tuple[str, str]] = {
    "approach_m": ("m", "approach alpha of the 1-D law: the rigid back's displacement less the rod's 1-D compliance"),
    "force_N": ("N", "contact force P"),
    "contact_radius_m": ("m", "radius of the contact patch"),
    "displacement_m": ("m", "displacement of the cap's rigid back towards the rod (the far end fixed)"),
    "law_approach_m": ("m", "approach of the case's analytic law (hertz or hertz_film) at the same force"),
}
_REQUIRED = ("approach_m", "force_N", "contact_radius_m", "displacement_m")
#: dataset -> (units, description): the unloading curves of a case whose material yields, all of
#: one length of their own (every curve's points, one after the other); none or all of them.
UNLOADING_DATASETS: dict[str, tuple[str, str]] = {
    "unloading_curve": ("1", "the unloading curve a point belongs to: 0, 1, ... from the smallest largest approach"),
    "unloading_approach_m": ("m", "approach alpha of the 1-D law on the unloading curve, from its maximum down"),
    "unloading_force_N": ("N", "contact force P on the unloading curve"),
}


@dataclass(frozen=True)
class ContactCurve:
    """A force-approach curve and where it comes from.

    Attributes
    ----------
    case_id : str
        The case it was computed for.
    data : dict of str to ndarray
        The datasets of :data:`CURVE_DATASETS`, shape (n,) each.
    summary : dict
        Scalars: the subtracted compliance, the interpolation error, the load range, ...
    config : dict
        The resolved case it was computed from.
    """

    case_id: str
    data: dict[str, NDArray[np.float64]]
    summary: dict[str, Any] = field(default_factory=dict)
    config: dict[str, Any] = field(default_factory=dict)

    def law_curve(self) -> dict[str, Any]:
        """The curve as a ``tabulated`` law reads it (``contact.curve`` of a case); with unloading
        curves, also ``unloading`` (``curve``, ``approach_m``, ``force_N``) and ``elastic_limit_m``
        (the law with memory)."""
        curve: dict[str, Any] = {
            key: [float(x) for x in self.data[key]] for key in ("approach_m", "force_N", "contact_radius_m")
        }
        if "unloading_curve" in self.data:
            curve["unloading"] = {
                key.removeprefix("unloading_"): [float(x) for x in self.data[key]] for key in UNLOADING_DATASETS
            }
            curve["elastic_limit_m"] = float(self.summary["elastic_limit_m"])
        return curve


def _data_sha256(data: Mapping[str, NDArray[np.float64]]) -> str:
    digest = hashlib.sha256()
    for name in sorted(data):
        array = np.ascontiguousarray(data[name], dtype="<f8")
        digest.update(name.encode() + b"\0" + array.tobytes())
    return digest.hexdigest()


def write_contact_curve(path: str | Path, curve: ContactCurve) -> Path:
    """Write ``curve`` to ``path`` atomically (layout in the module docstring).

    Raises
    ------
    ValueError
        A required dataset is missing, or the datasets are not 1-D of one length.
    """
    path = Path(path)
    missing = [name for name in _REQUIRED if name not in curve.data]
    if missing:
        raise ValueError(f"curve: missing datasets {missing}")
    data = {name: np.asarray(values, dtype=float) for name, values in curve.data.items() if name in CURVE_DATASETS}
    lengths = {array.shape for array in data.values()}
    if len(lengths) != 1 or len(next(iter(lengths))) != 1:
        raise ValueError(f"curve: datasets must be 1-D of one length, got shapes {sorted(lengths)}")
    unloading = {name: np.asarray(curve.data[name], dtype=float) for name in UNLOADING_DATASETS if name in curve.data}
    if unloading:
        shapes = {array.shape for array in unloading.values()}
        if len(unloading) != len(UNLOADING_DATASETS) or len(shapes) != 1 or len(next(iter(shapes))) != 1:
            raise ValueError(f"curve: the unloading datasets must all be given, 1-D of one length: {sorted(shapes)}")
        if "elastic_limit_m" not in curve.summary:
            raise ValueError("curve: unloading curves need the elastic limit (summary elastic_limit_m)")
        data.update(unloading)
    names = {**CURVE_DATASETS, **UNLOADING_DATASETS}
    config_json = provenance.canonical_json(curve.config)
    attrs = {
        "case_id": curve.case_id,
        "config_json": config_json,
        "config_sha256": hashlib.sha256(config_json.encode()).hexdigest(),
        "code_version": provenance.code_version(),
        "library_versions": provenance.canonical_json(provenance.library_versions()),
        "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "summary_json": json.dumps(curve.summary, sort_keys=True),
        "data_sha256": _data_sha256(data),
    }
    with atomic_output(path) as tmp:
        with h5py.File(tmp, "x", track_order=True) as h5:
            h5.attrs.update(attrs)
            for name, array in data.items():
                dataset = h5.create_dataset(name, data=array)
                units, description = names[name]
                dataset.attrs.update({"units": units, "description": description})
    log.info("wrote the contact curve of %s (%d points) to %s", curve.case_id, len(data["force_N"]), path)
    return path


def read_contact_curve(path: str | Path) -> ContactCurve:
    """Read a curve file and check its data against their hash.

    Raises
    ------
    StoredFileError
        The file cannot be read, misses a dataset, or its data do not match ``data_sha256``.
    """
    try:
        with h5py.File(path, "r") as h5:
            attrs = {key: h5.attrs[key] for key in ("case_id", "config_json", "summary_json", "data_sha256")}
            data = {
                name: np.asarray(h5[name][()], dtype=float)
                for name in (*CURVE_DATASETS, *UNLOADING_DATASETS)
                if name in h5
            }
    except (OSError, KeyError) as error:
        raise StoredFileError(path, f"not a readable contact-curve file ({error})") from None
    missing = [name for name in _REQUIRED if name not in data]
    if missing:
        raise StoredFileError(path, f"missing datasets {missing}")
    if _data_sha256(data) != attrs["data_sha256"]:
        raise StoredFileError(path, "the data do not match their data_sha256 (edited or corrupt)")
    return ContactCurve(
        case_id=str(attrs["case_id"]),
        data=data,
        summary=json.loads(attrs["summary_json"]),
        config=json.loads(attrs["config_json"]),
    )
