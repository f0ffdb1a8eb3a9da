"""The axial strain over the whole rod against time (output ``strain_field``): its grid.

A case that lists the output ``strain_field`` has every method that can (the registry's
:attr:`~rodimpact.solvers.registry.Method.records_field`) record the strain du/dx on a
subsampled grid of the rod: :class:`FieldGrid`'s cross-sections, evenly spaced from the
struck end (x = 0) to the far end (x = l), at evenly spaced times from the first contact on.
The grid is the same for every method of the case, so that their fields compare sample by
sample. It covers the contact and ``round_trips_after`` wave round trips 2 l / a after the
last contact ends (a run that stopped at a limit: up to its end), so that the waves the
contact left in the rod reach both ends and come back.

``sem`` records it through d'Alembert's solution driven by its contact force (exact for
that force, at any time and place), ``fem1d`` from its bar's displacements. ``sem_paper``
does not: its field would be the same construction from its own, first-order, force.
``fem_axi`` does not: its strain varies over a cross-section, which a field over x alone
does not hold. Those methods skip the output (their runs store no field).

The settings are declared once here (:func:`~rodimpact.solvers.options.setting`); the case
schema's ``field_grid`` is generated from them (:func:`rodimpact.config.load.registry_schema`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from rodimpact.solvers.options import Options, setting

__all__ = ["FIELD_OUTPUT", "FieldGrid", "field_datasets"]

#: The output (a case's ``outputs``) that asks for the field.
FIELD_OUTPUT = "strain_field"


@dataclass(frozen=True)
class FieldGrid(Options):
    """Where and when the strain field over the rod is recorded (output ``strain_field``)."""

    DESCRIPTION: ClassVar[str] = (
        "The grid of the output strain_field (the axial strain over the whole rod against time), the same for "
        "every method of the case; used only by a case that lists that output."
    )

    sections: int = setting(
        41,
        "Cross-sections where the strain is recorded, evenly spaced from the struck end (x = 0) to the far "
        "end (x = l), both included.",
        kind=int,
        minimum=2,
        maximum=1001,
    )
    samples_per_transit: int = setting(
        40,
        "Time samples per wave transit l / a of the rod (a = sqrt(E / rho), the bar wave speed), evenly "
        "spaced from the first contact on.",
        kind=int,
        minimum=2,
        maximum=1000,
    )
    round_trips_after: float = setting(
        1.0,
        "Time the field covers after the last contact ends, in wave round trips 2 l / a (at least one: the "
        "waves the contact leaves reach both ends and return to the struck end).",
        minimum=1,
        maximum=100,
    )

    def positions(self, length_m: float) -> NDArray[np.float64]:
        """The cross-sections, m from the struck end, shape (sections,)."""
        if not (math.isfinite(length_m) and length_m > 0):
            raise ValueError(f"the strain field needs a rod of finite length, got {length_m!r} m")
        return np.linspace(0.0, length_m, self.sections)

    def sample_step(self, transit_s: float) -> float:
        """The time between samples, s: the transit l / a over ``samples_per_transit``."""
        return transit_s / self.samples_per_transit

    def times(
        self, transit_s: float, status: str, contact_end_s: Sequence[float], run_end_s: float
    ) -> NDArray[np.float64]:
        """The sample times, s, shape (m,): multiples of :meth:`sample_step` from 0.

        A completed run (no further contact possible) is sampled to the last contact's end
        plus ``round_trips_after`` round trips 2 l / a (the last sample at or just after it;
        the solver computes the rod's free motion that far). A run stopped at a limit is
        sampled to its last time ``run_end_s`` (what comes after is not computed).
        """
        step = self.sample_step(transit_s)
        if status == "completed" and len(contact_end_s):
            count = math.ceil((float(contact_end_s[-1]) + self.round_trips_after * 2.0 * transit_s) / step)
        else:
            count = math.floor(run_end_s / step)
        return step * np.arange(max(count, 1) + 1, dtype=float)


def field_datasets(
    times: NDArray[np.float64], positions: NDArray[np.float64], strain: NDArray[np.float64], source: str
) -> dict[str, tuple[NDArray[np.float64], str, str]]:
    """The field as a run stores it: name -> (array, units, description).

    Parameters
    ----------
    times : ndarray, shape (m,)
        Sample times, s.
    positions : ndarray, shape (k,)
        Cross-sections, m from the struck end.
    strain : ndarray, shape (m, k)
        Axial strain du/dx (negative in compression).
    source : str
        How the method obtains it, for the description (e.g. "d'Alembert, from the contact force").
    """
    strain = np.asarray(strain, dtype=float)
    if strain.shape != (len(times), len(positions)):
        raise ValueError(f"strain field of shape {strain.shape}, expected ({len(times)}, {len(positions)})")
    return {
        "time": (np.asarray(times, dtype=float), "s", "time since first contact"),
        "x": (np.asarray(positions, dtype=float), "m", "distance of the cross-section from the struck end"),
        "strain": (strain, "1", f"axial strain du/dx over the rod (negative in compression; {source})"),
    }
