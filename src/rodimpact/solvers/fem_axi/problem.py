"""The impact as the axisymmetric continuum model sees it (geometry of both bodies)."""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

from rodimpact.contact.law import ContactLaw, RigidImpact
from rodimpact.contact.laws import build_law
from rodimpact.contact.stack import Stack
from rodimpact.model.materials import Material

__all__ = ["AxiImpact", "AxiScales"]


@dataclass(frozen=True)
class AxiScales:
    """The scales ``fem_axi`` sizes its mesh and its step with, from the case's contact law.

    Attributes
    ----------
    contact_time_s : float
        Contact time of the impactor on a rigid rod through the law, s.
    contact_radius_m : float
        Contact radius at the rigid-rod approach (the largest the impact reaches), m.
    """

    contact_time_s: float
    contact_radius_m: float


@dataclass(frozen=True)
class AxiImpact:
    """The impact as the continuum model sees it.

    Parameters
    ----------
    mass_kg, velocity_m_s : float
        Impactor mass m (total) and impact velocity.
    sphere_radius_m : float
        Radius R of the impactor's spherical surface.
    impactor_material, rod_material : Material
    body : {"sphere", "cap"}
        A whole elastic ball (its density scaled so that its mass is m), or an elastic
        spherical cap of the impactor's material backed by a rigid rear part that moves
        only along the axis (total mass m), as in the paper's FEM model.
    rod_radius_m, rod_length_m : float
    far_end : {"fixed", "free"}
    contact : ContactLaw or None
        The case's contact law, used only for the scales (:meth:`scales`): the continuum
        resolves the contact itself. None: Hertz's law of the two materials (in series with
        the thin-layer law of ``stack`` when there is one).
    stack : Stack or None
        Layers bonded on the rod's struck end (a film is a stack of one), each meshed as its
        own material region (discs of radius ``stack.disc_radius(rod_radius_m)`` on top of the
        end face; see :mod:`.film_mesh`): the impactor strikes the first layer. None: the bare
        end face.
    """

    mass_kg: float
    velocity_m_s: float
    sphere_radius_m: float
    impactor_material: Material
    body: Literal["sphere", "cap"]
    rod_radius_m: float
    rod_length_m: float
    rod_material: Material
    far_end: Literal["fixed", "free"] = "fixed"
    contact: ContactLaw | None = None
    stack: Stack | None = None

    @classmethod
    def from_case(cls, case: Mapping[str, Any], *, estimate: bool = False) -> AxiImpact:
        """The impact of a resolved case; ``stack`` from the contact block's film or stack when
        it has one, whatever its law (:meth:`Stack.of`). ``estimate`` is passed to
        :func:`~rodimpact.contact.laws.build_law` (a law whose data do not exist yet is
        replaced by the law it calibrates)."""
        imp, rod = case["impactor"], case["rod"]
        imp_mat, rod_mat = Material.from_mapping(imp["material"]), Material.from_mapping(rod["material"])
        contact = case.get("contact")
        return cls(
            mass_kg=float(imp["mass_kg"]),
            velocity_m_s=float(imp["velocity_m_s"]),
            sphere_radius_m=float(imp["radius_m"]),
            impactor_material=imp_mat,
            body=imp.get("body", "cap"),
            rod_radius_m=math.sqrt(float(rod["area_m2"]) / math.pi),
            rod_length_m=float(rod["length_m"]),
            rod_material=rod_mat,
            far_end=rod.get("far_end", "fixed"),
            contact=build_law(contact, float(imp["radius_m"]), imp_mat, rod_mat, estimate=estimate),
            stack=Stack.of(contact),
        )

    @functools.cached_property
    def law(self) -> ContactLaw:
        """The contact law of the scales: the case's; else Hertz's of the two materials, in
        series with the stack as thin layers when there is one."""
        if self.contact is not None:
            return self.contact
        if self.stack is not None:
            return self.stack.thin_layer_law(self.sphere_radius_m, self.impactor_material, self.rod_material)
        return build_law(None, self.sphere_radius_m, self.impactor_material, self.rod_material)

    @property
    def yields(self) -> bool:
        """A material of either body yields: the impactor's, the rod's or a layer's."""
        layers = self.stack.layers if self.stack is not None else ()
        return (
            self.impactor_material.yields
            or self.rod_material.yields
            or any(layer.yield_stress_pa is not None for layer in layers)
        )

    @property
    def film_radius_m(self) -> float:
        """Radius of the stack's disc, m (0 without one)."""
        return 0.0 if self.stack is None else self.stack.disc_radius(self.rod_radius_m)

    @functools.cached_property
    def rigid_contact(self) -> RigidImpact:
        """The impact on a rigid rod through the law."""
        return self.law.rigid_impact(self.mass_kg, self.velocity_m_s)

    def scales(self) -> AxiScales:
        """Contact time on a rigid rod and the largest contact radius, from the law.

        Raises
        ------
        ValueError
            The law gives no contact radius (it has no geometry to size a mesh with).
        """
        rigid = self.rigid_contact
        radius = self.law.contact_radius(rigid.max_approach_m)
        if radius is None:
            raise ValueError(f"contact: the {self.law.name} law gives no contact radius to size fem_axi's mesh")
        return AxiScales(contact_time_s=rigid.contact_time_s, contact_radius_m=float(radius))
