"""The contact laws by name, as a case names them (``contact: {law: <name>}``).

Adding a law is one module beside this one (a :class:`~rodimpact.contact.law.ContactLaw`
with a ``from_bodies`` constructor) and one entry in :data:`LAWS`; no solver changes.
"""

from __future__ import annotations

from typing import Any, Mapping

from rodimpact.contact.hertz import ElasticMaterial, HertzLaw
from rodimpact.contact.law import ContactLaw

__all__ = ["DEFAULT_LAW", "LAWS", "build_law"]

#: Law name -> law class (each has ``from_bodies(spec, sphere_radius_m, impactor, rod)``).
LAWS: dict[str, type[ContactLaw]] = {
    HertzLaw.name: HertzLaw,
}
#: The law of a case that names none.
DEFAULT_LAW = HertzLaw.name


def build_law(spec: Mapping[str, Any] | None, sphere_radius_m: float, impactor: ElasticMaterial,
              rod: ElasticMaterial) -> ContactLaw:
    """The contact law of a case.

    Parameters
    ----------
    spec : mapping or None
        The case's ``contact`` block, ``{"law": name, ...parameters}``; None: :data:`DEFAULT_LAW`.
    sphere_radius_m : float
        Radius of the impactor's spherical nose, m.
    impactor, rod : ElasticMaterial
        The two bodies' materials.

    Raises
    ------
    KeyError
        The law is unknown (the message lists the known ones).
    """
    spec = {"law": DEFAULT_LAW} if spec is None else spec
    name = spec.get("law", DEFAULT_LAW)
    if name not in LAWS:
        raise KeyError(f"unknown contact law {name!r}; known: {', '.join(LAWS)}")
    return LAWS[name].from_bodies(spec, sphere_radius_m, impactor, rod)
