"""The result every solver returns (:class:`ImpactResult`) and the histories it can store."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from dataclasses import field as dataclass_field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.solvers.field import FIELD_OUTPUT

__all__ = ["ImpactResult", "OUTPUT_DATASETS", "SERIES"]

#: Histories every solver fills: dataset name -> (units, description).
SERIES: dict[str, tuple[str, str]] = {
    "contact_force": ("N", "contact force P(t)"),
    "approach": ("m", "approach alpha(t) of impactor and rod end (negative: gap)"),
    "impactor_displacement": ("m", "impactor displacement towards the rod"),
    "impactor_velocity": ("m/s", "impactor velocity, positive towards the rod"),
    "rod_end_displacement": ("m", "axial displacement of the struck rod end, positive into the rod"),
}

#: Output name (a case's ``outputs``) -> (datasets it stores, datasets stored when present).
#: ``station_*`` have shape (n, k) for the k stations in the summary's ``station_x_m``.
OUTPUT_DATASETS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    **{name: ((name,), ()) for name in SERIES},
    "station_displacement": (("station_displacement",), ()),
    "contact_radius": (("contact_radius",), ()),
    "station_strain": (("station_strain",), ()),
    # gauge_* have shape (n, k) for the k gauges in the summary's gauge_x_m, gauge_length_m;
    # gauge_mean_strain: fem_axi's, over the cross-section's mean displacement (:mod:`.gauge_series`)
    "gauge_strain": (("gauge_strain",), ("gauge_mean_strain",)),
    "far_end_velocity": (("far_end_velocity",), ()),
    "energy": (
        ("impactor_kinetic_energy", "contact_energy", "rod_energy"),
        ("rod_kinetic_energy", "rod_strain_energy", "contact_dissipated_energy"),
    ),
    # not a history: the field over the rod on its own grid (ImpactResult.field, :mod:`.field`)
    "strain_field": ((), ()),
}


@dataclass(frozen=True)
class ImpactResult:
    """Outcome of one solver run. Failure is data: check ``success`` and ``status``.

    Attributes
    ----------
    success : bool
        True when at least the first contact was computed to its end.
    status : str
        ``completed`` (no further contact is possible), ``truncated`` (stopped by
        ``max_time_factor`` or ``max_contacts`` after a complete first contact) or
        ``failed``.
    message : str
        Human-readable explanation of the status.
    scheme : str
        The solver and scheme, e.g. ``implicit``, ``paper``, ``fem1d-P2-newmark``.
    dt_s : float
        The nominal time step, s.
    time, contact_force, approach, impactor_displacement, impactor_velocity, rod_end_displacement : ndarray, shape (n,)
        Histories at the nodes (s, N, m, m, m/s, m).
    contact_start_s, contact_end_s : ndarray, shape (c,)
        Every contact interval found, s.
    peak_time_s, peak_force_N : ndarray, shape (k,)
        Every local maximum of the force over all contacts.
    rebound_velocity_m_s : float
        Impactor velocity at the end of the run, m/s (negative: moving away from the rod).
    rod_energy_J : float
        Work done on the rod by the contact force, J (the energy left in the rod).
    energy_error : float
        (KE_in - KE_out - rod_energy - energy left in the contact law) / KE_in.
    n_steps, n_newton_iterations, n_events : int
        Cost counters: accepted nodes, Newton iterations, located contact events.
    wall_time_s : float
        Wall time of the solve, s.
    extra : dict
        More summary entries (scalars, strings, 1-D arrays), e.g. ``station_x_m``; for every
        method, ``dissipated_energy_J`` (the energy the contact dissipated, J) and
        ``residual_approach_m`` (the dent the contact left, m).
    extra_series : dict
        More histories: name -> (array of first dimension n, units, description), e.g.
        ``station_displacement`` or the energies.
    field : dict
        The strain over the whole rod on its own grid (output ``strain_field``,
        :mod:`rodimpact.solvers.field`): ``time`` (m,) s, ``x`` (k,) m and ``strain`` (m, k),
        each (array, units, description); empty when the run was not asked for it.
    """

    success: bool
    status: str
    message: str
    scheme: str
    dt_s: float
    time: NDArray[np.float64]
    contact_force: NDArray[np.float64]
    approach: NDArray[np.float64]
    impactor_displacement: NDArray[np.float64]
    impactor_velocity: NDArray[np.float64]
    rod_end_displacement: NDArray[np.float64]
    contact_start_s: NDArray[np.float64]
    contact_end_s: NDArray[np.float64]
    peak_time_s: NDArray[np.float64]
    peak_force_N: NDArray[np.float64]
    rebound_velocity_m_s: float
    rod_energy_J: float
    energy_error: float
    n_steps: int
    n_newton_iterations: int
    n_events: int
    wall_time_s: float
    extra: dict[str, Any] = dataclass_field(default_factory=dict)
    extra_series: dict[str, tuple[NDArray[np.float64], str, str]] = dataclass_field(default_factory=dict)
    field: dict[str, tuple[NDArray[np.float64], str, str]] = dataclass_field(default_factory=dict)

    @property
    def contact_time_s(self) -> float:
        """Duration of the first contact, s (NaN when it did not end)."""
        if len(self.contact_end_s) == 0:
            return math.nan
        return float(self.contact_end_s[0] - self.contact_start_s[0])

    @property
    def restitution(self) -> float:
        """Coefficient of restitution: the rebound speed over the impact speed, -w_end / w_0
        (the impactor's velocity at the run's last node over its first); NaN without nodes."""
        if self.impactor_velocity.size == 0 or self.impactor_velocity[0] == 0.0:
            return math.nan
        return float(-self.rebound_velocity_m_s / self.impactor_velocity[0])

    @property
    def n_contacts(self) -> int:
        """Number of complete contact intervals."""
        return int(len(self.contact_end_s))

    def summary(self) -> dict[str, Any]:
        """Scalars and small arrays for the HDF5 ``summary`` group (plain types)."""
        return {
            "contact_time_s": self.contact_time_s,
            "peak_force_N": np.asarray(self.peak_force_N, dtype=float),
            "peak_time_s": np.asarray(self.peak_time_s, dtype=float),
            "rebound_velocity_m_s": float(self.rebound_velocity_m_s),
            "restitution": self.restitution,
            "energy_error": float(self.energy_error),
            "rod_energy_J": float(self.rod_energy_J),
            "contact_start_s": np.asarray(self.contact_start_s, dtype=float),
            "contact_end_s": np.asarray(self.contact_end_s, dtype=float),
            "n_contacts": self.n_contacts,
            "success": bool(self.success),
            "status": self.status,
            "message": self.message,
            "scheme": self.scheme,
            "dt_s": float(self.dt_s),
            "n_steps": int(self.n_steps),
            "n_newton_iterations": int(self.n_newton_iterations),
            "n_events": int(self.n_events),
            "solver_wall_time_s": float(self.wall_time_s),
            **self.extra,
        }

    def series(self, outputs: Iterable[str]) -> dict[str, tuple[NDArray[np.float64], str, str]]:
        """``time`` plus the datasets of the requested outputs: name -> (array, units, description).

        Raises
        ------
        ValueError
            An output is unknown, or this run did not compute it (e.g. stations not asked).
        """
        out = {"time": (self.time, "s", "time since first contact")}
        for name in outputs:
            if name not in OUTPUT_DATASETS:
                raise ValueError(f"outputs: unknown output {name!r}; known: {sorted(OUTPUT_DATASETS)}")
            required, optional = OUTPUT_DATASETS[name]
            for dataset in required + optional:
                if dataset in SERIES:
                    out[dataset] = (getattr(self, dataset), *SERIES[dataset])
                elif dataset in self.extra_series:
                    out[dataset] = self.extra_series[dataset]
                elif dataset in required:
                    raise ValueError(f"outputs: {name!r} was not computed by this {self.scheme} run")
        return out

    def field_of(self, outputs: Iterable[str]) -> dict[str, tuple[NDArray[np.float64], str, str]]:
        """The field (:attr:`field`) when ``outputs`` ask for it, else empty (a method that does
        not record the field skips the output: its field is empty)."""
        return dict(self.field) if FIELD_OUTPUT in outputs else {}
