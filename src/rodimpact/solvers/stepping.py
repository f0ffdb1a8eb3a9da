"""What the three time-stepping solvers share, as scipy's ``OdeSolver`` base does for its
methods: their common settings, their stop limits, the end test's window, the histories every
run records (:class:`StepHistory`, which a method's own history extends) and the
:class:`~rodimpact.solvers.result.ImpactResult` built from them, with the energy balance and
its failure written once."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.analysis.signals import local_maxima
from rodimpact.contact.law import ContactLaw, contact_energies, contact_radii
from rodimpact.solvers.options import Options, setting
from rodimpact.solvers.result import ImpactResult

__all__ = [
    "NON_FINITE_ENERGY",
    "Nodes",
    "Outcome",
    "SEPARATION_ROUND_TRIPS",
    "StepHistory",
    "SteppingOptions",
    "contact_series",
    "energy_error",
    "limit_reached",
]

#: The window after a separation over which the impactor must stay clear of the rod's end
#: before a run may end, in wave round trips 2T: 8T, two periods 4T of a fixed rod's end
#: motion once the force has stopped (a free rod's is a drift plus a 2T-periodic motion).
#: The SEM checks its exact end motion over it; fem1d waits it out on a free rod (its fixed
#: rod has an energy bound); fem1d's cost model counts it.
SEPARATION_ROUND_TRIPS = 4.0

#: The message of a run that failed because its energy balance is not a finite number.
NON_FINITE_ENERGY = "non-finite energy balance"


@dataclass(frozen=True)
class SteppingOptions(Options):
    """The settings every time-stepping method has (its own class adds the rest)."""

    dt_s: float | None = setting(
        None,
        "Fixed time step; null chooses it from the case: the contact time on a rigid rod "
        "divided by steps_per_contact (or, for sem with steps_per_contact null, the step for tolerance).",
        unit="s",
        nullable=True,
        exclusive_minimum=0,
    )
    steps_per_contact: int | None = setting(
        None, "Time steps per contact time on a rigid rod, when dt_s is null.", kind=int, nullable=True, minimum=1
    )
    max_time_factor: float = setting(
        100.0, "Simulated time limit as a multiple of the estimated contact time.", exclusive_minimum=1
    )
    max_contacts: int = setting(
        50,
        "Largest number of successive contacts (the impactor re-striking the rod) that are followed.",
        kind=int,
        minimum=1,
    )


@dataclass(frozen=True)
class Outcome:
    """How a run ended: its status (``completed``, ``truncated``, ``failed``), why, and its wall time, s."""

    status: str
    message: str
    wall_time_s: float


def limit_reached(
    starts: list[float], ends: list[float], t: float, t_max: float, options: SteppingOptions
) -> tuple[str, str] | None:
    """The limits every time-stepping solver shares: too many contacts, or the time horizon.

    Parameters
    ----------
    starts, ends : list of float
        The contact starts and ends so far, s (a start beyond ``options.max_contacts`` is dropped).
    t : float
        The time reached, s.
    t_max : float
        The time horizon, s (``options.max_time_factor`` times the solver's contact-time estimate).
    options : SteppingOptions
        ``max_contacts`` and ``max_time_factor``.

    Returns
    -------
    (status, message) or None
        ``truncated`` (or ``failed`` before the first contact ended) and why, when a limit is
        reached; None otherwise.
    """
    if len(starts) > options.max_contacts:
        starts.pop()
        return "truncated", f"stopped at max_contacts={options.max_contacts}; later contacts not computed"
    if t >= t_max:
        status = "truncated" if ends else "failed"
        return status, (
            f"time horizon {t_max:.6g} s (max_time_factor={options.max_time_factor}) reached"
            + ("" if ends else " before the first contact ended")
        )
    return None


def contact_series(law: ContactLaw, approach_m: NDArray[np.float64]) -> dict[str, tuple[NDArray[np.float64], str, str]]:
    """The contact's histories at a run's nodes, as extra series: the energy it stores, the
    energy it has dissipated (a law with memory only) and the radius of its patch (a law with a
    geometry), from the approach at the nodes in time order (m, shape (n,))."""
    stored, dissipated = contact_energies(law, approach_m)
    series = {"contact_energy": (stored, "J", "energy stored in the contact, int_0^alpha P (the contact law)")}
    if law.memory:
        series["contact_energy"] = (stored, "J", "energy the contact would return on unloading (the contact law)")
        series["contact_dissipated_energy"] = (
            dissipated,
            "J",
            "energy the contact has dissipated: the loading work less what unloading returns (largest approach so far)",
        )
    radius = contact_radii(law, approach_m)
    if radius is not None:
        series["contact_radius"] = (radius, "m", "radius of the contact patch (the contact law; Hertz: sqrt(R alpha))")
    return series


def energy_error(*parts: NDArray[np.float64]) -> float:
    """The energy balance of a run whose bodies' energies are recorded: (E_0 - E_end) / E_0.

    Parameters
    ----------
    *parts : ndarray, shape (n,)
        The energies at every node that make up the total (the impactor's, the contact's, the
        rod's), J; the total is their sum in this order.

    Returns
    -------
    float
        The fraction of the initial energy lost (negative: gained); NaN or inf when a part is not finite.
    """
    first, last = parts[0][0], parts[0][-1]
    for part in parts[1:]:
        first, last = first + part[0], last + part[-1]
    return float((first - last) / first)


@dataclass(frozen=True)
class Nodes:
    """The histories every run records, as arrays of shape (n,): time (s), contact force (N),
    impactor displacement (m) and velocity (m/s), rod end displacement (m) and approach (m)."""

    time: NDArray[np.float64]
    force: NDArray[np.float64]
    x: NDArray[np.float64]
    w: NDArray[np.float64]
    u_end: NDArray[np.float64]
    alpha: NDArray[np.float64]


@dataclass(eq=False)
class StepHistory:
    """What every time-stepping run records at its nodes, one entry a node: lists the stepping
    loop appends to, turned into arrays once (:meth:`nodes`) and into the result once
    (:meth:`result`). A method's own histories (energies, stations) are a subclass's fields.

    Attributes
    ----------
    t, force, x, w, u_end, alpha : list of float
        Time (s), contact force (N), impactor displacement (m) and velocity (m/s, positive
        towards the rod), rod end displacement (m) and approach (m) at every node.
    starts, ends : list of float
        Every contact start (the first at t = 0) and end found, s.
    n_newton : int
        Newton iterations of the contact law's step equation.
    """

    t: list[float] = field(default_factory=list)
    force: list[float] = field(default_factory=list)
    x: list[float] = field(default_factory=list)
    w: list[float] = field(default_factory=list)
    u_end: list[float] = field(default_factory=list)
    alpha: list[float] = field(default_factory=list)
    starts: list[float] = field(default_factory=lambda: [0.0])
    ends: list[float] = field(default_factory=list)
    n_newton: int = 0

    def nodes(self) -> Nodes:
        """The histories as arrays (:class:`Nodes`)."""
        return Nodes(
            time=np.asarray(self.t),
            force=np.asarray(self.force),
            x=np.asarray(self.x),
            w=np.asarray(self.w),
            u_end=np.asarray(self.u_end),
            alpha=np.asarray(self.alpha),
        )

    def result(
        self,
        nodes: Nodes,
        outcome: Outcome,
        *,
        scheme: str,
        dt_s: float,
        energy_error: float,
        rod_energy_J: float,
        n_events: int,
        extra: dict[str, Any],
        extra_series: dict[str, tuple[NDArray[np.float64], str, str]],
        field: dict[str, tuple[NDArray[np.float64], str, str]] | None = None,
        min_prominence: float = 0.0,
    ) -> ImpactResult:
        """The run's :class:`~rodimpact.solvers.result.ImpactResult`.

        A run that did not fail fails when its energy balance is not finite
        (:data:`NON_FINITE_ENERGY`); the contact intervals are the complete ones; the force
        maxima are every local maximum that rises ``min_prominence`` (N) above its
        surroundings (:func:`~rodimpact.analysis.signals.local_maxima`).

        Parameters
        ----------
        nodes : Nodes
            This history's arrays (:meth:`nodes`).
        outcome : Outcome
            How the run ended (its method's own checks applied).
        scheme : str
            The solver and scheme.
        dt_s : float
            The nominal time step, s.
        energy_error : float
            The run's energy balance (:func:`energy_error`, or the method's own).
        rod_energy_J : float
            The energy left in the rod, J.
        n_events : int
            Located contact events.
        extra, extra_series, field : dict
            The method's summary entries, series and strain field (:class:`ImpactResult`).
        min_prominence : float
            Force maxima that rise less than this are not kept, N.
        """
        status, message = outcome.status, outcome.message
        if status != "failed" and not math.isfinite(energy_error):
            status, message = "failed", NON_FINITE_ENERGY
        ends = np.asarray(self.ends)
        peak_t, peak_p = local_maxima(nodes.time, nodes.force, min_prominence=min_prominence)
        return ImpactResult(
            success=status != "failed",
            status=status,
            message=message,
            scheme=scheme,
            dt_s=dt_s,
            time=nodes.time,
            contact_force=nodes.force,
            approach=nodes.alpha,
            impactor_displacement=nodes.x,
            impactor_velocity=nodes.w,
            rod_end_displacement=nodes.u_end,
            contact_start_s=np.asarray(self.starts[: len(ends)]),
            contact_end_s=ends,
            peak_time_s=peak_t,
            peak_force_N=peak_p,
            rebound_velocity_m_s=float(self.w[-1]),
            rod_energy_J=rod_energy_J,
            energy_error=energy_error,
            n_steps=len(nodes.time) - 1,
            n_newton_iterations=int(self.n_newton),
            n_events=n_events,
            wall_time_s=outcome.wall_time_s,
            extra=extra,
            extra_series=extra_series,
            field={} if field is None else field,
        )
