"""Numerical options of ``fem_axi`` (the axisymmetric continuum model)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from rodimpact.solvers.options import OptionError, setting
from rodimpact.solvers.stepping import SteppingOptions

__all__ = ["FILM_LAYERS", "FEMAxiOptions"]

FILM_LAYERS = 4
"""Elements through the thickest layer of a film or stack (the default of ``film_layers``)."""


@dataclass(frozen=True)
class FEMAxiOptions(SteppingOptions):
    """Numerics of ``fem_axi``: axisymmetric continuum of rod and impactor, frictionless unilateral contact."""

    DESCRIPTION: ClassVar[str] = (
        "Numerics of fem_axi, the axisymmetric continuum model of rod and impactor with "
        "frictionless unilateral contact (Lagrange multipliers)."
    )

    steps_per_contact: int | None = setting(
        300, "Time steps per contact time on a rigid rod, when dt_s is null.", kind=int, nullable=True, minimum=20
    )
    element: str = setting("P2", "Lagrange element of both bodies' triangles.", kind=str, choices=("P1", "P2"))
    elements_across: int = setting(
        10,
        "Elements across the largest contact radius, estimated from the contact law before meshing.",
        kind=int,
        minimum=2,
    )
    contact_extent: float = setting(
        1.5,
        "Radius of the fine mesh and of the candidate contact zone, in estimated contact radii.",
        exclusive_minimum=1,
    )
    continuum_diameters: float | None = setting(
        5.0,
        "Length of the rod modelled as a continuum from its struck end, in rod diameters; beyond it "
        "the rod is a 1-D bar joined to the continuum's last section (plane sections, uniaxial stress), on a rod "
        "at least 10 such continua long. Null: the whole rod is a continuum.",
        nullable=True,
        minimum=1,
    )
    film_layers: int = setting(
        FILM_LAYERS,
        "Elements through the thickest layer of a film or stack on the struck end; every other layer gets "
        "as many as make its elements at most as high, at least one.",
        kind=int,
        minimum=1,
    )
    plastic_extent: float = setting(
        2.0,
        "Radius about the contact point within which a yielding material may yield, in estimated contact "
        "radii; beyond it the body stays elastic and keeps its factorisation (a solve fails when the elastic "
        "stress beyond reaches the yield stress). Read only where a material declares a yield stress.",
        exclusive_minimum=0,
    )
    cap_height: float = setting(
        1.0, "Impactor body 'cap' only: height of the elastic cap, in sphere radii.", exclusive_minimum=0, maximum=1
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.dt_s is None and self.steps_per_contact is None:
            raise OptionError("steps_per_contact", "must be given when dt_s is null")

    def step(self, contact_time_s: float) -> float:
        """The time step, s, for a contact time on a rigid rod of ``contact_time_s``."""
        return self.dt_s if self.dt_s is not None else contact_time_s / self.steps_per_contact
