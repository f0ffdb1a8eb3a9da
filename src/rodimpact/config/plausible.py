"""Physical plausibility of a run before any job: numbers double precision carries, a contact
the nose's sphere can make, and a cost within the project's budget.

The configuration layer calls :func:`check_plausible` for every run of every case and sweep
point, before its options are checked against the case. A run is refused when

* a scale of its case cannot be computed, or lies outside [1/:data:`REPRESENTABLE`,
  :data:`REPRESENTABLE`] (then any product or quotient of two scales is a normal double);
  the scales are the inputs and the times, lengths, forces and impedances derived from them
  (:func:`case_scales`);
* the largest approach on a rigid rod reaches the nose's radius (the contact radius
  sqrt(R alpha) would reach R: no spherical contact of that size);
* its method's cost model (the registry's ``cost``) needs more steps than the method's
  step budget, or more time or memory than :class:`Budget` (``limits`` in config.yaml).

The finding names the field that causes it: of the case's inputs (its bodies and its
method's settings), the one whose return to a reference value (the paper's Table 1 model
for the bodies, the setting's default for the numerics) relieves the check the most
(:func:`culprit`).
"""

from __future__ import annotations

import copy
import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from rodimpact.contact.laws import DEFAULT_LAW
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.options import OptionError
from rodimpact.solvers.registry import METHODS

__all__ = [
    "Budget",
    "Finding",
    "REFERENCE",
    "REPRESENTABLE",
    "case_scales",
    "check_plausible",
    "culprit",
    "machine_memory_mib",
]

#: Every scale of a case lies within [1 / REPRESENTABLE, REPRESENTABLE] (its SI value).
REPRESENTABLE = 1e150
#: The reference of each input of the bodies: the paper's Table 1 model (steel on steel).
REFERENCE: dict[str, float] = {
    "impactor.mass_kg": 0.5,
    "impactor.radius_m": 0.01,
    "impactor.velocity_m_s": 1.0,
    "rod.length_m": 0.5,
    "rod.area_m2": 5.0e-5,
    "rod.radius_m": math.sqrt(5.0e-5 / math.pi),
    **{
        f"{body}.material.{key}": value
        for body in ("impactor", "rod")
        for key, value in (("youngs_modulus_pa", 2.1e11), ("poisson_ratio", 0.3), ("density_kg_m3", 7800.0))
    },
}
_UNITS = {
    "mass_kg": "kg",
    "radius_m": "m",
    "velocity_m_s": "m/s",
    "length_m": "m",
    "area_m2": "m^2",
    "youngs_modulus_pa": "Pa",
    "density_kg_m3": "kg/m^3",
    "poisson_ratio": "",
}


def machine_memory_mib() -> float:
    """This machine's physical memory, MiB (the memory budget's default)."""
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2.0**20


@dataclass(frozen=True)
class Budget:
    """What one run may cost (config.yaml's ``limits``).

    Attributes
    ----------
    run_time_s : float
        Estimated solve time of one run, s.
    memory_mib : float
        Estimated memory of one run's solver, MiB.
    """

    run_time_s: float
    memory_mib: float

    @classmethod
    def of(cls, limits: Mapping[str, Any]) -> Budget:
        """From config.yaml's ``limits`` (``memory_mib`` null: this machine's memory)."""
        memory = limits.get("memory_mib")
        return cls(float(limits["run_time_s"]), machine_memory_mib() if memory is None else float(memory))


@dataclass(frozen=True)
class Finding:
    """Why a run is refused.

    Attributes
    ----------
    field : str
        The dotted field at fault, as the case file spells it (``numerics.<method>.<name>``
        for a setting).
    reason : str
        One sentence with the derived number that breaks.
    setting : bool
        The field is a method's setting (it may come from config.yaml's ``numerics``).
    budget : bool
        The field is config.yaml's ``limits`` (no input of the case relieves the cost).
    """

    field: str
    reason: str
    setting: bool = False
    budget: bool = False


