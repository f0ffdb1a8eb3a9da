"""Parameter sweeps: a case run over a grid of parameter values, one HDF5 run per point.

A case that declares ``sweep:`` (``workflow/schemas/cases.schema.yaml``) is a template: it is
run at every point of the grid of its swept parameters (all combinations). The grid is a
:class:`pandas.DataFrame`, one column per parameter and one row per point, which the
workflow wraps in snakemake's ``Paramspace``; a point is named ``name~value_name~value``.
"""

from __future__ import annotations

import copy
import itertools
import logging
import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # the annotation only; pandas is imported where the frame is built
    import pandas as pd

logger = logging.getLogger(__name__)

__all__ = [
    "SWEEP_PARAMETERS",
    "SIGNIFICANT_DIGITS",
    "SweepError",
    "sweep_frame",
    "sweep_point_case",
    "sweep_points",
    "sweep_values",
]


class SweepError(ValueError):
    """A sweep is malformed: ``field`` is the path inside the case's ``sweep`` (e.g.
    ``parameters.mass_kg.num``), ``reason`` what is wrong."""

    def __init__(self, field: str, reason: str) -> None:
        self.field, self.reason = field, reason
        super().__init__(f"{field}: {reason}" if field else reason)

    def __reduce__(self):
        return SweepError, (self.field, self.reason)


#: Digits the swept values are rounded to: they name the point's files, and a value read back
#: from a file name is then the very float of the grid.
SIGNIFICANT_DIGITS = 6


def _ball_diameter(case: dict, d: float) -> None:
    density = case["impactor"]["material"]["density_kg_m3"]
    case["impactor"].update(radius_m=d / 2.0, mass_kg=density * math.pi * d**3 / 6.0)


def _impactor(field: str) -> Callable[[dict, float], None]:
    return lambda case, value: case["impactor"].update({field: value})


def _rod_length(case: dict, length: float) -> None:
    case["rod"]["length_m"] = length


def _film(setter: Callable[[dict, float], None]) -> Callable[[dict, float], None]:
    def set_film(case: dict, value: float) -> None:
        film = (case.get("contact") or {}).get("film")
        if film is None:
            raise ValueError("the case has no film (contact.film) to sweep")
        setter(film, value)

    return set_film


def _film_material(field: str) -> Callable[[dict, float], None]:
    def set_material(film: dict, value: float) -> None:
        if field == "poisson_ratio" and not value < 0.5:
            raise ValueError(f"the film's Poisson's ratio must be < 0.5, got {value!r}")
        film["material"] = {**film["material"], field: value}

    return _film(set_material)


def _film_thickness(film: dict, value: float) -> None:
    film["thickness_m"] = value


#: swept parameter -> (what it sets, how it changes a resolved case in place)
SWEEP_PARAMETERS: dict[str, tuple[str, Callable[[dict, float], None]]] = {
    "ball_diameter_m": ("a solid ball of the impactor's material: radius d/2, mass rho pi d^3/6, m", _ball_diameter),
    "mass_kg": ("the impactor's mass, kg", _impactor("mass_kg")),
    "radius_m": ("the radius of the impactor's spherical nose, m", _impactor("radius_m")),
    "velocity_m_s": ("the impact velocity, m/s", _impactor("velocity_m_s")),
    "rod_length_m": ("the rod's length, m", _rod_length),
    "film_modulus_pa": ("the film's Young's modulus, Pa", _film_material("youngs_modulus_pa")),
    "film_poisson_ratio": ("the film's Poisson's ratio", _film_material("poisson_ratio")),
    "film_thickness_m": ("the film's thickness, m", _film(_film_thickness)),
}


def _rounded(value: float) -> float:
    return float(f"{value:.{SIGNIFICANT_DIGITS}g}")


def sweep_values(spec: Sequence[float] | Mapping[str, Any]) -> list[float]:
    """The values of one swept parameter.

    Parameters
    ----------
    spec : sequence of float or mapping
        A list of values, or ``{"start", "stop", "num", "spacing"}`` (``spacing`` ``linear``,
        the default, or ``log``): ``num`` values from ``start`` to ``stop`` inclusive.

    Returns
    -------
    list of float
        The values rounded to :data:`SIGNIFICANT_DIGITS` significant digits.

    Raises
    ------
    SweepError
        A value is not positive and finite, ``stop`` <= ``start``, ``num`` < 2, or two values
        round to the same;
        ``field`` is the key of ``spec`` at fault (``start``, ``stop``, ``num``, ``spacing``)
        or empty for the values themselves.
    """
    if isinstance(spec, Mapping):
        start, stop, num = float(spec["start"]), float(spec["stop"]), spec["num"]
        if int(num) != num or num < 2:
            raise SweepError("num", f"must be an integer >= 2, got {num!r}")
        spacing = spec.get("spacing", "linear")
        if spacing not in ("linear", "log"):
            raise SweepError("spacing", f"must be 'linear' or 'log', got {spacing!r}")
        if not (start > 0 and stop > 0 and math.isfinite(start) and math.isfinite(stop)):
            raise SweepError("", f"start, stop: must be finite and > 0, got {start!r}, {stop!r}")
        if not stop > start:
            raise SweepError("stop", f"must be > start ({start!r}), got {stop!r}")
        raw = (np.geomspace if spacing == "log" else np.linspace)(start, stop, int(num))
    else:
        raw = np.asarray(list(spec), dtype=float)
        if raw.size == 0 or not np.all(np.isfinite(raw) & (raw > 0)):
            raise SweepError("", f"values must be finite and > 0, got {list(spec)!r}")
    values = [_rounded(float(v)) for v in raw]
    if len(set(values)) != len(values):
        raise SweepError("", f"values coincide after rounding to {SIGNIFICANT_DIGITS} digits: {values}")
    return values


