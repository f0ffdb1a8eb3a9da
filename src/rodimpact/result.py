"""Result object shared by every solver (SEM and FEM) and the post-processing they share."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Iterable

import numpy as np
from scipy.signal import peak_prominences
from numpy.typing import NDArray

__all__ = ["ImpactResult", "OUTPUT_DATASETS", "SERIES", "ZIGZAG_UNSTABLE", "check_stepping", "first_contact_maxima",
           "limit_reached", "local_maxima", "sawtooth_amplitude", "zigzag_steps"]

#: A force alternating up and down at every step over this many steps (:func:`zigzag_steps`)
#: marks an unstable step.
ZIGZAG_UNSTABLE = 10

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
    "energy": (("impactor_kinetic_energy", "contact_energy", "rod_energy"),
               ("rod_kinetic_energy", "rod_strain_energy")),
}


def check_stepping(dt_s: float | None, steps_per_contact: int | None, min_steps: int,
                   max_time_factor: float, max_contacts: int, *, steps_optional: bool = False) -> None:
    """Validate the time-stepping settings every solver's options share.

    Raises
    ------
    ValueError
        Naming the first offending setting.
    """
    if dt_s is not None and not (math.isfinite(dt_s) and dt_s > 0):
        raise ValueError(f"dt_s must be > 0 or None, got {dt_s!r}")
    if steps_per_contact is None:
        if not steps_optional:
            raise ValueError("steps_per_contact must be given")
    elif int(steps_per_contact) != steps_per_contact or steps_per_contact < min_steps:
        extra = " or None" if steps_optional else ""
        raise ValueError(f"steps_per_contact must be an integer >= {min_steps}{extra}, got {steps_per_contact!r}")
    if not max_time_factor > 1:
        raise ValueError(f"max_time_factor must be > 1, got {max_time_factor!r}")
    if int(max_contacts) != max_contacts or max_contacts < 1:
        raise ValueError(f"max_contacts must be an integer >= 1, got {max_contacts!r}")


def first_contact_maxima(peak_time_s: Any, peak_force_N: Any, contact_end_s: Any) -> NDArray[np.float64]:
    """The force maxima (N) that fall within the first contact (all of them if none ended)."""
    times, peaks = np.atleast_1d(peak_time_s), np.atleast_1d(peak_force_N)
    ends = np.atleast_1d(contact_end_s)
    return peaks[times <= ends[0]] if len(ends) else peaks


def sawtooth_amplitude(force: Any) -> float:
    """Largest step-to-step zig-zag of a force history, relative to its largest value.

    max |P_{n+1} - 2 P_n + P_{n-1}| / (4 max P): about h^2 |P''| / (4 max P) on a smooth
    history, close to 1 when the force alternates between zero and its peak.
    """
    p = np.asarray(force, dtype=float)
    if len(p) < 3 or not np.max(p) > 0:
        return 0.0
    return float(np.max(np.abs(p[2:] - 2.0 * p[1:-1] + p[:-2])) / (4.0 * np.max(p)))


def zigzag_steps(force: Any, threshold: float = 0.05) -> int:
    """Longest run of steps over which the force alternates up, down, up, ...

    Counts consecutive increments dP_n that change sign at every step while each exceeds
    ``threshold`` times the largest force. An explicit scheme's instability (a root of its
    step below -1) makes such a run as long as the contact; a smooth but under-resolved
    force (a few steps per rise) does not alternate at every step.
    """
    p = np.asarray(force, dtype=float)
    if len(p) < 3 or not np.max(p) > 0:
        return 0
    d = np.diff(p)
    big = np.abs(d) > threshold * np.max(p)
    alternating = big[1:] & big[:-1] & (np.sign(d[1:]) == -np.sign(d[:-1]))
    if not alternating.any():
        return 0
    # longest run of True: the distance between the falses around it
    edges = np.flatnonzero(np.diff(np.concatenate([[0], alternating.astype(np.int8), [0]])))
    return int(np.max(edges[1::2] - edges[::2]) + 1)


def limit_reached(starts: list[float], ends: list[float], t: float, t_max: float,
                  max_contacts: int) -> tuple[str, str] | None:
    """The limits a time-stepping solver shares: too many contacts, or the time horizon.

    Returns (status, message) when a limit is reached (dropping the contact start beyond
    ``max_contacts``), else None.
    """
    if len(starts) > max_contacts:
        starts.pop()
        return "truncated", f"stopped at max_contacts={max_contacts}; later contacts not computed"
    if t >= t_max:
        status = "truncated" if ends else "failed"
        return status, f"time horizon {t_max:.6g} s reached" + ("" if ends else " before the first contact ended")
    return None


def local_maxima(
    time: NDArray[np.float64], force: NDArray[np.float64], min_prominence: float = 0.0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Every strict local maximum of a sampled force, refined by a parabola.

    Parameters
    ----------
    time, force : ndarray, shape (n,)
        Nodes (increasing times, s) and force values, N.
    min_prominence : float
        Keep only maxima that rise at least this much (N) above the higher of the two
        minima that separate them from higher ground (``scipy.signal`` prominence); 0
        keeps every maximum.

    Returns
    -------
    peak_time_s, peak_force_N : ndarray, shape (k,)
        The vertex of the parabola through each interior maximum and its two neighbours
        (the node itself where the parabola is degenerate).
    """
    t = np.asarray(time, dtype=float)
    p = np.asarray(force, dtype=float)
    if len(p) < 3:
        return np.empty(0), np.empty(0)
    i = np.flatnonzero((p[1:-1] > p[:-2]) & (p[1:-1] >= p[2:]) & (p[1:-1] > 0)) + 1
    if min_prominence > 0 and len(i):
        i = i[peak_prominences(p, i)[0] >= min_prominence]
    times, values = [], []
    for k in i:
        t0, t1, t2 = t[k - 1], t[k], t[k + 1]
        p0, p1, p2 = p[k - 1], p[k], p[k + 1]
        # Newton form of the interpolating parabola through the three nodes
        d01 = (p1 - p0) / (t1 - t0)
        d12 = (p2 - p1) / (t2 - t1)
        curv = (d12 - d01) / (t2 - t0)
        if curv < 0:
            tv = 0.5 * (t0 + t1) - d01 / (2.0 * curv)
            tv = min(max(tv, t0), t2)
            pv = p0 + d01 * (tv - t0) + curv * (tv - t0) * (tv - t1)
        else:
            tv, pv = t1, p1
        times.append(tv)
        values.append(max(pv, p1))
    return np.asarray(times), np.asarray(values)


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
        (KE_in - KE_out - rod_energy - Hertz energy left) / KE_in.
    n_steps, n_newton_iterations, n_events : int
        Cost counters: accepted nodes, Newton iterations, located contact events.
    wall_time_s : float
        Wall time of the solve, s.
    extra : dict
        More summary entries (scalars, strings, 1-D arrays), e.g. ``station_x_m``.
    extra_series : dict
        More histories: name -> (array of first dimension n, units, description), e.g.
        ``station_displacement`` or the energies.
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
    extra: dict[str, Any] = field(default_factory=dict)
    extra_series: dict[str, tuple[NDArray[np.float64], str, str]] = field(default_factory=dict)

    @property
    def contact_time_s(self) -> float:
        """Duration of the first contact, s (NaN when it did not end)."""
        if len(self.contact_end_s) == 0:
            return math.nan
        return float(self.contact_end_s[0] - self.contact_start_s[0])

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