def case_scales(case: Mapping[str, Any]) -> tuple[dict[str, tuple[float, str]], ImpactProblem]:
    """The case's scales, SI: its inputs and what the methods derive from them, as
    name -> (value, unit); and the problem they come from.

    Raises
    ------
    ArithmeticError, ValueError
        A scale cannot be computed in double precision.
    """
    problem = ImpactProblem.from_case(case, estimate=True)
    rigid, rod = problem.rigid_contact, problem.rod
    imp = case["impactor"]
    scales = {
        "impactor mass m": (problem.mass_kg, "kg"),
        "impact velocity v0": (problem.velocity_m_s, "m/s"),
        "nose radius R": (float(imp["radius_m"]), "m"),
        "rod length l": (rod.length_m, "m"),
        "rod cross-section S": (rod.area_m2, "m^2"),
        "impactor's Young's modulus": (float(imp["material"]["youngs_modulus_pa"]), "Pa"),
        "impactor's density": (float(imp["material"]["density_kg_m3"]), "kg/m^3"),
        "rod's Young's modulus": (rod.material.youngs_modulus_pa, "Pa"),
        "rod's density": (rod.material.density_kg_m3, "kg/m^3"),
        "rigid-rod contact time t_H": (rigid.contact_time_s, "s"),
        "rigid-rod peak force P_H": (rigid.peak_force_N, "N"),
        "rigid-rod largest approach alpha_H": (rigid.max_approach_m, "m"),
        "rod wave speed a": (rod.wave_speed, "m/s"),
        "rod impedance Z": (rod.impedance, "kg/s"),
        "wave round trip 2T": (rod.reflection_period, "s"),
        "contact time estimate": (problem.contact_time_estimate(), "s"),
    }
    return scales, problem


def _scales_finding(case: Mapping[str, Any]) -> tuple[float, str] | None:
    """(badness, reason) of the scales check: decades beyond the range (inf: not computable)."""
    try:
        scales, problem = case_scales(case)
    except (ArithmeticError, ValueError) as exc:
        return math.inf, f"its scales cannot be computed in double precision ({exc})"
    worst, reason = 0.0, ""
    for name, (value, unit) in scales.items():
        finite = math.isfinite(value) and value != 0.0
        excess = abs(math.log10(abs(value))) - math.log10(REPRESENTABLE) if finite else math.inf
        if excess > worst:
            worst = excess
            reason = (
                f"its {name} = {value:.3g} {unit} lies outside [{1 / REPRESENTABLE:g}, {REPRESENTABLE:g}] "
                f"{unit}, beyond what double precision carries through the solvers' products"
            )
    if worst > 0.0:
        return worst, reason
    approach, radius = problem.rigid_contact.max_approach_m, float(case["impactor"]["radius_m"])
    if approach >= radius:
        return (
            math.log10(approach / radius) + 1e-12,
            f"its largest approach on a rigid rod, alpha_H = {approach:.3g} m, reaches the nose radius "
            f"R = {radius:.3g} m (the contact radius sqrt(R alpha) would reach R): no spherical contact "
            "of that size",
        )
    return None


def _cost_finding(case: Mapping[str, Any], method: str, budget: Budget) -> tuple[float, str] | None:
    """(badness, reason) of ``method``'s cost: decades beyond the first limit it breaks."""
    spec = METHODS[method]
    try:
        cost = spec.estimate(case, case["numerics"][method])
    except OptionError:
        return None  # the options' own check names it
    except (ArithmeticError, ValueError) as exc:
        return math.inf, f"{method}'s cost cannot be estimated in double precision ({exc})"
    if cost.exceeds_step_limit:
        return (
            math.log10(cost.steps_needed / cost.step_limit),
            f"{method} would need about {cost.steps_needed:.3g} steps of {cost.time_step_s:.3g} s for the "
            f"estimated contact, beyond its step budget max_steps = {cost.step_limit:.0f}",
        )
    if not cost.solve_s <= budget.run_time_s:
        return (
            math.log10(cost.solve_s / budget.run_time_s),
            f"{method} would take about {cost.solve_s:.3g} s ({cost.steps:.3g} steps of {cost.time_step_s:.3g} s), "
            f"beyond the budget limits.run_time_s = {budget.run_time_s:g} s of config.yaml",
        )
    if not cost.mem_mib <= budget.memory_mib:
        return (
            math.log10(cost.mem_mib / budget.memory_mib),
            f"{method} would need about {cost.mem_mib:.3g} MiB, beyond the budget limits.memory_mib = "
            f"{budget.memory_mib:.0f} MiB",
        )
    return None


def _with(case: Mapping[str, Any], field: str, value: Any) -> dict[str, Any]:
    """A copy of the resolved ``case`` with the dotted ``field`` set to ``value`` (a rod radius
    sets the area it gives)."""
    changed = copy.deepcopy(dict(case))
    *parents, leaf = field.split(".")
    node = changed
    for key in parents:
        node = node[key]
    node[leaf] = value
    if field == "rod.radius_m":
        changed["rod"]["area_m2"] = math.pi * value**2
    return changed


def _candidates(case: Mapping[str, Any], method: str | None) -> list[tuple[str, Any, bool]]:
    """(field, reference, is a setting) of the inputs that may cause a finding."""
    out: list[tuple[str, Any, bool]] = []
    for field, reference in REFERENCE.items():
        if field == "rod.area_m2" and case["rod"].get("radius_m") is not None:
            continue
        if field == "rod.radius_m" and case["rod"].get("radius_m") is None:
            continue
        out.append((field, reference, False))
    if method is not None:
        defaults = METHODS[method].options().as_settings()
        for name, value in case["numerics"][method].items():
            if value != defaults.get(name):
                out.append((f"numerics.{method}.{name}", defaults.get(name), True))
    return out


