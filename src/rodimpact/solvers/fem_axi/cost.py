"""The cost model of a ``fem_axi`` run: an upper bound of the meshes' DOFs, times the steps."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.cost import MIB, SOLVE_S, Cost, contact_duration, horizon, recording_end
from rodimpact.solvers.fem_axi.farbar import BAR_ELEMENTS_PER_RADIUS, continuum_length
from rodimpact.solvers.fem_axi.gauges import continuum_cover_m
from rodimpact.solvers.fem_axi.layers import FILM_ASPECT, layer_elements
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.gauge_series import case_gauges

__all__ = ["fem_axi_cost", "fem_axi_dofs", "fem_axi_indentation_cost"]

#: fem_axi: s per DOF of the set-up (meshes, factorisations), s per step and DOF (3.8e-7 to
#: 5.7e-7 measured), bytes per DOF of the bound (sparse factors, the contact columns G, the
#: meshes and bases: 3.7 KiB per actual DOF measured, 49511 DOFs in 281 MiB).
FEM_AXI_SETUP_DOF_S = 1e-4
FEM_AXI_DOF_STEP_S = 7e-7
FEM_AXI_DOF_BYTES = 6000.0
#: Measured over modelled solve time, median of the stored runs (``Cost.typical_share``;
#: ``python -m rodimpact.tools.cost_share``); of the static indentation, its one measurement
#: (2.5 s where it estimates 9.9 s).
FEM_AXI_TYPICAL_SHARE = 0.13
FEM_AXI_INDENTATION_TYPICAL_SHARE = 0.25
#: Triangles per (fine size)^2 of area in the refined zones of fem_axi's meshes: longest-edge
#: refinement leaves edges between half the target and the target (4 to 16 for right
#: triangles); 7 to 22 measured, the most at coarse levels, where constant terms weigh.
FEM_AXI_TRIANGLES = 16.0
#: Triangles a body's mesh has beyond the model (corners, the sphere's chords).
FEM_AXI_EXTRA_TRIANGLES = 600.0
#: The film (:mod:`.film_mesh`): its columns per r_f / s_f away from the contact (s_f the
#: columns' largest spacing; longest-edge refinement leaves between s_f / 2 and s_f) and per
#: fine size within the contact extent (the rod's face there is about fine / 2), and the
#: rod's triangles per r_f / s_f in the graded band under the film (5 to 20 measured).
FILM_COLUMNS_PER_SPACING = 1.25
FILM_COLUMNS_PER_FINE = 2.0
FILM_BAND_TRIANGLES = 15.0


def _refined_triangles(extent: float, coarse: float) -> float:
    """Triangles, per :data:`FEM_AXI_TRIANGLES`, of a quarter plane meshed at the fine size
    (the unit of length) within ``extent`` of the corner, then growing by half the distance
    beyond it up to ``coarse``: pi/4 extent^2 + pi ((extent - 2)(1 - 1/coarse) + 2 ln coarse)."""
    count = math.pi / 4.0 * extent**2
    if coarse > 1.0:
        count += math.pi * (max(extent - 2.0, 0.0) * (1.0 - 1.0 / coarse) + 2.0 * math.log(coarse))
    return count


def _film_triangles(problem: AxiImpact, fine: float, extent: float, layers: int) -> float:
    """Triangles a film or stack adds to the rod's mesh: its rows of columns and the rod's
    band under it (``layers``: elements through the thickest layer)."""
    if problem.stack is None:
        return 0.0
    thicknesses = [layer.thickness_m for layer in problem.stack.layers]
    counts = layer_elements(thicknesses, layers)
    r_f = problem.film_radius_m
    spacing = min(FILM_ASPECT * min(h / n for h, n in zip(thicknesses, counts)), r_f / 2.0)
    columns = FILM_COLUMNS_PER_SPACING * r_f / spacing + FILM_COLUMNS_PER_FINE * min(extent, r_f) / fine
    return 2.0 * sum(counts) * columns + FILM_BAND_TRIANGLES * r_f / spacing


def fem_axi_dofs(case: Mapping[str, Any], *, with_gauges: bool = True) -> int:
    """Upper-side estimate of the DOFs of fem_axi's two meshes (rod and impactor), closed form.

    The meshes (:mod:`rodimpact.solvers.fem_axi.meshes`) are fine (a_H / ``elements_across``,
    a_H the contact radius estimated from the case's law) within ``contact_extent`` a_H of the
    contact point, graded beyond
    at half the distance up to a coarse size (a/4 by a/2 cells in the rod of radius a, R/4
    in the impactor), and coarse elsewhere, over the continuum's length (:mod:`.farbar`; the
    bar beyond adds one DOF per node; with gauges, the continuum reaches one rod diameter
    beyond the last gauge, :mod:`.gauges`). Vector P2 elements carry about 4 DOFs per
    triangle, P1 about 1. The 40 stored fem_axi runs have 0.48 to 0.90 of it (free DOFs).
    A film or stack (``contact.film``, ``contact.stack``) adds its layers of columns and the rod's graded band under it
    (:func:`_film_triangles`); its thin-layer law's larger contact radius sizes the rest.

    Parameters
    ----------
    case : mapping
        A resolved case (``numerics.fem_axi``, ``impactor``, ``rod``; ``gauges`` when its
        ``outputs`` list ``gauge_strain``).
    with_gauges : bool
        Extend the continuum over the case's gauges, as a run does (default); False: the
        model without them (the static indentation's).

    Returns
    -------
    int
        DOFs (rod + impactor), before the fixed ones are removed.
    """
    problem = AxiImpact.from_case(case, estimate=True)
    options = FEMAxiOptions.from_settings(case["numerics"]["fem_axi"])
    contact_radius = problem.scales().contact_radius_m
    fine = contact_radius / options.elements_across
    extent = options.contact_extent * options.elements_across
    a, length = problem.rod_radius_m, problem.rod_length_m
    cover = continuum_cover_m(case_gauges(case), a, length) if with_gauges else 0.0
    z_c = continuum_length(a, length, options.continuum_diameters, cover)
    bar_dofs = 0.0 if z_c is None else (length - z_c) * BAR_ELEMENTS_PER_RADIUS / a + 1.0
    meshed = length if z_c is None else z_c
    rod = (
        _refined_triangles(extent, a / 4.0 / fine) * FEM_AXI_TRIANGLES
        + 2.0 * 4.0 * math.ceil(2.0 * meshed / a)
        + _film_triangles(problem, fine, options.contact_extent * contact_radius, options.film_layers)
    )
    height = 2.0 if problem.body == "sphere" else min(options.cap_height, 1.0)
    radius = problem.sphere_radius_m
    area = math.pi / 4.0 * (2.0 if problem.body == "sphere" else 1.0)  # R^2
    impactor = (
        _refined_triangles(extent, radius * min(height, 1.0) / 4.0 / fine) * FEM_AXI_TRIANGLES
        + 2.0 * area * 16.0 / min(height, 1.0) ** 2
    )
    per_triangle = 4.0 if options.element == "P2" else 1.0
    return int(math.ceil(per_triangle * (rod + impactor + 2.0 * FEM_AXI_EXTRA_TRIANGLES) + bar_dofs))


def fem_axi_cost(case: Mapping[str, Any], options: FEMAxiOptions) -> Cost:
    """The steps, time and memory of one ``fem_axi`` solve of ``case`` (a resolved case)."""
    axi = AxiImpact.from_case(case, estimate=True)
    problem = ImpactProblem.from_case(case, estimate=True)
    step = options.step(axi.scales().contact_time_s)
    # its end test (.separation) stops once its energy bound proves that no contact can
    # follow; max(2T, a quarter of the contact) after the contact is the upper-side allowance
    contact = contact_duration(problem)
    span = horizon(problem, options.max_time_factor, contact, max(problem.rod.reflection_period, 0.25 * contact))
    # a run that records gauges or the far end's velocity steps on to its recording's end
    # (beyond the time limit)
    span = max(span, recording_end(case, problem, contact))
    dofs = fem_axi_dofs(case)
    steps = span / step + 1.0
    return Cost(
        time_step_s=step,
        steps=steps,
        solve_s=SOLVE_S + dofs * (FEM_AXI_SETUP_DOF_S + FEM_AXI_DOF_STEP_S * steps),
        mem_mib=dofs * FEM_AXI_DOF_BYTES / MIB,
        typical_share=FEM_AXI_TYPICAL_SHARE,
    )


#: The static indentation's candidate columns per contact extent (in contact radii) and element
#: across the contact radius: 111 columns at extent 1.5 and 10 elements with the sensor's stack.
INDENTATION_COLUMNS = 8.0


def fem_axi_indentation_cost(case: Mapping[str, Any], settings: Mapping[str, Any]) -> Cost:
    """The time and memory of the static indentation (:mod:`.indentation`) of ``case``'s
    bodies with the ``numerics.fem_axi`` ``settings``: the meshes' set-up and one solve per
    candidate column, each costing a step's solve (upper side: 2.5 s measured where it estimates 9.9 s, the
    heaviest Table 2 ball on the sensor's stack)."""
    options = FEMAxiOptions.from_settings(settings)
    dofs = fem_axi_dofs({**case, "numerics": {**case["numerics"], "fem_axi": dict(settings)}}, with_gauges=False)
    columns = INDENTATION_COLUMNS * options.contact_extent * options.elements_across
    return Cost(
        time_step_s=math.nan,
        steps=0.0,
        solve_s=SOLVE_S + dofs * (FEM_AXI_SETUP_DOF_S + FEM_AXI_DOF_STEP_S * columns),
        mem_mib=dofs * FEM_AXI_DOF_BYTES / MIB,
        typical_share=FEM_AXI_INDENTATION_TYPICAL_SHARE,
    )
