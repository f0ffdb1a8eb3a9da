"""A stack of bonded layers on the rod's struck end (a sensor as built): the ``hertz_stack`` law.

A piezoelectric film sensor is more than its polymer: an electrode on each face and the bond
line that glues it to the rod are layers of their own. A case gives the layers from the struck
face to the rod (``contact.stack.layers``), each with its thickness and the range of it, its
material (with the material's ranges) and its source. :class:`Stack` is that geometry, read
from a case's contact block by :meth:`Stack.of` whether the block gives one ``film`` (a stack
of one layer) or a ``stack``; the continuum meshes each layer as its own bonded region, and
the law calibrated by the continuum indents it.

The analytic law here is the thin-layer approximation extended to layers: where the contact
radius is much larger than the stack, each column of every layer is compressed with no lateral
strain, so the layers are beds of springs in series, of compliance h_i / M_i per unit area
(M_i the constrained modulus of :func:`~rodimpact.contact.film.constrained_modulus`). The
stack then acts as one layer of thickness H = sum h_i and constrained modulus

    M_eff = H / sum(h_i / M_i),

and the law is :class:`~rodimpact.contact.film.HertzFilmLaw` with c = pi M_eff R / H. It is an
approximation, too soft at the contact sizes of the experiment (the continuum's indentation
measures its error: ``results/tables/film_indentation.csv``); docs/contact-laws.md.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from rodimpact.contact.film import FilmLayer, HertzFilmLaw, film_constant
from rodimpact.contact.hertz import ElasticMaterial, hertz_constant
from rodimpact.contact.law import LawSettings, Needs
from rodimpact.settings.declare import REQUIRED, Material, OptionError, Settings, setting

__all__ = ["HertzStackLaw", "HertzStackSettings", "LayerSettings", "Stack", "StackSettings"]


@dataclass(frozen=True, kw_only=True)
class LayerSettings(Settings):
    """One layer of a stack bonded on the rod's struck end."""

    name: str = setting(REQUIRED, "What the layer is, in words (e.g. top electrode, piezo film, bond line).", kind=str)
    thickness_m: float = setting(REQUIRED, "Thickness of the layer.", unit="m", exclusive_minimum=0)
    thickness_range_m: list[float] = setting(
        REQUIRED,
        "[low, high] of the thickness, from the layer's source (or a bracket the source explains); "
        "the prediction band reads it.",
        unit="m",
        exclusive_minimum=0,
        items=(2, 2),
    )
    material: Mapping[str, Any] = setting(
        REQUIRED,
        "The layer's material: a name from the materials file, or an inline material; its ranges are the band's.",
        kind=Material,
    )
    source: str = setting(REQUIRED, "Where the layer's thickness and material come from.", kind=str)

    def __post_init__(self) -> None:
        super().__post_init__()
        low, high = (float(x) for x in self.thickness_range_m)
        if not (low < high and low <= self.thickness_m <= high):
            raise OptionError(
                "thickness_range_m",
                f"the thickness {self.thickness_m:g} m must lie inside a non-empty range, got [{low:g}, {high:g}]",
            )
        object.__setattr__(self, "thickness_range_m", [low, high])


@dataclass(frozen=True, kw_only=True)
class StackSettings(Settings):
    """Layers bonded on the rod's struck end, from the struck face to the rod."""

    layers: list[LayerSettings] = setting(
        REQUIRED, "The layers, from the struck face to the rod.", kind=LayerSettings, items=(1, None)
    )
    area_m2: float | None = setting(
        None,
        "Area of the stack's patch (null: the whole end face); fem_axi meshes a disc of this area.",
        unit="m^2",
        exclusive_minimum=0,
        nullable=True,
    )
    source: str = setting("", "Where the stack's make-up and size come from.", kind=str)


@dataclass(frozen=True, kw_only=True)
class HertzStackSettings(LawSettings):
    """The ``hertz_stack`` law's settings: the stack."""

    stack: StackSettings = setting(REQUIRED, "The layers bonded on the rod's struck end.", kind=StackSettings)


