"""Finite-element methods (scikit-fem): ``fem1d``, the rod as a 1D bar with Hertz contact."""

from .bar import BarModel, bar_model
from .fem1d import FEM1DOptions, solve_fem1d

__all__ = ["BarModel", "FEM1DOptions", "bar_model", "solve_fem1d"]
