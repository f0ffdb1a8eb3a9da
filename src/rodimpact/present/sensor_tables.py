"""Tables of the sensor as built, from band files and case files only.

- :func:`sensor_band_frame`: each row's contact time by the SEM with the law the continuum
  calibrates on the stack, at the sourced nominal constants and over their ranges (the band),
  and whether the measurement lies inside;
- :func:`sensor_fit_frame`: the inverse analysis, labelled as a fit: one layer's thickness
  fitted by least squares to the measured times of a reading (relative errors), the
  leave-one-out predictions, and the fitted value applied to other readings
  (:mod:`rodimpact.analysis.inverse`).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.inverse import fit_theta, leave_one_out, predict_at
from rodimpact.storage.bands import CaseBand

__all__ = ["CALIBRATED_METHOD", "sensor_band_frame", "sensor_fit_frame", "thickness_parameter"]

log = logging.getLogger(__name__)

#: How the band's and the fit's times are computed, in words.
CALIBRATED_METHOD = "SEM with the law of the continuum's indentation"


def thickness_parameter(layer: str) -> str:
    """The band's name of a layer's thickness (``jobs.sensor_band.stack_parameters``)."""
    return f"{layer}: thickness_m"


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


def _grid(bands: Sequence[CaseBand], parameter: str) -> tuple[np.ndarray, np.ndarray]:
    """The common grid of ``parameter`` and each band's times along it, shape (k,) and (n, k)."""
    for band in bands:
        if parameter not in band.parameters:
            raise ValueError(f"band of {band.case_id!r}: no constant {parameter!r}; it has {list(band.parameters)}")
    grid = np.asarray(bands[0].axis_values[parameter], float)
    for band in bands[1:]:
        if not np.array_equal(np.asarray(band.axis_values[parameter], float), grid):
            raise ValueError(f"band of {band.case_id!r}: its grid of {parameter!r} differs from {bands[0].case_id!r}'s")
    return grid, np.vstack([np.asarray(b.axis_us[parameter], float) for b in bands])


def sensor_fit_frame(
    fitted: Sequence[CaseBand],
    applied: Sequence[CaseBand],
    cases: Mapping[str, Mapping[str, Any]],
    layer: str,
    variants: Mapping[str, str],
) -> tuple[pd.DataFrame, dict[str, Any]]:
    """The fit of ``layer``'s thickness to the measured times of the ``fitted`` cases.

    Parameters
    ----------
    fitted, applied : sequence of CaseBand
        Bands (with the layer's thickness grid) of the reading fitted, and of the readings the
        fitted value is applied to.
    cases : mapping
        Case id -> resolved case (row, mass, the layer's sourced range).
    layer : str
        The layer's name.
    variants : mapping
        Case id -> its reading.

    Returns
    -------
    frame : DataFrame
        One row per case: ``variant, role`` (fitted, applied), ``row, case_id, mass_g,
        measured_us, nominal_us`` (the sourced stack), ``fitted_us`` (the fitted stack),
        ``held_out_us`` (fitted on the other rows; fitted reading only), and their errors.
    summary : dict
        ``layer, fitted_thickness_um, standard_error_um, source_low_um, source_high_um,
        inside_source_range, success, status, residual_rms_pct, loo_mean_abs_error_pct, rows``.
    """
    parameter = thickness_parameter(layer)
    if not fitted:
        raise ValueError("fitted: no band of the reading to fit")
    grid, predicted = _grid(fitted, parameter)
    measured = np.array([b.measured_us for b in fitted])
    layer_of = next(item for item in cases[fitted[0].case_id]["contact"]["stack"]["layers"] if item["name"] == layer)
    source_range = tuple(map(float, layer_of["thickness_range_m"]))
    fit = fit_theta(grid, predicted, measured, source_range=source_range)
    loo = leave_one_out(grid, predicted, measured, source_range=source_range)
    rows = []
    for i, band in enumerate(fitted):
        row, mass = _row(cases.get(band.case_id) or {}, band.case_id)
        rows.append(
            {
                "variant": variants.get(band.case_id, ""),
                "role": "fitted",
                "row": row,
                "case_id": band.case_id,
                "mass_g": mass,
                "measured_us": band.measured_us,
                "nominal_us": band.nominal_us,
                "fitted_us": float(fit.predicted[i]),
                "held_out_us": float(loo.held_out_predicted[i]),
            }
        )
    if applied:
        applied_grid, applied_times = _grid(applied, parameter)
        at_fit = predict_at(applied_grid, applied_times, fit.theta)
        for i, band in enumerate(applied):
            row, mass = _row(cases.get(band.case_id) or {}, band.case_id)
            rows.append(
                {
                    "variant": variants.get(band.case_id, ""),
                    "role": "applied",
                    "row": row,
                    "case_id": band.case_id,
                    "mass_g": mass,
                    "measured_us": band.measured_us,
                    "nominal_us": band.nominal_us,
                    "fitted_us": float(at_fit[i]),
                    "held_out_us": math.nan,
                }
            )
    frame = pd.DataFrame(rows)
    for column in ("nominal", "fitted", "held_out"):
        frame[f"{column}_error_pct"] = (frame[f"{column}_us"] - frame["measured_us"]) / frame["measured_us"] * 100.0
    summary = {
        "layer": layer,
        "fitted_thickness_um": 1e6 * fit.theta,
        "standard_error_um": 1e6 * fit.standard_error,
        "source_low_um": 1e6 * source_range[0],
        "source_high_um": 1e6 * source_range[1],
        "inside_source_range": bool(fit.inside_range),
        "success": bool(fit.success),
        "status": fit.status,
        "residual_rms_pct": 100.0 * fit.residual_rms,
        "loo_mean_abs_error_pct": float(loo.mean_abs_error_pct),
        "rows": len(fitted),
    }
    log.info(
        "fit of %s's thickness: %.2f +/- %.2f um (source %.0f-%.0f um, inside: %s), rms %.2f %%, "
        "leave-one-out mean |error| %.2f %%",
        layer,
        summary["fitted_thickness_um"],
        summary["standard_error_um"],
        summary["source_low_um"],
        summary["source_high_um"],
        summary["inside_source_range"],
        summary["residual_rms_pct"],
        summary["loo_mean_abs_error_pct"],
    )
    return frame, summary