def sweep_points(sweep: Mapping[str, Any]) -> list[dict[str, float]]:
    """The sweep's grid: one mapping parameter -> value per point, parameters in declared order.

    Parameters
    ----------
    sweep : mapping
        The case's ``sweep`` (``parameters``: name -> values spec, see :func:`sweep_values`).

    Raises
    ------
    SweepError
        An unknown parameter or a bad values spec; ``field`` is its path in ``sweep``.
    """
    parameters = sweep.get("parameters") or {}
    if not parameters:
        raise SweepError("parameters", "a sweep needs at least one parameter")
    columns = {}
    for name, spec in parameters.items():
        if name not in SWEEP_PARAMETERS:
            raise SweepError(f"parameters.{name}", f"unknown sweep parameter; known: {', '.join(SWEEP_PARAMETERS)}")
        try:
            columns[name] = sweep_values(spec)
        except SweepError as error:
            field = f"parameters.{name}" + (f".{error.field}" if error.field else "")
            raise SweepError(field, error.reason) from None
        except (ValueError, KeyError, TypeError) as error:
            raise SweepError(f"parameters.{name}", str(error)) from None
    return [dict(zip(columns, row)) for row in itertools.product(*columns.values())]


def sweep_frame(sweep: Mapping[str, Any]) -> pd.DataFrame:
    """:func:`sweep_points` as a :class:`pandas.DataFrame` (one float column per parameter), the
    form snakemake's ``Paramspace`` takes; same errors."""
    import pandas as pd  # only the workflow's Paramspace needs it; the configuration check does not

    points = sweep_points(sweep)
    return pd.DataFrame(points, columns=list(points[0]), dtype=float)


def sweep_point_case(case: Mapping[str, Any], point: Mapping[str, Any], name: str) -> dict[str, Any]:
    """The resolved case at one point of its sweep.

    Parameters
    ----------
    case : mapping
        A resolved sweep case (with ``sweep``: ``methods``, ``parameters``).
    point : mapping
        Parameter name -> value (SI units), e.g. a point of :func:`sweep_points`.
    name : str
        The point's name (its Paramspace instance pattern), part of the run's id.

    Returns
    -------
    dict
        A plain case (no ``sweep``) whose ``methods`` are the sweep's, with ``sweep_point``
        holding the point's parameters and ``sweep_of`` the sweep case's id (stored with
        the run).
    """
    unknown = [key for key in point if key not in SWEEP_PARAMETERS]
    if unknown:
        raise ValueError(f"point: unknown sweep parameter(s) {unknown}; known: {', '.join(SWEEP_PARAMETERS)}")
    # the case without its sweep: the sweep's grid grows with the points, and copying it into every
    # point made planning quadratic in them
    sweep = case["sweep"]
    resolved = _plain_copy({key: value for key, value in case.items() if key != "sweep"})
    values = {key: float(value) for key, value in point.items()}
    for key, value in values.items():
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"point.{key}: must be finite and > 0, got {value!r}")
        SWEEP_PARAMETERS[key][1](resolved, value)
    resolved.update(
        id=f"{case['id']}.sweep.{name}",
        methods=list(sweep["methods"]),
        sweep_point=values,
        sweep_of=case["id"],
        description=f"{case['id']} at " + ", ".join(f"{k} = {v:g}" for k, v in values.items()),
        measured={},
        published={},
    )
    return resolved


def _plain_copy(value: Any) -> Any:
    """A deep copy of plain configuration data (mappings, lists and tuples of scalars and
    strings), several times faster than :func:`copy.deepcopy`, which a planned sweep pays at
    every point; any other object is copied by :func:`copy.deepcopy`."""
    if isinstance(value, dict):
        return {key: _plain_copy(item) for key, item in value.items()}
    if isinstance(value, list):
        return [_plain_copy(item) for item in value]
    if isinstance(value, tuple):
        return tuple(_plain_copy(item) for item in value)
    if value is None or isinstance(value, (str, int, float, bool)):
        return value
    return copy.deepcopy(value)
