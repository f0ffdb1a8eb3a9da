"""The contact laws by name, as a case names them (``contact: {law: <name>, ...settings}``).

Adding a law is one module beside this one (a :class:`~rodimpact.contact.law.ContactLaw`
that declares its name, label, settings, needs, methods and conflicts, with a
``from_bodies`` constructor) and one entry in :data:`LAWS`; no solver, schema, check, rule or
table changes: they read the declarations through the functions below.

- :func:`law_of`: the law class of a resolved ``contact`` block;
- :func:`contact_schema`: the ``contact`` block's JSON schema, made from the declarations;
- :func:`bodies_contact`: the contact block of the analytic law of a case's bodies;
- :func:`build_law`: the law of a case, ready for a solver.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from rodimpact.contact.film import HertzFilmLaw
from rodimpact.contact.hertz import ElasticMaterial, HertzLaw
from rodimpact.contact.law import ContactLaw
from rodimpact.contact.spring import SpringLaw
from rodimpact.contact.stack import HertzStackLaw
from rodimpact.contact.tabulated import TabulatedLaw
from rodimpact.contact.thornton import ThorntonLaw
from rodimpact.settings.declare import Setting

__all__ = ["DEFAULT_LAW", "LAWS", "UnknownLaw", "bodies_contact", "build_law", "contact_schema", "law_of"]

#: Law name -> law class, in the order messages and the schema list them.
LAWS: dict[str, type[ContactLaw]] = {
    law.name: law for law in (HertzLaw, HertzFilmLaw, HertzStackLaw, TabulatedLaw, SpringLaw, ThorntonLaw)
}
#: The law of a case that names none.
DEFAULT_LAW = HertzLaw.name


class UnknownLaw(KeyError):
    """A law name that is not in :data:`LAWS` (``name``: the name asked for)."""

    field = "contact.law"

    def __init__(self, name: str) -> None:
        self.name = name
        super().__init__(name)

    def __str__(self) -> str:
        return f"unknown contact law {self.name!r}; known: {', '.join(LAWS)}"


def law_of(contact: Mapping[str, Any] | None) -> type[ContactLaw]:
    """The law class of a case's resolved ``contact`` block (None or no ``law``: :data:`DEFAULT_LAW`).

    Raises
    ------
    UnknownLaw
        The block names a law that is not in :data:`LAWS`.
    """
    name = (contact or {}).get("law", DEFAULT_LAW)
    if name not in LAWS:
        raise UnknownLaw(name)
    return LAWS[name]


def contact_schema(material_ref: str = "#/$defs/material") -> dict[str, Any]:
    """The JSON schema of a case's ``contact`` block, from the laws' declarations.

    ``law`` is one of :data:`LAWS`; the other keys are the union of every law's settings
    (each with its full schema; two laws that declare the same key declare it alike). Which
    keys a given law takes, and which it requires, the configuration checks per law
    (``rodimpact.config.bodies.resolve_contact``), as it checks each method's numerics.

    Parameters
    ----------
    material_ref : str
        The schema a material setting refers to (a name or an inline material; the resolved
        case's complete material).

    Raises
    ------
    ValueError
        Two laws declare one key differently.
    """
    properties: dict[str, Any] = {
        "law": {
            "title": "contact law",
            "type": "string",
            "enum": list(LAWS),
            "description": "The law's name (rodimpact.contact.laws.LAWS).",
        }
    }
    owners: dict[str, tuple[str, Setting]] = {}
    for name, law in LAWS.items():
        for key, meta in law.settings.settings().items():
            if key in owners:
                if _value_kind(owners[key][1]) != _value_kind(meta):
                    raise ValueError(
                        f"contact laws {owners[key][0]!r} and {name!r} declare the setting {key!r} differently"
                    )
                continue
            owners[key] = (name, meta)
            declared = [other.settings.settings()[key] for other in LAWS.values() if key in other.settings.settings()]
            takers = [n for n, other in LAWS.items() if key in other.settings.settings()]
            union = dataclasses.replace(meta, nullable=any(m.nullable for m in declared))
            sub = union.json_schema(material_ref=material_ref)  # no default: a law's own fills it in
            sub["description"] = f"{sub['description']} Laws: {', '.join(takers)}."
            properties[key] = sub
    laws = " ".join(f"`{name}`: {(law.__doc__ or '').strip().splitlines()[0]}" for name, law in LAWS.items())
    return {
        "description": f"The contact between impactor and rod (default {{law: {DEFAULT_LAW}}}). {laws}",
        "type": "object",
        "additionalProperties": False,
        "required": ["law"],
        "properties": properties,
    }


def _value_kind(meta: Setting) -> tuple[Any, ...]:
    """What a setting's values are, whatever its doc and whether it may be null."""
    return (
        meta.kind,
        meta.unit,
        meta.items,
        meta.choices,
        meta.minimum,
        meta.exclusive_minimum,
        meta.maximum,
        meta.exclusive_maximum,
    )


def bodies_contact(contact: Mapping[str, Any] | None) -> dict[str, Any] | None:
    """The ``contact`` block of the analytic law of a case's bodies: the thin-layer law with
    the case's film or stack, or None (:data:`DEFAULT_LAW`) with neither. It is the law a
    curve calibrates, and stands in for a law whose curve does not exist yet."""
    contact = contact or {}
    if contact.get("stack") is not None:
        return {"law": HertzStackLaw.name, "stack": contact["stack"]}
    film = contact.get("film")
    return None if film is None else {"law": HertzFilmLaw.name, "film": film}


def build_law(
    spec: Mapping[str, Any] | None,
    sphere_radius_m: float,
    impactor: ElasticMaterial,
    rod: ElasticMaterial,
    *,
    estimate: bool = False,
) -> ContactLaw:
    """The contact law of a case.

    Parameters
    ----------
    spec : mapping or None
        The case's resolved ``contact`` block, ``{"law": name, ...settings}``; None:
        :data:`DEFAULT_LAW`.
    sphere_radius_m : float
        Radius of the impactor's spherical nose, m.
    impactor, rod : ElasticMaterial
        The two bodies' materials.
    estimate : bool
        For an estimate made before the law's data exist (the configuration check, the cost
        model): a law whose curve a rule computes (``needs.curve_rule``), given without it, is
        replaced by the analytic law of the same bodies (:func:`bodies_contact`).

    Raises
    ------
    UnknownLaw
        The law is unknown (the message lists the known ones).
    """
    law = law_of(spec)
    if spec is None:
        spec = {"law": law.name}
    if estimate and law.needs.curve_rule is not None and spec.get("curve") is None:
        return build_law(bodies_contact(spec), sphere_radius_m, impactor, rod)
    return law.from_bodies(spec, sphere_radius_m, impactor, rod)
