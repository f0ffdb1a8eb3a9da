"""Resolving a case's materials and contact (the configuration layer's part for the bodies).

A material is a name from the materials file or an inline mapping; it resolves to its three
constants (and the source's ``ranges`` where the materials file gives them). A case's
``contact`` block resolves to ``{"law", "film", "from"}`` with the film's material resolved,
or to nothing for Hertz's law with no film (the default), so that a case that does not name
a law is the same resolved case as one that names ``hertz``. Every error names its field.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from rodimpact.contact.laws import DEFAULT_LAW, LAWS
from rodimpact.solvers.registry import METHODS

__all__ = ["MATERIAL_FIELDS", "check_law", "check_material_ranges", "resolve_contact", "resolve_material"]

MATERIAL_FIELDS = ("youngs_modulus_pa", "poisson_ratio", "density_kg_m3")
#: The film's thickness range when its source gives none: +/- this fraction.
DEFAULT_THICKNESS_TOLERANCE = 0.10

ErrorFactory = Callable[..., Exception]


def check_material_ranges(materials: Mapping[str, Mapping[str, Any]], error: ErrorFactory) -> None:
    """Each material's ``ranges`` are non-empty and hold the nominal value.

    ``error(message, field=...)`` builds the exception raised.
    """
    for name, material in materials.items():
        for key, (low, high) in material.get("ranges", {}).items():
            if not low < high:
                raise error(f"range [{low:g}, {high:g}] is empty (low must be < high)",
                            field=f"materials.{name}.ranges.{key}")
            if not low <= material[key] <= high:
                raise error(f"nominal {material[key]:g} lies outside its range [{low:g}, {high:g}]",
                            field=f"materials.{name}.ranges.{key}")


def resolve_material(value: str | Mapping[str, Any], materials: Mapping[str, Mapping[str, Any]],
                     error: ErrorFactory, field: str) -> dict[str, Any]:
    """A material name or inline mapping as ``{"name", constants..., ["ranges"]}``."""
    if isinstance(value, str):
        if value not in materials:
            raise error(f"unknown material {value!r}; known: {', '.join(materials)}", field=field)
        name, data = value, materials[value]
    else:
        name, data = value.get("name"), value
    resolved: dict[str, Any] = {"name": name, **{key: float(data[key]) for key in MATERIAL_FIELDS}}
    if data.get("ranges"):
        resolved["ranges"] = {key: [float(x) for x in data["ranges"][key]] for key in sorted(data["ranges"])}
    return resolved


def resolve_contact(contact: Mapping[str, Any] | None, materials: Mapping[str, Mapping[str, Any]],
                    error: ErrorFactory) -> dict[str, Any]:
    """``{"contact": resolved}``, or ``{}`` for Hertz's law with no film (the default).

    Raises (through ``error``) on an unknown law, a law without what it needs (hertz_film
    without a film, tabulated without ``from``), a film on the hertz law, an unknown film
    material or a thickness outside its range.
    """
    if contact is None:
        return {}
    law = contact["law"]
    if law not in LAWS:
        raise error(f"unknown contact law {law!r}; known: {', '.join(LAWS)}", field="contact.law")
    film = contact.get("film")
    if law == "hertz_film" and film is None:
        raise error("the hertz_film law needs a film (thickness_m, material)", field="contact.film")
    if law == DEFAULT_LAW and film is not None:
        raise error("the hertz law takes no film; use law hertz_film (or tabulated) for a film", field="contact.film")
    if law == "tabulated" and "from" not in contact:
        raise error("the tabulated law needs 'from' (where its curve comes from)", field="contact.from")
    if law == DEFAULT_LAW:
        return {}
    resolved: dict[str, Any] = {"law": law}
    if "from" in contact:
        resolved["from"] = contact["from"]
    if film is not None:
        thickness = float(film["thickness_m"])
        tolerance = DEFAULT_THICKNESS_TOLERANCE
        low, high = film.get("thickness_range_m", [(1 - tolerance) * thickness, (1 + tolerance) * thickness])
        if not (low < high and low <= thickness <= high):
            raise error(f"the thickness {thickness:g} m must lie inside a non-empty range, got [{low:g}, {high:g}]",
                        field="contact.film.thickness_range_m")
        resolved["film"] = {
            "thickness_m": thickness,
            "thickness_range_m": [float(low), float(high)],
            "area_m2": None if film.get("area_m2") is None else float(film["area_m2"]),
            "material": resolve_material(film["material"], materials, error, "contact.film.material"),
        }
    return {"contact": resolved}


def check_law(case: Mapping[str, Any], error: ErrorFactory) -> None:
    """Every method of the case (and of its sweep) can take its contact law (a continuum
    method cannot take a law that is only a curve)."""
    law = LAWS[(case.get("contact") or {}).get("law", DEFAULT_LAW)]
    own = list(case["methods"])
    swept = [m for m in (case.get("sweep") or {}).get("methods", []) if m not in own]
    for index, name in enumerate(own + swept):
        if METHODS[name].contact == "continuum" and not law.continuum_form:
            raise error(f"method {name!r} resolves the contact in the continuum and cannot take the {law.name} law "
                        "(a force-approach curve); run it on the case's bodies (law hertz or hertz_film)",
                        field=f"methods[{index}]" if index < len(own) else "sweep.methods")
