"""The sensor's prediction band from the continuum: the science behind the ``sensor_band`` rule.

For one case whose law is calibrated by the continuum (``tabulated`` from the indentation) and
whose rod carries a stack of layers, every constant the stack knows only to a range is a
parameter of the band (:func:`stack_parameters`): each layer's thickness
(``thickness_range_m``) and each constant of each layer material with ``ranges`` in the
materials file (a material shared by two layers is one parameter: one ink, one modulus). The
contact time at a set of values is the calibrated SEM's: the continuum's static indentation of
the case's ball on the stack so changed (:func:`~rodimpact.jobs.indentation.indentation_curve`),
then the SEM with that curve as its law.

The band evaluates the nominal stack (with the case's own curve, the ``indentation`` rule's,
when the rule hands it over) and the two corners where every parameter sits at the end that
lengthens (shortens) the contact. Which end that is comes from the analytic law of the case's
bodies (the stack's thin-layer law, :func:`law_longer_high`: a run of the SEM at each end of the
range, the others nominal), which is too soft to give the time but not its direction. With
``axes`` (the named target ``make sensor-axes``) the band also evaluates each parameter at the
two ends of its range by the continuum, reads the lengthening end from that axis and records
whether the time is monotone along every axis (``monotone``) and whether the two directions
agree. Where the time is monotone along every axis, the two corners bound it over the box, if
the parameters act independently of each other's values.
"""

from __future__ import annotations

import copy
import logging
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from rodimpact.contact.laws import bodies_contact
from rodimpact.jobs.indentation import indentation_curve
from rodimpact.jobs.runner import run_case
from rodimpact.storage.atomic import atomic_directory
from rodimpact.storage.bands import CaseBand, write_band
from rodimpact.storage.curves import read_contact_curve

__all__ = [
    "StackParameter",
    "calibrated_time_us",
    "law_longer_high",
    "sensor_band",
    "sensor_band_to_file",
    "sensor_bands_into",
    "stack_parameters",
    "with_values",
]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class StackParameter:
    """A constant of a stack known to a range.

    Attributes
    ----------
    name : str
        ``"{layer name}: thickness_m"`` or ``"{material name}: {constant}"``.
    nominal, low, high : float
        Its nominal value and range (SI units: m, Pa or 1).
    """

    name: str
    nominal: float
    low: float
    high: float


def _stack(case: Mapping[str, Any]) -> Mapping[str, Any]:
    stack = (case.get("contact") or {}).get("stack")
    if stack is None:
        raise ValueError(f"case {case['id']!r} has no stack (contact.stack)")
    return stack


def stack_parameters(case: Mapping[str, Any]) -> list[StackParameter]:
    """The constants of the case's stack that have a range, layers first (from the struck face).

    Layers of the same name (the two electrodes of one print) share their thickness's parameter;
    their thicknesses and ranges must then agree.

    Raises
    ------
    ValueError
        Two layers of one name have different thicknesses or ranges.
    """
    layers = _stack(case)["layers"]
    parameters: list[StackParameter] = []
    for layer in layers:
        parameter = StackParameter(
            f"{layer['name']}: thickness_m", float(layer["thickness_m"]), *map(float, layer["thickness_range_m"])
        )
        same = [p for p in parameters if p.name == parameter.name]
        if same and same[0] != parameter:
            raise ValueError(f"case {case['id']!r}: the layers named {layer['name']!r} differ in thickness or range")
        if not same:
            parameters.append(parameter)
    seen: set[str] = set()
    for layer in layers:
        material = layer["material"]
        if material["name"] in seen:
            continue
        seen.add(material["name"])
        for constant, (low, high) in sorted((material.get("ranges") or {}).items()):
            parameters.append(
                StackParameter(f"{material['name']}: {constant}", float(material[constant]), float(low), float(high))
            )
    return parameters


def with_values(case: Mapping[str, Any], values: Mapping[str, float]) -> dict[str, Any]:
    """A copy of the case with the stack's constants ``values`` (names of :func:`stack_parameters`).

    Raises
    ------
    KeyError
        A name is not a layer's thickness or a layer material's constant.
    """
    changed = copy.deepcopy(dict(case))
    layers = _stack(changed)["layers"]
    for name, value in values.items():
        owner, _, key = name.rpartition(": ")
        hit = False
        for layer in layers:
            if key == "thickness_m" and layer["name"] == owner:
                layer["thickness_m"] = float(value)
                hit = True
            elif layer["material"]["name"] == owner and key in layer["material"]:
                layer["material"][key] = float(value)
                hit = True
        if not hit:
            raise KeyError(f"{name!r} is no constant of case {case['id']!r}'s stack")
    return changed


def calibrated_time_us(
    case: Mapping[str, Any],
    settings: Mapping[str, Any] | None = None,
    method: str = "sem",
    curve: Mapping[str, Any] | None = None,
) -> float:
    """Contact time, us, of ``method`` with the law the continuum's indentation of the case gives
    (``curve``: that law's curve, already computed, as ``ContactCurve.law_curve`` gives it)."""
    law_curve = indentation_curve(case, settings).law_curve() if curve is None else curve
    with_curve = {**case, "contact": {**case["contact"], "curve": law_curve}}
    return 1e6 * run_case(with_curve, method).contact_time_s


def law_longer_high(case: Mapping[str, Any], parameter: StackParameter, method: str = "sem") -> bool:
    """Whether the high end of ``parameter``'s range lengthens the contact (its low end otherwise),
    by ``method`` with the analytic law of the case's bodies (the stack's thin-layer law,
    :func:`~rodimpact.contact.laws.bodies_contact`): a second's work where the continuum's
    indentation takes several."""
    contact = bodies_contact(case.get("contact"))
    bodies = {**case, "contact": contact}
    low, high = (
        run_case(with_values(bodies, {parameter.name: value}), method).contact_time_s
        for value in (parameter.low, parameter.high)
    )
    return bool(high >= low)


