"""The semi-analytical method (SEM): Hertz contact + impulse responses + Volterra equation."""

from .problem import SCHEMES, ImpactProblem, SEMOptions
from ..result import SERIES, ImpactResult, local_maxima

SEMResult = ImpactResult  # the SEM's result is the shared result object
from .solver import solve_sem

__all__ = ["SCHEMES", "SERIES", "ImpactProblem", "SEMOptions", "SEMResult", "local_maxima", "solve_sem"]
