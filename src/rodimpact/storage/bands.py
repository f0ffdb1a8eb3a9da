"""Prediction bands as HDF5 files: the outputs of the workflow's ``film_band`` and ``sensor_band`` rules.

A band file holds, for one or more cases, the contact time at the nominal constants, at
corners of the box of their ranges, and, where computed, along each constant's range with the
others nominal (the evidence that the contact time is monotone in each, so that the corners
bound it). Layout: one group per case (its id), with

- attributes ``measured_us`` (NaN when none), ``nominal_us``, ``band_min_us``,
  ``band_max_us``, ``monotone`` (True when the contact time is monotone along every axis; absent
  without axes), ``parameters_json`` (the constants' names, in the order of
  ``corner_parameters``' columns), ``law_longer_high_json`` (per constant, whether its high end
  lengthens the contact by the analytic law of the case's bodies; empty when not computed);
- datasets ``corner_parameters`` (k, p): the constants of each corner (the film band's eight
  corners of (film_modulus_pa, film_poisson_ratio, film_thickness_m); the sensor band's two),
  ``corner_us`` (k,); ``axis_values_{i}`` (j,) and ``axis_us_{i}`` (j,) for each constant i
  whose axis was computed;

and root attributes ``variant``, ``method``, ``code_version``, ``library_versions``,
``config_json`` (the cases), ``created_utc`` and ``data_sha256`` (checked on read).
"""

from __future__ import annotations

import hashlib
import json
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

__all__ = ["BAND_PARAMETERS", "CaseBand", "read_band", "write_band"]

#: The film's constants a band spans, in the order of ``corner_parameters``' columns.
BAND_PARAMETERS = ("film_modulus_pa", "film_poisson_ratio", "film_thickness_m")


@dataclass(frozen=True)
class CaseBand:
    """The band of one case (see the module docstring for the fields; times in microseconds).
    ``parameters`` names the constants (the film band's :data:`BAND_PARAMETERS` by default);
    ``axis_values`` and ``axis_us`` may be empty (the axes not computed), and
    ``law_longer_high`` is empty or has an entry per constant."""

    case_id: str
    measured_us: float
    nominal_us: float
    corner_parameters: NDArray[np.float64]
    corner_us: NDArray[np.float64]
    axis_values: dict[str, NDArray[np.float64]]
    axis_us: dict[str, NDArray[np.float64]]
    parameters: tuple[str, ...] = field(default=BAND_PARAMETERS)
    law_longer_high: tuple[bool, ...] = ()

    @property
    def band_min_us(self) -> float:
        """The least corner's time, us."""
        return float(np.min(self.corner_us))

    @property
    def band_max_us(self) -> float:
        """The greatest corner's time, us."""
        return float(np.max(self.corner_us))

    @property
    def monotone(self) -> bool | None:
        """The contact time is monotone along each constant's range (the others nominal); None
        when the axes were not computed."""
        if not self.axis_us:
            return None
        return all(np.all(np.diff(t) >= 0) or np.all(np.diff(t) <= 0) for t in self.axis_us.values())


def _arrays(band: CaseBand) -> dict[str, NDArray[np.float64]]:
    arrays = {
        "corner_parameters": np.asarray(band.corner_parameters, float),
        "corner_us": np.asarray(band.corner_us, float),
    }
    for index, name in enumerate(band.parameters):
        if name in band.axis_us:
            arrays[f"axis_values_{index}"] = np.asarray(band.axis_values[name], float)
            arrays[f"axis_us_{index}"] = np.asarray(band.axis_us[name], float)
    return arrays


def _sha256(bands: list[CaseBand]) -> str:
    digest = hashlib.sha256()
    for band in bands:
        digest.update(band.case_id.encode() + b"\0" + json.dumps(list(band.parameters)).encode())
        if band.law_longer_high:  # (a band without it hashes as before)
            digest.update(json.dumps(list(band.law_longer_high)).encode())
        digest.update(np.asarray([band.measured_us, band.nominal_us], "<f8").tobytes())
        for name, array in sorted(_arrays(band).items()):
            digest.update(name.encode() + np.ascontiguousarray(array, "<f8").tobytes())
    return digest.hexdigest()


def write_band(path: str | Path, bands: list[CaseBand], *, variant: str, method: str, config: Any) -> Path:
    """Write the bands of one reading atomically (layout in the module docstring)."""
    path = Path(path)
    with atomic_output(path) as tmp:
        with h5py.File(tmp, "x", track_order=True) as h5:
            h5.attrs.update(
                {
                    "variant": variant,
                    "method": method,
                    "code_version": provenance.code_version(),
                    "library_versions": provenance.canonical_json(provenance.library_versions()),
                    "config_json": provenance.canonical_json(config),
                    "created_utc": datetime.now(UTC).isoformat(timespec="seconds"),
                    "data_sha256": _sha256(bands),
                }
            )
            for band in bands:
                group = h5.create_group(band.case_id)
                group.attrs.update(
                    {
                        "measured_us": band.measured_us,
                        "nominal_us": band.nominal_us,
                        "band_min_us": band.band_min_us,
                        "band_max_us": band.band_max_us,
                        "parameters_json": json.dumps(list(band.parameters)),
                        "law_longer_high_json": json.dumps(list(band.law_longer_high)),
                    }
                )
                if band.monotone is not None:
                    group.attrs["monotone"] = band.monotone
                for name, array in _arrays(band).items():
                    group.create_dataset(name, data=array)
    return path


def read_band(path: str | Path) -> tuple[str, list[CaseBand]]:
    """The variant and the bands of a band file, checked against its hash.

    Raises
    ------
    StoredFileError
        The file cannot be read, or its data do not match ``data_sha256``.
    """
    try:
        with h5py.File(path, "r") as h5:
            variant, expected = str(h5.attrs["variant"]), str(h5.attrs["data_sha256"])
            bands = []
            for case_id, group in h5.items():
                names = tuple(json.loads(str(group.attrs["parameters_json"])))
                axis_values = {n: group[f"axis_values_{i}"][()] for i, n in enumerate(names) if f"axis_us_{i}" in group}
                axis_us = {n: group[f"axis_us_{i}"][()] for i, n in enumerate(names) if f"axis_us_{i}" in group}
                longer = tuple(json.loads(str(group.attrs.get("law_longer_high_json", "[]"))))
                bands.append(
                    CaseBand(
                        case_id,
                        float(group.attrs["measured_us"]),
                        float(group.attrs["nominal_us"]),
                        group["corner_parameters"][()],
                        group["corner_us"][()],
                        axis_values,
                        axis_us,
                        names,
                        longer,
                    )
                )
    except (OSError, KeyError) as error:
        raise StoredFileError(path, f"not a readable band file ({error})") from None
    if _sha256(bands) != expected:
        raise StoredFileError(path, "the data do not match their data_sha256 (edited or corrupt)")
    return variant, bands
