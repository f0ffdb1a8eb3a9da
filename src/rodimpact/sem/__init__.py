"""The semi-analytical method (SEM): Hertz contact + impulse responses + Volterra equation."""

from .problem import SCHEMES, ImpactProblem, SEMOptions
from ..result import SERIES, ImpactResult, local_maxima

SEMResult = ImpactResult  # the SEM's result is the shared result object
from .solver import UnstableStepError, solve_sem
from .stability import paper_step_limit

__all__ = ["SCHEMES", "SERIES", "ImpactProblem", "SEMOptions", "SEMResult", "UnstableStepError", "local_maxima",
           "paper_step_limit", "solve_sem"]
