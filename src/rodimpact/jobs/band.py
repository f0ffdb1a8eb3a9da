"""The film's prediction band: the science behind the ``film_band`` rule.

The film's Young's modulus, Poisson's ratio and thickness are each known only to a range
(their sources': ``config/materials.yaml`` ``ranges``, the film's ``thickness_range_m``).
For each case of one Table 2 reading with a film, the SEM computes the contact time at the
nominal constants and at the 8 corners of the box of the three ranges; the corners' min and max
are the band. Where the contact time is monotone along every axis, its extremes over the box lie
at corners. With ``axes`` (the named target ``make film-axes``, not the default build) it also
computes :data:`AXIS_POINTS` points along each range with the others nominal, the evidence of
that monotonicity (recorded per case).
"""

from __future__ import annotations

import itertools
import logging
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from rodimpact.analysis.sweeps import sweep_point_case
from rodimpact.jobs.runner import run_case
from rodimpact.storage.bands import BAND_PARAMETERS, CaseBand, write_band

__all__ = ["AXIS_POINTS", "case_band", "film_ranges", "band_to_file"]

log = logging.getLogger(__name__)

#: Points along each constant's range (the monotonicity check).
AXIS_POINTS = 5


def film_ranges(case: Mapping[str, Any]) -> dict[str, tuple[float, float]]:
    """The range of each of :data:`~rodimpact.storage.bands.BAND_PARAMETERS` for the case's film
    (a constant without a range in the materials file is fixed at its value)."""
    film = (case.get("contact") or {}).get("film")
    if film is None:
        raise ValueError(f"case {case['id']!r} has no film")
    material, ranges = film["material"], film["material"].get("ranges", {})
    modulus, poisson = material["youngs_modulus_pa"], material["poisson_ratio"]
    return {
        "film_modulus_pa": tuple(ranges.get("youngs_modulus_pa", (modulus, modulus))),
        "film_poisson_ratio": tuple(ranges.get("poisson_ratio", (poisson, poisson))),
        "film_thickness_m": tuple(film["thickness_range_m"]),
    }


def _contact_time_us(case: Mapping[str, Any], point: Mapping[str, float], method: str) -> float:
    return (
        1e6 * run_case(sweep_point_case({**case, "sweep": {"methods": [method]}}, point, "band"), method).contact_time_s
    )


def case_band(case: Mapping[str, Any], method: str = "sem", axes: bool = False) -> CaseBand:
    """The band of one case (see the module docstring); ``axes``: also each constant's range."""
    ranges = film_ranges(case)
    film = case["contact"]["film"]
    nominal = {
        "film_modulus_pa": film["material"]["youngs_modulus_pa"],
        "film_poisson_ratio": film["material"]["poisson_ratio"],
        "film_thickness_m": film["thickness_m"],
    }
    corners = np.array(list(itertools.product(*(ranges[n] for n in BAND_PARAMETERS))), float)
    corner_us = np.array([_contact_time_us(case, dict(zip(BAND_PARAMETERS, c)), method) for c in corners])
    axis_values, axis_us = {}, {}
    for name in BAND_PARAMETERS if axes else ():
        low, high = ranges[name]
        values = np.linspace(low, high, AXIS_POINTS) if high > low else np.array([low])
        axis_values[name] = values
        axis_us[name] = np.array([_contact_time_us(case, {**nominal, name: float(v)}, method) for v in values])
    measured = (case.get("measured") or {}).get("contact_time_us")
    band = CaseBand(
        case_id=str(case["id"]),
        measured_us=math.nan if measured is None else float(measured),
        nominal_us=_contact_time_us(case, nominal, method),
        corner_parameters=corners,
        corner_us=corner_us,
        axis_values=axis_values,
        axis_us=axis_us,
    )
    log.info(
        "case %s: nominal %.2f us, band %.2f-%.2f us, monotone along every axis: %s",
        band.case_id,
        band.nominal_us,
        band.band_min_us,
        band.band_max_us,
        "not computed" if band.monotone is None else band.monotone,
    )
    if band.monotone is False:
        log.warning(
            "case %s: the contact time is not monotone along some constant's range; the corners may not bound it",
            band.case_id,
        )
    return band


def band_to_file(
    cases: Sequence[Mapping[str, Any]], variant: str, path: str, method: str = "sem", axes: bool = False
) -> None:
    """The bands of ``cases`` (one reading), written atomically to ``path``; ``axes``: with each
    constant's range (:func:`case_band`)."""
    write_band(
        path,
        [case_band(case, method, axes) for case in cases],
        variant=variant,
        method=method,
        config=[dict(case) for case in cases],
    )