def sensor_band(
    case: Mapping[str, Any],
    settings: Mapping[str, Any] | None = None,
    method: str = "sem",
    *,
    nominal_curve: Mapping[str, Any] | None = None,
    axes: bool = False,
) -> CaseBand:
    """The band of one case (see the module docstring).

    Parameters
    ----------
    case : mapping
        A resolved case with a stack and a law calibrated by the indentation.
    settings : mapping, optional
        ``numerics.fem_axi`` of the continuum's indentation.
    method : str
        The 1-D method that runs the calibrated law.
    nominal_curve : mapping, optional
        The case's own calibrated curve (the ``indentation`` rule's), for the nominal stack:
        computed again when not given.
    axes : bool
        Also each constant's range by the continuum, the others nominal (two more indentations
        per constant): the corners are then each constant's lengthening end by the continuum's
        own axis, and the band records whether the time is monotone along every axis. Without
        the axes the lengthening ends are the analytic law's (:func:`law_longer_high`).
    """
    parameters = stack_parameters(case)
    names = tuple(p.name for p in parameters)
    nominal_us = calibrated_time_us(case, settings, method, nominal_curve)
    by_law = tuple(law_longer_high(case, p, method) for p in parameters)
    axis_values, axis_us = {}, {}
    for p in parameters if axes else ():
        values = sorted({p.low, p.nominal, p.high})
        times = [
            nominal_us if v == p.nominal else calibrated_time_us(with_values(case, {p.name: v}), settings, method)
            for v in values
        ]
        axis_values[p.name], axis_us[p.name] = np.asarray(values), np.asarray(times)
    # each parameter's end that lengthens the contact: from its own axis, else by the analytic law
    longer = {}
    for p, high_longer in zip(parameters, by_law, strict=True):
        if axes:
            values, times = axis_values[p.name], axis_us[p.name]
            high_longer = bool(times[values == p.high][0] >= times[values == p.low][0])
        longer[p.name] = (p.high, p.low) if high_longer else (p.low, p.high)
    corners = np.array([[longer[n][0] for n in names], [longer[n][1] for n in names]])
    corner_us = np.array(
        [calibrated_time_us(with_values(case, dict(zip(names, c))), settings, method) for c in corners]
    )
    measured = (case.get("measured") or {}).get("contact_time_us")
    band = CaseBand(
        case_id=str(case["id"]),
        measured_us=math.nan if measured is None else float(measured),
        nominal_us=nominal_us,
        corner_parameters=corners,
        corner_us=corner_us,
        axis_values=axis_values,
        axis_us=axis_us,
        parameters=names,
        law_longer_high=by_law,
    )
    log.info(
        "case %s: nominal %.2f us, band %.2f-%.2f us over %d constants, monotone along every axis: %s",
        band.case_id,
        band.nominal_us,
        band.band_min_us,
        band.band_max_us,
        len(names),
        "not computed" if band.monotone is None else band.monotone,
    )
    if band.monotone is False:
        log.warning(
            "case %s: the contact time is not monotone along some constant's range; the corners may not bound it",
            band.case_id,
        )
    disagree = [
        p.name for p, high in zip(parameters, by_law, strict=True) if axes and (longer[p.name][0] == p.high) != high
    ]
    if disagree:
        log.warning(
            "case %s: the continuum and the analytic law lengthen the contact at opposite ends of %s",
            band.case_id,
            disagree,
        )
    return band


def sensor_band_to_file(
    case: Mapping[str, Any],
    variant: str,
    path: str,
    settings: Mapping[str, Any] | None = None,
    method: str = "sem",
    *,
    curve_file: str | None = None,
    axes: bool = False,
) -> None:
    """:func:`sensor_band` of ``case``, written atomically to ``path``; the nominal stack's law
    from ``curve_file`` (the case's ``indentation`` output) when given.

    Raises
    ------
    ValueError
        ``curve_file`` is another case's curve.
    """
    nominal = None
    if curve_file is not None:
        curve = read_contact_curve(curve_file)
        if curve.case_id != case["id"]:
            raise ValueError(f"curve_file: {curve_file} is the curve of case {curve.case_id!r}, not {case['id']!r}")
        nominal = curve.law_curve()
    write_band(
        path,
        [sensor_band(case, settings, method, nominal_curve=nominal, axes=axes)],
        variant=variant,
        method=method,
        config=dict(case),
    )


def sensor_bands_into(
    cases: Sequence[Mapping[str, Any]],
    variant: str,
    directory: str | Path,
    settings: Mapping[str, Any] | None = None,
    method: str = "sem",
    *,
    curve_files: Mapping[str, str] | None = None,
    axes: bool = False,
) -> list[Path]:
    """:func:`sensor_band_to_file` of every case of one reading, to ``directory/{case}.h5`` (the
    nominal stack's law from ``curve_files[case id]`` where given), the directory appearing whole
    or not at all (:func:`~rodimpact.storage.atomic.atomic_directory`); the files written."""
    directory = Path(directory)
    with atomic_directory(directory) as tmp:
        for case in cases:
            sensor_band_to_file(
                case,
                variant,
                str(tmp / f"{case['id']}.h5"),
                settings,
                method,
                curve_file=(curve_files or {}).get(case["id"]),
                axes=axes,
            )
    return [directory / f"{case['id']}.h5" for case in cases]