@dataclass(frozen=True)
class Stack:
    """Layers bonded on the rod's struck end, as the models use them.

    Parameters
    ----------
    layers : tuple of FilmLayer
        From the struck face to the rod (at least one).
    area_m2 : float or None
        Area of the patch, m^2 (None: the whole end face); the continuum meshes a disc of the
        same area, centred on the axis.
    names : tuple of str
        Each layer's name, in words ("" where none is given).
    """

    layers: tuple[FilmLayer, ...]
    area_m2: float | None = None
    names: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not self.layers:
            raise ValueError("layers: a stack needs at least one layer")
        if self.area_m2 is not None and not (math.isfinite(self.area_m2) and self.area_m2 > 0):
            raise ValueError(f"area_m2 must be > 0 or None, got {self.area_m2!r}")
        if not self.names:
            object.__setattr__(self, "names", tuple(layer.name for layer in self.layers))
        if len(self.names) != len(self.layers):
            raise ValueError("names: one per layer")

    @classmethod
    def of(cls, contact: Mapping[str, Any] | None) -> Stack | None:
        """The layers of a case's resolved contact block: its ``film`` (one layer) or its
        ``stack``, whatever the law; None when it has neither."""
        contact = contact or {}
        if contact.get("stack") is not None:
            stack = contact["stack"]
            area = stack.get("area_m2")
            layers = tuple(FilmLayer.from_mapping(layer) for layer in stack["layers"])
            return cls(
                layers,
                None if area is None else float(area),
                tuple(str(layer.get("name", "")) for layer in stack["layers"]),
            )
        if contact.get("film") is not None:
            film = FilmLayer.from_mapping(contact["film"])
            return cls((film,), film.area_m2, ("film",))
        return None

    @property
    def thickness_m(self) -> float:
        """Total thickness H = sum h_i, m."""
        if len(self.layers) == 1:
            return self.layers[0].thickness_m
        return math.fsum(layer.thickness_m for layer in self.layers)

    @property
    def constrained_modulus_pa(self) -> float:
        """The constrained modulus of one layer of thickness H as compliant as the stack's beds
        of springs in series, H / sum(h_i / M_i), Pa (a layer's own for one layer)."""
        if len(self.layers) == 1:
            return self.layers[0].constrained_modulus_pa
        return self.thickness_m / math.fsum(layer.thickness_m / layer.constrained_modulus_pa for layer in self.layers)

    def disc_radius(self, rod_radius_m: float) -> float:
        """Radius of the disc of the patch's area on a rod of radius ``rod_radius_m``, m."""
        if self.area_m2 is None:
            return rod_radius_m
        return min(math.sqrt(self.area_m2 / math.pi), rod_radius_m)

    def thin_layer_law(self, sphere_radius_m: float, impactor: ElasticMaterial, rod: ElasticMaterial) -> HertzFilmLaw:
        """Hertz's law in series with the stack as beds of springs (the thin-layer approximation)."""
        return HertzFilmLaw(
            k=hertz_constant(sphere_radius_m, impactor, rod),
            c=film_constant(sphere_radius_m, self.thickness_m, self.constrained_modulus_pa),
            sphere_radius_m=sphere_radius_m,
            thickness_m=self.thickness_m,
        )


@dataclass(frozen=True)
class HertzStackLaw(HertzFilmLaw):
    """Hertz's law in series with a stack of thin bonded layers (the thin-layer approximation)."""

    name = "hertz_stack"
    label = "Hertz with a layered thin stack (approximation)"
    reading = "Hertz contact in series with the stack as thin layers"
    settings = HertzStackSettings
    #: Its band is the continuum's (the calibrated law's), not the thin-layer one of ``needs.film``.
    needs = Needs()

    @classmethod
    def from_bodies(
        cls, spec: Mapping[str, Any], sphere_radius_m: float, impactor: ElasticMaterial, rod: ElasticMaterial
    ) -> HertzStackLaw:
        """The law of a case: ``spec["stack"]`` is the resolved stack (see :class:`Stack`)."""
        stack = Stack.of({"stack": spec["stack"]})
        law = stack.thin_layer_law(sphere_radius_m, impactor, rod)
        return cls(k=law.k, c=law.c, sphere_radius_m=law.sphere_radius_m, thickness_m=law.thickness_m)
