"""Prediction bands as HDF5 files: the output of the workflow's ``film_band`` rule.

A band file holds, for the cases of one Table 2 reading with a film, the contact time at the
film's nominal constants, at the corners of the box of their ranges, and along each
constant's range with the others nominal (the evidence that the contact time is monotone in
each, so that the corners bound it). Layout: one group per case (its id), with

- attributes ``measured_us`` (NaN when none), ``nominal_us``, ``band_min_us``,
  ``band_max_us``, ``monotone`` (True when the contact time is monotone along every axis);
- datasets ``corner_parameters`` (8, 3): (film_modulus_pa, film_poisson_ratio,
  film_thickness_m) of each corner, ``corner_us`` (8,); ``axis_values_{name}`` (k,) and
  ``axis_us_{name}`` (k,) for each of the three;

and root attributes ``variant``, ``method``, ``code_version``, ``library_versions``,
``config_json`` (the cases), ``created_utc`` and ``data_sha256`` (checked on read).
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from datetime import datetime, timezone
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
    """The band of one case (see the module docstring for the fields; times in microseconds)."""

    case_id: str
    measured_us: float
    nominal_us: float
    corner_parameters: NDArray[np.float64]
    corner_us: NDArray[np.float64]
    axis_values: dict[str, NDArray[np.float64]]
    axis_us: dict[str, NDArray[np.float64]]

    @property
    def band_min_us(self) -> float:
        return float(np.min(self.corner_us))

    @property
    def band_max_us(self) -> float:
        return float(np.max(self.corner_us))

    @property
    def monotone(self) -> bool:
        """The contact time is monotone along each constant's range (the others nominal)."""
        return all(np.all(np.diff(t) >= 0) or np.all(np.diff(t) <= 0) for t in self.axis_us.values())


def _arrays(band: CaseBand) -> dict[str, NDArray[np.float64]]:
    arrays = {"corner_parameters": np.asarray(band.corner_parameters, float), "corner_us": np.asarray(band.corner_us, float)}
    for name in BAND_PARAMETERS:
        arrays[f"axis_values_{name}"] = np.asarray(band.axis_values[name], float)
        arrays[f"axis_us_{name}"] = np.asarray(band.axis_us[name], float)
    return arrays


def _sha256(bands: list[CaseBand]) -> str:
    digest = hashlib.sha256()
    for band in bands:
        digest.update(band.case_id.encode() + b"\0")
        digest.update(np.asarray([band.measured_us, band.nominal_us], "<f8").tobytes())
        for name, array in sorted(_arrays(band).items()):
            digest.update(name.encode() + np.ascontiguousarray(array, "<f8").tobytes())
    return digest.hexdigest()


def write_band(path: str | Path, bands: list[CaseBand], *, variant: str, method: str,
               config: Any) -> Path:
    """Write the bands of one reading atomically (layout in the module docstring)."""
    path = Path(path)
    with atomic_output(path) as tmp:
        with h5py.File(tmp, "x", track_order=True) as h5:
            h5.attrs.update({
                "variant": variant, "method": method, "code_version": provenance.code_version(),
                "library_versions": provenance.canonical_json(provenance.library_versions()),
                "config_json": provenance.canonical_json(config),
                "created_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                "data_sha256": _sha256(bands),
            })
            for band in bands:
                group = h5.create_group(band.case_id)
                group.attrs.update({"measured_us": band.measured_us, "nominal_us": band.nominal_us,
                                    "band_min_us": band.band_min_us, "band_max_us": band.band_max_us,
                                    "monotone": band.monotone})
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
                axis_values = {n: group[f"axis_values_{n}"][()] for n in BAND_PARAMETERS}
                axis_us = {n: group[f"axis_us_{n}"][()] for n in BAND_PARAMETERS}
                bands.append(CaseBand(case_id, float(group.attrs["measured_us"]), float(group.attrs["nominal_us"]),
                                      group["corner_parameters"][()], group["corner_us"][()], axis_values, axis_us))
    except (OSError, KeyError) as error:
        raise StoredFileError(path, f"not a readable band file ({error})") from None
    if _sha256(bands) != expected:
        raise StoredFileError(path, "the data do not match their data_sha256 (edited or corrupt)")
    return variant, bands
