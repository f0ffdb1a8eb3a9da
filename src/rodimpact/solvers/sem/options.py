"""Numerical options of the semi-analytical method: ``sem`` (implicit) and ``sem_paper``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.options import OptionError, setting
from rodimpact.solvers.sem.stability import check_paper_step, implicit_step
from rodimpact.solvers.stepping import SteppingOptions

__all__ = ["PaperSEMOptions", "SCHEMES", "SEMOptions"]

#: ``implicit``: piecewise-linear force, exact product integration, contact force implicit.
#: ``paper``: the paper's step-by-step formula, force held constant and lagged one step.
SCHEMES = ("implicit", "paper")


@dataclass(frozen=True)
class _SEMCommon(SteppingOptions):
    """Settings both SEM schemes have."""

    energy_tolerance: float = setting(
        0.01,
        "A run whose energy balance is off by more than this fraction of the impact energy fails.",
        exclusive_minimum=0,
    )
    max_steps: int = setting(5_000_000, "Step budget of one run; a run that needs more fails.", kind=int, minimum=10)

    scheme: ClassVar[str] = ""

    @property
    def automatic_step(self) -> bool:
        """True when the step is chosen from the case (and checked by step doubling)."""
        return False

    def step(self, problem: ImpactProblem) -> float:
        """The (first) time step to use for ``problem``, s."""
        if self.dt_s is not None:
            return self.dt_s
        return problem.rigid_contact.contact_time_s / self.steps_per_contact


@dataclass(frozen=True)
class SEMOptions(_SEMCommon):
    """Numerics of ``sem``: the implicit scheme (piecewise-linear force, second order)."""

    DESCRIPTION: ClassVar[str] = (
        "Numerics of sem, the semi-analytical method with the derived unit-impulse "
        "responses and the implicit (second-order) scheme."
    )
    scheme: ClassVar[str] = "implicit"

    steps_per_contact: int | None = setting(
        None,
        "Time steps per contact time on a rigid rod, when dt_s is null; null: the step is chosen "
        "from the case's time scales for tolerance and checked by step doubling.",
        kind=int,
        nullable=True,
        minimum=10,
    )
    tolerance: float = setting(
        1e-6,
        "Relative error aimed at, and checked by step doubling, on the first contact time and its "
        "largest force, when dt_s and steps_per_contact are null.",
        exclusive_minimum=0,
        exclusive_maximum=1,
    )

    @property
    def automatic_step(self) -> bool:
        return self.dt_s is None and self.steps_per_contact is None

    def step(self, problem: ImpactProblem) -> float:
        if self.automatic_step:
            return implicit_step(problem, self.tolerance)
        return super().step(problem)


@dataclass(frozen=True)
class PaperSEMOptions(_SEMCommon):
    """Numerics of ``sem_paper``: the paper's explicit scheme (force lagged one step, first order)."""

    DESCRIPTION: ClassVar[str] = (
        "Numerics of sem_paper, the paper's explicit scheme that lags the force by one "
        "step (docs/paper-notes.md); it needs finer steps, hence the larger default."
    )
    scheme: ClassVar[str] = "paper"

    steps_per_contact: int | None = setting(
        20000,
        "Time steps per contact time on a rigid rod, when dt_s is null (the scheme has no "
        "automatic step: one of the two must be given).",
        kind=int,
        nullable=True,
        minimum=10,
    )
    allow_unstable: bool = setting(
        False,
        "Run a step beyond the scheme's stability limit 2 Z / k_c (to see the instability) instead of refusing it.",
        kind=bool,
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.dt_s is None and self.steps_per_contact is None:
            raise OptionError(
                "steps_per_contact", "must be given when dt_s is null (the paper scheme has no automatic step)"
            )

    def check(self, problem: ImpactProblem) -> None:
        """Refuse a step beyond the scheme's stability limit (unless ``allow_unstable``)."""
        check_paper_step(problem, self, self.step(problem))
