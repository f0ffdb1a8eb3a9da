"""How a film or stack is divided through its thickness: the part of :mod:`.film_mesh` the
cost model needs, without the mesher's imports (scikit-fem, scipy).

``case_file`` jobs estimate every method's cost of every case; they import this module, not
:mod:`.film_mesh`, which re-exports :data:`FILM_ASPECT` and :func:`layer_elements`. The check of
a positive finite argument (:func:`positive`) lives here, at the bottom of the meshers' imports:
every mesher (:mod:`.mesh_geometry`, :mod:`.meshes`, :mod:`.film_mesh`) checks its arguments
with it.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence

from rodimpact.solvers.fem_axi.options import FILM_LAYERS

__all__ = ["FILM_ASPECT", "layer_elements", "positive"]

FILM_ASPECT = 6.0
"""Largest ratio of a film cell's width to its height (the columns' spacing away from the contact)."""


def positive(name: str, value: float) -> float:
    """``value`` as a float.

    Raises
    ------
    ValueError
        ``value`` is not a positive finite real number (a bool is not one).
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not 0 < value < math.inf:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    return float(value)


def layer_elements(thicknesses_m: Sequence[float], layers: int = FILM_LAYERS) -> list[int]:
    """Elements through each layer's thickness: ``layers`` through the thickest, and through
    every other as many as make them at most as high (at least one).

    Parameters
    ----------
    thicknesses_m : sequence of float
        The layers' thicknesses, m (> 0).
    layers : int
        Elements through the thickest layer (>= 1).
    """
    if isinstance(layers, bool) or not isinstance(layers, int) or layers < 1:
        raise ValueError(f"layers must be a positive integer, got {layers!r}")
    thicknesses = [positive("film_thickness_m", h) for h in thicknesses_m]
    if not thicknesses:
        raise ValueError("film_thickness_m: at least one layer")
    height = max(thicknesses) / layers
    return [layers if h == max(thicknesses) else max(1, math.ceil(h / height - 1e-9)) for h in thicknesses]