def culprit(
    case: Mapping[str, Any], badness: Callable[[Mapping[str, Any]], float], method: str | None = None
) -> tuple[str, bool] | None:
    """The input whose return to its reference lowers ``badness(case)`` the most: (field, is
    a setting); ties go to the first in the order of :data:`REFERENCE`, then the settings.
    A contact law other than the default whose replacement by the default clears the finding
    is the culprit first (:func:`_law_culprit`). None when no single input lowers it."""
    law = _law_culprit(case, badness)
    if law is not None:
        return law
    best, found = badness(case), None
    for field, reference, setting in _candidates(case, method):
        try:
            value = badness(_with(case, field, reference))
        except (ArithmeticError, ValueError, OptionError):
            continue
        if value < best:
            best, found = value, (field, setting)
    return found


def _law_culprit(case: Mapping[str, Any], badness: Callable[[Mapping[str, Any]], float]) -> tuple[str, bool] | None:
    """The case's contact law, when the default law on the same bodies clears the finding: its
    one numeric setting (``contact.stiffness_n_per_m`` of a spring), else ``contact.law``."""
    contact = case.get("contact") or {}
    if contact.get("law") in (None, DEFAULT_LAW):
        return None
    plain = {key: value for key, value in case.items() if key != "contact"}
    try:
        if badness(plain) > 0.0 or badness(case) <= 0.0:
            return None
    except (ArithmeticError, ValueError, OptionError):
        return None
    numeric = [key for key, value in contact.items() if isinstance(value, (int, float)) and not isinstance(value, bool)]
    return (f"contact.{numeric[0]}" if len(numeric) == 1 else "contact.law", False)


def _furthest(case: Mapping[str, Any]) -> str:
    """The input of the bodies furthest (in decades) from its reference."""

    def distance(field: str) -> float:
        node: Any = case
        for key in field.split("."):
            node = node[key]
        try:
            return abs(math.log10(abs(float(node)) / REFERENCE[field]))
        except (TypeError, ValueError, ArithmeticError):
            return math.inf

    return max((field for field, _, _ in _candidates(case, None)), key=distance)


def _badness(finding: Callable[[Mapping[str, Any]], tuple[float, str] | None]) -> Callable[[Mapping[str, Any]], float]:
    def measure(case: Mapping[str, Any]) -> float:
        result = finding(case)
        return 0.0 if result is None else result[0]

    return measure


def _named(field: str, case: Mapping[str, Any], reason: str) -> str:
    """The reason with the field's value (and its material's name) in front."""
    parts = field.split(".")
    if len(parts) == 3 and parts[1] == "material":
        material = case[parts[0]]["material"]
        value = material[parts[2]]
        label = f"material {material['name']!r}: " if material.get("name") else ""
        return f"{label}{parts[2]} = {value:g} {_UNITS.get(parts[2], '')}".rstrip() + f": {reason}"
    node: Any = case
    for key in parts:
        node = node[key]
    unit = _UNITS.get(parts[-1], "")
    shown = f"{node:g}" if isinstance(node, (int, float)) and not isinstance(node, bool) else repr(node)
    return f"{shown} {unit}".rstrip() + f": {reason}"


def check_plausible(case: Mapping[str, Any], budget: Budget) -> Finding | None:
    """The first reason to refuse the case's runs (None: every run is plausible).

    Parameters
    ----------
    case : mapping
        A resolved case (its ``methods`` and their ``numerics``).
    budget : Budget
        What one run may cost.
    """
    scales = _scales_finding(case)
    if scales is not None:
        field, setting = culprit(case, _badness(_scales_finding)) or (_furthest(case), False)
        return Finding(_material_field(field, case), _named(field, case, scales[1]), setting)
    for method in case["methods"]:
        cost = _cost_finding(case, method, budget)
        if cost is not None:
            found = culprit(case, _badness(lambda c, method=method: _cost_finding(c, method, budget)), method)
            if found is None:  # an ordinary case: the budget itself is the field at fault
                limit = "memory_mib" if "limits.memory_mib" in cost[1] else "run_time_s"
                return Finding(f"limits.{limit}", cost[1], budget=True)
            field, setting = found
            return Finding(_material_field(field, case), _named(field, case, cost[1]), setting)
    return None


def _material_field(field: str, case: Mapping[str, Any]) -> str:
    """A material's constant is the case's ``<body>.material`` when the material is named."""
    parts = field.split(".")
    if len(parts) == 3 and parts[1] == "material" and case[parts[0]]["material"].get("name"):
        return f"{parts[0]}.material"
    return field
