"""The semi-analytical method (SEM): Hertz contact + impulse responses + Volterra equation."""

from .problem import SCHEMES, ImpactProblem, SEMOptions
from .result import SERIES, SEMResult, local_maxima
from .solver import solve_sem

__all__ = ["SCHEMES", "SERIES", "ImpactProblem", "SEMOptions", "SEMResult", "local_maxima", "solve_sem"]
