"""Numerical options of ``fem1d`` (the rod as a 1D finite-element bar)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.options import OptionError, setting
from rodimpact.solvers.stepping import SteppingOptions

__all__ = ["FEM1DOptions", "MIN_POINTS_PER_WAVELENGTH", "MIN_STEPS_PER_CONTACT", "WARN_POINTS_PER_WAVELENGTH"]

#: Below this many nodes per wavelength of the contact's wave the run warns; below the
#: hard minimum it refuses.
WARN_POINTS_PER_WAVELENGTH = 10.0
MIN_POINTS_PER_WAVELENGTH = 4.0
#: Fewer steps per contact time on a rigid rod cannot resolve the contact.
MIN_STEPS_PER_CONTACT = 20


@dataclass(frozen=True)
class FEM1DOptions(SteppingOptions):
    """Numerics of ``fem1d``: the rod as a scikit-fem bar, Newmark time stepping, the case's contact law."""

    DESCRIPTION: ClassVar[str] = (
        "Numerics of fem1d, the rod as a scikit-fem bar (P1 or P2 elements) with "
        "Newmark time stepping and the same contact law as the SEM."
    )

    steps_per_contact: int | None = setting(
        2000,
        "Time steps per contact time on a rigid rod, when dt_s is null.",
        kind=int,
        nullable=True,
        minimum=MIN_STEPS_PER_CONTACT,
    )
    element: str = setting("P2", "Lagrange element of the bar.", kind=str, choices=("P1", "P2"))
    elements: int | None = setting(
        None,
        "Number of elements along the rod; null chooses points_per_wavelength nodes per wavelength "
        "of the contact's wave (at least 20 elements).",
        kind=int,
        nullable=True,
        minimum=1,
    )
    points_per_wavelength: float = setting(
        200.0,
        "Nodes per wavelength a t_c of the contact's wave (t_c the contact time on a rigid rod), "
        "when elements is null.",
        exclusive_minimum=0,
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.dt_s is None and self.steps_per_contact is None:
            raise OptionError("steps_per_contact", "must be given when dt_s is null")

    def check(self, problem: ImpactProblem) -> None:
        """Refuse settings that cannot resolve the case's contact (see :meth:`resolve`)."""
        self.resolve(problem)

    def resolve(self, problem: ImpactProblem) -> tuple[int, float, list[str]]:
        """Element count, time step (s) and warnings for ``problem``.

        Raises
        ------
        OptionError
            The settings cannot resolve the contact (naming the setting and the value it needs).
        """
        t_contact = problem.rigid_contact.contact_time_s
        wavelength = problem.rod.wave_speed * t_contact
        order = 1 if self.element == "P1" else 2
        length = problem.rod.length_m
        n = self.elements
        if n is None:
            n = max(20, math.ceil(self.points_per_wavelength * length / (order * wavelength)))
        points = wavelength / (length / (n * order))
        needed = math.ceil(WARN_POINTS_PER_WAVELENGTH * length / (order * wavelength))
        warnings = []
        field = "elements" if self.elements is not None else "points_per_wavelength"
        if points < MIN_POINTS_PER_WAVELENGTH:
            raise OptionError(
                field,
                f"gives {points:.2f} nodes per wavelength of the contact's wave (a t_c = "
                f"{wavelength:.3g} m) with elements={n}; needs elements >= {needed}",
            )
        if points < WARN_POINTS_PER_WAVELENGTH:
            warnings.append(
                f"elements={n} gives only {points:.1f} nodes per wavelength of the contact's "
                f"wave; elements >= {needed} recommended"
            )
        dt = self.dt_s if self.dt_s is not None else t_contact / self.steps_per_contact
        if dt > t_contact / MIN_STEPS_PER_CONTACT:
            raise OptionError(
                "dt_s",
                f"gives dt_s={dt:.3g} s, which cannot resolve a contact of {t_contact:.3g} s "
                f"(on a rigid rod); needs dt_s <= {t_contact / MIN_STEPS_PER_CONTACT:.3g} s "
                f"(steps_per_contact >= {MIN_STEPS_PER_CONTACT})",
            )
        return n, dt, warnings
