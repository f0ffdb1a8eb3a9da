"""Resolving a case's materials and contact (the configuration layer's part for the bodies).

A material is a name from the materials file or an inline mapping; it resolves to its three
elastic constants, its yield stress and hardening modulus where it gives them (a material
without them stays elastic), and the source's ``ranges`` where the materials file gives them. A case's
``contact`` block resolves, through its law's declared settings, to ``{"law", ...settings}``
with every material resolved, or to nothing for the default law with no settings, so that a
case that does not name a law is the same resolved case as one that names it. Every error
names its field.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from rodimpact.contact.laws import DEFAULT_LAW, LAWS, UnknownLaw, law_of
from rodimpact.model.materials import Material as MaterialModel
from rodimpact.settings.declare import Material, MissingSetting, OptionError
from rodimpact.solvers.registry import CONTACT_KINDS, METHODS

__all__ = ["MATERIAL_FIELDS", "check_law", "check_material_ranges", "resolve_contact", "resolve_material", "runs_law"]

MATERIAL_FIELDS = Material.CONSTANTS

ErrorFactory = Callable[..., Exception]


def check_material_ranges(materials: Mapping[str, Mapping[str, Any]], error: ErrorFactory) -> None:
    """Each material's plastic constants are sound (a positive yield stress, a hardening modulus
    with it and below Young's) and its ``ranges`` are non-empty and hold the nominal value.

    ``error(message, field=...)`` builds the exception raised.
    """
    for name, material in materials.items():
        plastic = Material.plastic_problem(
            material["youngs_modulus_pa"], material.get("yield_stress_pa"), material.get("hardening_modulus_pa")
        )
        if plastic is not None:
            raise error(plastic[1], field=f"materials.{name}.{plastic[0]}")
        for key, (low, high) in material.get("ranges", {}).items():
            if key not in material:
                raise error(
                    f"a range of {key}, which the material does not give", field=f"materials.{name}.ranges.{key}"
                )
            if not low < high:
                raise error(
                    f"range [{low:g}, {high:g}] is empty (low must be < high)", field=f"materials.{name}.ranges.{key}"
                )
            if not low <= material[key] <= high:
                raise error(
                    f"nominal {material[key]:g} lies outside its range [{low:g}, {high:g}]",
                    field=f"materials.{name}.ranges.{key}",
                )


def resolve_material(
    value: str | Mapping[str, Any], materials: Mapping[str, Mapping[str, Any]], error: ErrorFactory, field: str
) -> dict[str, Any]:
    """A material name or inline mapping as ``{"name", constants..., ["ranges"]}``."""
    if isinstance(value, str):
        if value not in materials:
            raise error(f"unknown material {value!r}; known: {', '.join(materials)}", field=field)
        name, data = value, materials[value]
    else:
        name, data = value.get("name"), value
    resolved: dict[str, Any] = {"name": name, **{key: float(data[key]) for key in MATERIAL_FIELDS}}
    # a plastic constant only where the material gives it: an elastic material resolves as ever
    resolved.update({key: float(data[key]) for key in Material.PLASTIC if data.get(key) is not None})
    plastic = Material.plastic_problem(
        resolved["youngs_modulus_pa"], resolved.get("yield_stress_pa"), resolved.get("hardening_modulus_pa")
    )
    if plastic is not None:
        where = f"materials.{value}" if isinstance(value, str) else field
        raise error(plastic[1], field=f"{where}.{plastic[0]}")
    if data.get("ranges"):
        resolved["ranges"] = {key: [float(x) for x in data["ranges"][key]] for key in sorted(data["ranges"])}
    return resolved


def resolve_contact(
    contact: Mapping[str, Any] | None, materials: Mapping[str, Mapping[str, Any]], error: ErrorFactory
) -> dict[str, Any]:
    """``{"contact": resolved}``, or ``{}`` for the default law with no settings.

    The law's declared settings (``settings`` of its class in
    :data:`~rodimpact.contact.laws.LAWS`) say which keys it takes, which it needs, their
    bounds and defaults; materials are resolved from the materials file. The resolved block
    is ``{"law": name, ...every setting, defaults filled in}``.

    Raises (through ``error``, with the field) on an unknown law, a key the law does not
    take, a setting it needs and is not given, a value out of its bounds, an unknown
    material.
    """
    if contact is None:
        return {}
    try:
        law = law_of(contact)
    except UnknownLaw as unknown:
        raise error(str(unknown), field=UnknownLaw.field) from None
    declared = law.settings.settings()
    for key in contact:
        if key != "law" and key not in declared:
            takers = [name for name, other in LAWS.items() if key in other.settings.settings()]
            hint = (
                f"laws that take it: {', '.join(takers)}"
                if takers
                else f"its settings: {', '.join(declared) or 'none'}"
            )
            raise error(f"the {law.name} law takes no {key!r}; {hint}", field=f"contact.{key}")

    def material(value: Any, path: str) -> dict[str, Any]:
        return resolve_material(value, materials, error, f"contact.{path}")

    try:
        settings = law.settings.from_settings({k: v for k, v in contact.items() if k != "law"}, material=material)
    except MissingSetting as missing:
        raise error(f"missing; the {law.name} law needs it", field=f"contact.{missing.field}") from None
    except OptionError as wrong:
        raise error(wrong.reason, field=f"contact.{wrong.field}") from None
    resolved = settings.as_settings()
    if law.name == DEFAULT_LAW and not resolved:
        return {}
    return {"contact": {"law": law.name, **resolved}}


def runs_law(case: Mapping[str, Any], method: str) -> bool:
    """Whether ``method`` can run the resolved case's contact law: the law's ``method_contact``
    holds how the method treats the contact (the registry's ``Method.contact``)."""
    return METHODS[method].contact in law_of(case.get("contact")).method_contact


def check_law(case: Mapping[str, Any], error: ErrorFactory) -> None:
    """Every method of the case (and of its sweep) can run its contact law (the law's
    ``method_contact``; a law with memory, a method that carries it: the registry's
    ``Method.memory``), the case sets no field the law conflicts with (``conflicts``), and the
    law's settings suit the case's materials (``bodies_problem``)."""
    law = law_of(case.get("contact"))
    for field, why in law.conflicts.items():
        if case.get(field) is not None:
            raise error(f"the {law.name} law cannot be combined with {field!r}: {why}", field="contact.law")
    problem = law.bodies_problem(
        case.get("contact") or {},
        MaterialModel.from_mapping(case["impactor"]["material"]),
        MaterialModel.from_mapping(case["rod"]["material"]),
    )
    if problem is not None:
        raise error(problem[1], field=f"contact.{problem[0]}")
    own = list(case["methods"])
    swept = [m for m in (case.get("sweep") or {}).get("methods", []) if m not in own]
    for index, name in enumerate(own + swept):
        if law.memory and not METHODS[name].memory:
            can = [other for other, declared in METHODS.items() if declared.memory]
            raise error(
                f"method {name!r} cannot carry the memory of the {law.name} law (its largest approach and the "
                f"dent it leaves); methods that can: {', '.join(can)}",
                field=f"methods[{index}]" if index < len(own) else "sweep.methods",
            )
        if not runs_law(case, name):
            kind = METHODS[name].contact
            can = [other for other, other_law in LAWS.items() if kind in other_law.method_contact]
            raise error(
                f"method {name!r} {CONTACT_KINDS[kind]} and cannot take the {law.name} law; "
                f"laws it can take: {', '.join(can)}",
                field=f"methods[{index}]" if index < len(own) else "sweep.methods",
            )
