"""What the three time-stepping solvers share: their common settings and their stop limits."""

from __future__ import annotations

from dataclasses import dataclass

from rodimpact.solvers.options import Options, setting

__all__ = ["Outcome", "SteppingOptions", "limit_reached"]


@dataclass(frozen=True)
class SteppingOptions(Options):
    """The settings every time-stepping method has (its own class adds the rest)."""

    dt_s: float | None = setting(
        None, "Fixed time step; null chooses it from the case: the contact time on a rigid rod "
        "divided by steps_per_contact (or, for sem with steps_per_contact null, the step for tolerance).",
        unit="s", nullable=True, exclusive_minimum=0)
    steps_per_contact: int | None = setting(
        None, "Time steps per contact time on a rigid rod, when dt_s is null.", kind=int, nullable=True, minimum=1)
    max_time_factor: float = setting(
        100.0, "Simulated time limit as a multiple of the estimated contact time.", exclusive_minimum=1)
    max_contacts: int = setting(
        50, "Largest number of successive contacts (the impactor re-striking the rod) that are followed.",
        kind=int, minimum=1)


@dataclass(frozen=True)
class Outcome:
    """How a run ended: its status (``completed``, ``truncated``, ``failed``), why, and its wall time, s."""

    status: str
    message: str
    wall_time_s: float


def limit_reached(starts: list[float], ends: list[float], t: float, t_max: float, options: SteppingOptions
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
        return status, (f"time horizon {t_max:.6g} s (max_time_factor={options.max_time_factor}) reached"
                        + ("" if ends else " before the first contact ended"))
    return None
