"""The table of the sensor as built, from band files and case files only.

:func:`sensor_band_frame`: each row's contact time by the SEM with the law the continuum
calibrates on the stack, at the sourced nominal constants and over their ranges (the band), and
whether the measurement lies inside.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import pandas as pd

from rodimpact.storage.bands import CaseBand

__all__ = ["CALIBRATED_METHOD", "sensor_band_frame"]

#: How the band's times are computed, in words.
CALIBRATED_METHOD = "SEM with the law of the continuum's indentation"


def _row(case: Mapping[str, Any], case_id: str) -> tuple[str, float]:
    mass = 1000.0 * float(case["impactor"]["mass_kg"]) if case else math.nan
    return str(case.get("row", case_id)), mass


def sensor_band_frame(bands: Sequence[tuple[str, CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """One row per case: ``variant, row, case_id, mass_g, method, measured_us, band_min_us,
    nominal_us, band_max_us, measured_in_band, nominal_error_pct, monotone, constants``.

    Parameters
    ----------
    bands : sequence of (variant, CaseBand)
        The band of each case (``read_band`` of each ``sensor_band`` file).
    cases : mapping
        Case id -> resolved case (row and mass).
    """
    rows = []
    for variant, band in bands:
        row, mass = _row(cases.get(band.case_id) or {}, band.case_id)
        measured = band.measured_us
        rows.append(
            {
                "variant": variant,
                "row": row,
                "case_id": band.case_id,
                "mass_g": mass,
                "method": CALIBRATED_METHOD,
                "measured_us": measured,
                "band_min_us": band.band_min_us,
                "nominal_us": band.nominal_us,
                "band_max_us": band.band_max_us,
                "measured_in_band": bool(math.isfinite(measured) and band.band_min_us <= measured <= band.band_max_us),
                "nominal_error_pct": (band.nominal_us - measured) / measured * 100.0,
                "monotone": bool(band.monotone),
                "constants": len(band.parameters),
            }
        )
    columns = [
        "variant",
        "row",
        "case_id",
        "mass_g",
        "method",
        "measured_us",
        "band_min_us",
        "nominal_us",
        "band_max_us",
        "measured_in_band",
        "nominal_error_pct",
        "monotone",
        "constants",
    ]
    frame = pd.DataFrame(rows, columns=columns)
    return frame.sort_values(["variant", "mass_g"], kind="stable").reset_index(drop=True)
