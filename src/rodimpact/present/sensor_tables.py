"""The table of the sensor as built, from band files and case files only.

:func:`sensor_band_frame`: each row's contact time by the SEM with the law the continuum
calibrates on the stack, at the sourced nominal constants and over their ranges (the band), and
whether the measurement lies inside. :func:`band_axes_frame`: each constant's range, the others
nominal, for any bands computed with their axes (the sensor's, ``make sensor-axes``; the film's,
``make film-axes``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.storage.bands import CaseBand

__all__ = ["CALIBRATED_METHOD", "band_axes_frame", "sensor_band_frame"]

#: How the band's times are computed, in words.
CALIBRATED_METHOD = "SEM with the law of the continuum's indentation"


def _row(case: Mapping[str, Any], case_id: str) -> tuple[str, float]:
    mass = 1000.0 * float(case["impactor"]["mass_kg"]) if case else math.nan
    return str(case.get("row", case_id)), mass


def sensor_band_frame(bands: Sequence[tuple[str, CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """One row per case: ``variant, row, case_id, mass_g, method, measured_us, band_min_us,
    nominal_us, band_max_us, measured_in_band, nominal_error_pct, constants``, and ``monotone``
    where some band has its axes.

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
                "monotone": band.monotone,
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
    if all(band.monotone is None for _, band in bands):
        columns.remove("monotone")
    frame = pd.DataFrame(rows, columns=columns)
    return frame.sort_values(["variant", "mass_g"], kind="stable").reset_index(drop=True)


def _end(high: bool) -> str:
    return "high" if high else "low"


def band_axes_frame(bands: Sequence[tuple[str, CaseBand]], cases: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """One row per case and constant of the bands that have their axes: ``variant, row, case_id,
    mass_g, constant, low, high`` (the constant's range, SI), ``low_us, nominal_us, high_us``
    (the time with the constant at its low end, every constant nominal, the constant at its high
    end), ``monotone`` (along this range), ``continuum_lengthens_at`` (the end, ``high`` or
    ``low``, that lengthens the contact by the band's own model: the sensor's continuum, the
    film's thin-layer law), and, where some band records the direction of the bodies' analytic
    law (the sensor's), ``law_lengthens_at`` and ``agree``. Bands without axes give no row."""
    rows = []
    for variant, band in bands:
        row, mass = _row(cases.get(band.case_id) or {}, band.case_id)
        for index, name in enumerate(band.parameters):
            if name not in band.axis_us:
                continue
            values, times = np.asarray(band.axis_values[name]), np.asarray(band.axis_us[name])
            steps = np.diff(times)
            continuum = bool(times[-1] >= times[0])
            law = band.law_longer_high[index] if band.law_longer_high else None
            rows.append(
                {
                    "variant": variant,
                    "row": row,
                    "case_id": band.case_id,
                    "mass_g": mass,
                    "constant": name,
                    "low": float(values[0]),
                    "high": float(values[-1]),
                    "low_us": float(times[0]),
                    "nominal_us": band.nominal_us,
                    "high_us": float(times[-1]),
                    "monotone": bool(np.all(steps >= 0) or np.all(steps <= 0)),
                    "continuum_lengthens_at": _end(continuum),
                    "law_lengthens_at": None if law is None else _end(law),
                    "agree": None if law is None else bool(law == continuum),
                }
            )
    frame = pd.DataFrame(rows)
    if not any(band.law_longer_high for _, band in bands):
        frame = frame.drop(columns=["law_lengthens_at", "agree"], errors="ignore")
    return frame.sort_values(["variant", "mass_g"], kind="stable").reset_index(drop=True) if rows else frame
