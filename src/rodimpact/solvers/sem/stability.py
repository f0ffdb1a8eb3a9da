"""Step size of the SEM: the paper scheme's stability limit and the implicit scheme's choice.

The paper's scheme (``scheme="paper"``) holds the contact force constant over a step at
its value from the previous step. Linearise it about a state of the contact, P = k_c alpha
with the contact stiffness k_c = dP/dalpha (the law's :meth:`stiffness`; 3/2 k alpha^(1/2)
for Hertz), for a step h shorter than
the wave round trip 2T (the rod end then answers a force held over a step with the
displacement h P / Z, Z = S sqrt(E rho) the rod's impedance). A perturbation
(e_n of the approach, w_n of the impactor's velocity) obeys

    e_{n+1} = (1 - a - b/2) e_n + h w_n,     w_{n+1} = w_n - (b/h) e_n,
    a = h k_c / Z,   b = h^2 k_c / m,

with characteristic polynomial lambda^2 - (2 - a - b/2) lambda + (1 - a + b/2). By the
Jury conditions its roots lie in the unit disc if and only if
    (i)  1 + tr + det = 4 - 2a > 0     i.e.  h < 2 Z / k_c,
    (ii) det = 1 - a + b/2 < 1         i.e.  h < 2 m / Z,
    (1 - tr + det = b > 0 always holds).
(i) is the limit that matters: beyond it a root crosses -1 and a step-to-step sawtooth of
the force grows geometrically: the lagged force overshoots the rod's instantaneous
answer. (ii) only separates growth from decay of the slow mode at the rate
h k_c (h/2m - 1/Z) per step, an O(h) drift over a contact that vanishes as h -> 0 (on a
rigid rod, Z -> oo, the scheme is never unstable, only first order).

k_c is largest where the approach is (the law is monotone with a stiffness that does not
fall as it is pressed); the approach never exceeds the rigid-rod approach alpha_H, where
the law's stored energy equals the impact energy (all the kinetic energy in the contact), so

    h_limit = 2 Z / k_c(alpha_H)

is a step below which the scheme is stable throughout any contact of the case.
:func:`paper_step_limit` returns it; ``tests/test_sem_stability.py`` verifies the sharp
threshold with the run's actual largest approach (stable at 0.9, unstable at 1.1 of it).

The implicit scheme has no such limit. :func:`implicit_step` chooses its step from the
case's time scales; :mod:`.solver` then checks the choice by step doubling.
"""

from __future__ import annotations

import logging
import math
from typing import Any

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.options import OptionError

__all__ = [
    "AUTO_ERROR_CONSTANT",
    "AUTO_STEPS",
    "UnstableStepError",
    "check_paper_step",
    "contact_time_scale",
    "implicit_step",
    "tolerance_step",
    "paper_step_limit",
]

log = logging.getLogger(__name__)

#: Error constant C of the implicit scheme, err ~ C (h / tau)^2 with tau from
#: :func:`contact_time_scale`; measured <= 1 on the shipped cases (first contact time and
#: largest force at 100 steps per tau), taken 4 for margin.
AUTO_ERROR_CONSTANT = 4.0
#: Fewest steps over the estimated contact time the first guess of the automatic step takes.
AUTO_STEPS = 20_000


class UnstableStepError(OptionError):
    """The paper scheme was asked for a step beyond its stability limit (``field``: the
    setting that gave the step, ``dt_s`` or ``steps_per_contact``)."""

    def __str__(self) -> str:
        return self.reason


def paper_step_limit(problem: ImpactProblem, approach_m: float | None = None) -> float:
    """Largest stable step of the paper's lagged explicit scheme, s: 2 Z / k_c.

    Parameters
    ----------
    problem : ImpactProblem
        The impact.
    approach_m : float, optional
        The largest approach alpha at which to evaluate k_c, m; defaults to the rigid-rod
        approach, an upper bound for every rod, so that the limit holds for the case.

    Returns
    -------
    float
        The step limit, s (``inf`` for a rod of infinite impedance). Derived for steps
        shorter than the wave round trip 2T (see the module docstring).
    """
    alpha = problem.rigid_contact.max_approach_m if approach_m is None else approach_m
    kc = problem.contact.stiffness(alpha)
    impedance = problem.rod.impedance
    if kc == 0.0 or not math.isfinite(impedance):
        return math.inf
    return 2.0 * impedance / kc


