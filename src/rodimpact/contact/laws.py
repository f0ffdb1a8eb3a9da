"""The contact laws by name, as a case names them (``contact: {law: <name>}``).

Adding a law is one module beside this one (a :class:`~rodimpact.contact.law.ContactLaw`
with a ``from_bodies`` constructor) and one entry in :data:`LAWS`; no solver changes.
"""

from __future__ import annotations

from typing import Any, Mapping

from rodimpact.contact.film import HertzFilmLaw
from rodimpact.contact.hertz import ElasticMaterial, HertzLaw
from rodimpact.contact.law import ContactLaw
from rodimpact.contact.tabulated import TabulatedLaw

__all__ = ["DEFAULT_LAW", "LAWS", "UnknownLaw", "build_law"]

#: Law name -> law class (each has ``from_bodies(spec, sphere_radius_m, impactor, rod)``).
LAWS: dict[str, type[ContactLaw]] = {law.name: law for law in (HertzLaw, HertzFilmLaw, TabulatedLaw)}
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


def build_law(spec: Mapping[str, Any] | None, sphere_radius_m: float, impactor: ElasticMaterial,
              rod: ElasticMaterial, *, estimate: bool = False) -> ContactLaw:
    """The contact law of a case.

    Parameters
    ----------
    spec : mapping or None
        The case's ``contact`` block, ``{"law": name, ...parameters}``; None: :data:`DEFAULT_LAW`.
    sphere_radius_m : float
        Radius of the impactor's spherical nose, m.
    impactor, rod : ElasticMaterial
        The two bodies' materials.
    estimate : bool
        For an estimate made before the law's data exist (the configuration check, the cost
        model): a law built from data it does not have yet (``tabulated`` without its curve)
        is replaced by the law of the same bodies it calibrates (its ``estimate_law``).

    Raises
    ------
    UnknownLaw
        The law is unknown (the message lists the known ones).
    """
    spec = {"law": DEFAULT_LAW} if spec is None else spec
    name = spec.get("law", DEFAULT_LAW)
    if name not in LAWS:
        raise UnknownLaw(name)
    law = LAWS[name]
    if estimate and hasattr(law, "estimate_law") and spec.get("curve") is None:
        return law.estimate_law(spec, sphere_radius_m, impactor, rod)
    return law.from_bodies(spec, sphere_radius_m, impactor, rod)
