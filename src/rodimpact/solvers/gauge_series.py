"""What the strain gauges and the far end read (outputs ``gauge_strain``, ``far_end_velocity``).

A case that lists the output ``gauge_strain`` has every method record the strain at its
gauges (:class:`~rodimpact.model.gauges.Gauge`, the case's ``gauges``), and one that lists
``far_end_velocity`` the velocity of the rod's far end x = L along the rod. Each method
computes them from its own solution (the drivers' ``gauges`` and ``far_end_velocity``
arguments); this module holds what they share: which gauges a case asks for, and the
datasets they store.

Datasets (:data:`~rodimpact.solvers.result.OUTPUT_DATASETS`): ``gauge_strain`` (n, k), the
mean axial strain over each gauge (dimensionless, negative in compression), with the gauges'
centres and lengths in the summary's ``gauge_x_m`` and ``gauge_length_m`` (k,); ``fem_axi``
reads it at the rod's surface and adds ``gauge_mean_strain`` (n, k), the same over the
cross-section's mean axial displacement. ``far_end_velocity`` (n,), m/s, positive away from
the struck end (zero at a fixed far end).

A run that records either goes on after its last contact ends until every wave that contact
sent has passed the farthest section it records (:func:`recorded_reach_m`,
:func:`record_until_s`); the time it had to reach is the summary's ``recorded_until_s``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.model.gauges import Gauge

__all__ = [
    "FAR_END_OUTPUT",
    "GAUGE_OUTPUT",
    "RECORD_CONTACT_MARGIN",
    "RECORD_TRANSIT_MARGIN",
    "case_gauges",
    "checked_gauges",
    "far_end_datasets",
    "gauge_datasets",
    "record_until_s",
    "recorded_reach_m",
]

#: The output (a case's ``outputs``) that asks for the gauges' strain.
GAUGE_OUTPUT = "gauge_strain"
#: The output that asks for the far end's velocity.
FAR_END_OUTPUT = "far_end_velocity"

#: A run that records gauges or the far end's velocity goes on after its last contact ends for
#: the bar-speed transit x/c to the farthest section it records, lengthened by this fraction of
#: it, plus :data:`RECORD_CONTACT_MARGIN` of the time from the impact to that end
#: (:func:`record_until_s`). At the bar speed c = sqrt(E/rho) the last of the force reaches x
#: exactly x/c after it left in the SEM; the other methods' pulses trail a little: fem1d's
#: discrete bar and Newmark's rule slow its short waves, and fem_axi's continuum carries the
#: 3-D (Pochhammer-Chree) dispersion, whose waves as short as the rod's diameter travel below c
#: (its dilatational waves are faster, but the bar speed is the slowest front that matters for
#: the pulse's end). Measured (a 10 mm steel ball at 1 m/s on a fixed steel rod of radius 5 mm,
#: contact 35 us), the last time the strain exceeds 1 % of its peak, after t_end + x/c in units
#: of x/c: fem1d at 0.25 m, -1.4 % at its default resolution, +3.5 % at the warning threshold
#: (10 nodes per wavelength, 100 steps per contact); fem_axi (5 and 8 elements across, 100 and
#: 200 steps per contact), its surface strain, before it at 0.05 and 0.1 m and up to +5.1 % at
#: 0.2 m (40 diameters), its mean strain up to +5.5 % there and +8.3 % at 0.1 m on the coarser
#: mesh. With the contact's margin the two give 6.8 % of the transit at 0.2 m and 8.6 % at 0.1 m.
RECORD_TRANSIT_MARGIN = 0.05
#: ... plus this fraction of the time from the impact to the last contact's end (for one contact,
#: its contact time): the methods place a contact's end differently within a step (fem1d at the
#: root of the approach's Hermite interpolant, fem_axi by extrapolating P^(2/3) within its step of
#: about 1/100 of the contact, after nodes that leave the contact one at a time), and the record
#: ends at the first node beyond; 2 % is 2 of fem_axi's steps at 100 steps per contact (40 of
#: fem1d's default 2000), and keeps a margin of a few steps for a gauge so near the struck end
#: that 5 % of its transit is less than a step.
RECORD_CONTACT_MARGIN = 0.02


def case_gauges(case: Mapping[str, Any]) -> tuple[Gauge, ...]:
    """The gauges a resolved case asks for: its ``gauges`` (a list of ``{station_m,
    gauge_length_m}``) when its ``outputs`` list ``gauge_strain``, else none.

    Raises
    ------
    rodimpact.model.gauges.GaugeError
        A gauge's mapping is malformed (its key in ``field``).
    """
    if GAUGE_OUTPUT not in case.get("outputs", ()):
        return ()
    return tuple(Gauge.from_settings(gauge) for gauge in case.get("gauges", ()))


def checked_gauges(gauges: Sequence[Gauge], rod_length_m: float) -> tuple[Gauge, ...]:
    """The gauges, each checked to lie on a rod of length ``rod_length_m`` (m).

    Raises
    ------
    rodimpact.model.gauges.GaugeError
        A gauge is off the rod (its setting in ``field``).
    """
    return tuple(gauge.check(rod_length_m) for gauge in gauges)


def gauge_datasets(
    gauges: Sequence[Gauge],
    strain: NDArray[np.float64],
    how: str,
    mean_strain: NDArray[np.float64] | None = None,
) -> tuple[dict[str, tuple[NDArray[np.float64], str, str]], dict[str, NDArray[np.float64]]]:
    """The gauges' extra series and summary entries.

    Parameters
    ----------
    gauges : sequence of Gauge
        The k gauges.
    strain : ndarray, shape (n, k)
        The mean axial strain over each gauge at the run's n nodes (a point gauge: du/dx).
    how : str
        How the method computed it, for the dataset's description.
    mean_strain : ndarray, shape (n, k), optional
        The same over the cross-section's mean axial displacement, when ``strain`` is read
        at the surface (``fem_axi``): stored as ``gauge_mean_strain``.

    Returns
    -------
    series : dict
        ``gauge_strain`` (and ``gauge_mean_strain``): (array, units, description).
    summary : dict
        ``gauge_x_m`` and ``gauge_length_m``, shape (k,), m.
    """
    series = {
        "gauge_strain": (
            np.asarray(strain, dtype=float),
            "1",
            f"mean axial strain over each gauge (gauge_x_m, gauge_length_m; negative in compression; {how})",
        )
    }
    if mean_strain is not None:
        series["gauge_mean_strain"] = (
            np.asarray(mean_strain, dtype=float),
            "1",
            "mean axial strain over each gauge of the cross-section mean axial displacement (negative in compression)",
        )
    summary = {
        "gauge_x_m": np.asarray([gauge.station_m for gauge in gauges], dtype=float),
        "gauge_length_m": np.asarray([gauge.gauge_length_m for gauge in gauges], dtype=float),
    }
    return series, summary


def far_end_datasets(velocity: NDArray[np.float64], how: str) -> dict[str, tuple[NDArray[np.float64], str, str]]:
    """The far end's velocity as an extra series, shape (n,), m/s; ``how`` says how it was computed."""
    return {
        "far_end_velocity": (
            np.asarray(velocity, dtype=float),
            "m/s",
            f"axial velocity of the rod's far end x = L, positive away from the struck end ({how})",
        )
    }


def recorded_reach_m(gauges: Sequence[Gauge], far_end_velocity: bool, rod_length_m: float) -> float | None:
    """The farthest section a run records, m from the struck end: the far end L for its
    velocity, else the far end x + g/2 of its farthest gauge; None when it records neither."""
    if far_end_velocity:
        return float(rod_length_m)
    if not gauges:
        return None
    return max(gauge.ends()[1] for gauge in gauges)


def record_until_s(last_end_s: float, reach_m: float, wave_speed_m_s: float) -> float:
    """The time a run that records up to ``reach_m`` (:func:`recorded_reach_m`) must reach, s:
    its last contact's end ``last_end_s`` (s from the impact) plus the bar-speed transit to that
    section, with the margins :data:`RECORD_TRANSIT_MARGIN` and :data:`RECORD_CONTACT_MARGIN`.

        t_rec = (1 + RECORD_CONTACT_MARGIN) t_end + (1 + RECORD_TRANSIT_MARGIN) reach / c
    """
    transit = reach_m / wave_speed_m_s
    return (1.0 + RECORD_CONTACT_MARGIN) * last_end_s + (1.0 + RECORD_TRANSIT_MARGIN) * transit