def contact_time_scale(problem: ImpactProblem) -> float:
    """The time scale of the contact force's rise and fall, s.

    The contact time on a rigid rod t_H (Hertz: 2.94 alpha_H / v0), scaled by alpha_Z /
    alpha_H when that is smaller than 1: alpha_Z is the approach at which the law's force
    reaches Z v0, where a force fed through the rod's impedance Z levels off (thin rods),
    long before t_H.
    """
    rigid = problem.rigid_contact
    impedance = problem.rod.impedance
    if not math.isfinite(impedance):
        return rigid.contact_time_s
    alpha_z = problem.contact.approach(impedance * problem.velocity_m_s)
    return rigid.contact_time_s * min(1.0, alpha_z / rigid.max_approach_m)


def tolerance_step(problem: ImpactProblem, tolerance: float) -> float:
    """The implicit scheme's step for ``tolerance`` from its error model, s: tau sqrt(tolerance
    / C) with tau = :func:`contact_time_scale` and C = :data:`AUTO_ERROR_CONSTANT`, and at
    most a 20th of the wave round trip 2T (the reflections' kinks on a resolved history)."""
    if not (0.0 < tolerance < 1.0):
        raise ValueError(f"tolerance must be in (0, 1), got {tolerance!r}")
    step = contact_time_scale(problem) * math.sqrt(tolerance / AUTO_ERROR_CONSTANT)
    period = problem.rod.reflection_period
    return min(step, period / 20.0) if math.isfinite(period) else step


def implicit_step(problem: ImpactProblem, tolerance: float) -> float:
    """First guess of the implicit (second-order) scheme's step for ``tolerance``, s.

    h = tau sqrt(tolerance / C) with tau = :func:`contact_time_scale` and C =
    :data:`AUTO_ERROR_CONSTANT`, and at most a 20th of the wave round trip 2T, so that the
    reflections' kinks in the force fall on a resolved history; but no finer than
    :data:`AUTO_STEPS` steps over the estimated contact time (a long contact on a thin
    rod varies slowly after its rise). The solver starts from twice this guess, made
    commensurate with the round trip, checks it against a run at about twice its step and
    refines it until the estimate meets the tolerance.
    """
    step = tolerance_step(problem, tolerance)
    period = problem.rod.reflection_period
    duration = problem.contact_time_estimate()
    if math.isfinite(period):
        duration -= period  # the estimate's round trip: an upper bound, not a time scale
    return max(step, duration / AUTO_STEPS)


def check_paper_step(problem: ImpactProblem, options: Any, h: float) -> None:
    """Refuse a step of the paper scheme beyond :func:`paper_step_limit`.

    Parameters
    ----------
    problem : ImpactProblem
    options : PaperSEMOptions
        Its ``allow_unstable`` lets the step run (with a warning); its ``dt_s`` says which
        setting gave the step.
    h : float
        The step, s.

    Raises
    ------
    UnstableStepError
        The step exceeds the limit and ``allow_unstable`` is False.
    """
    limit = paper_step_limit(problem)
    if h <= limit:
        return
    alpha = problem.rigid_contact.max_approach_m
    message = (
        f"dt_s={h:.4g} s exceeds the paper scheme's stability limit 2 Z / k_c = {limit:.4g} s "
        f"(rod impedance Z = {problem.rod.impedance:.4g} kg/s, contact stiffness k_c = dP/dalpha "
        f"= {problem.contact.stiffness(alpha):.4g} N/m at the rigid-rod approach {alpha:.4g} m)"
    )
    if not options.allow_unstable:
        needed = math.ceil(problem.rigid_contact.contact_time_s / limit)
        field = "dt_s" if options.dt_s is not None else "steps_per_contact"
        raise UnstableStepError(
            field,
            f"{message}; take dt_s <= {limit:.4g} s (steps_per_contact >= {needed}), "
            "or set allow_unstable: true to run it anyway",
        )
    log.warning("%s; running anyway (allow_unstable)", message)
