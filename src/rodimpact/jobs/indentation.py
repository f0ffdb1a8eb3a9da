"""The contact law calibrated by the continuum: the science behind the ``indentation`` rule.

For a case whose law is ``tabulated`` (``from: fem_axi_indentation``), the continuum model
presses a hemispherical cap of the case's ball (its rigid back at the sphere's centre plane)
onto the case's rod, with its film when it has one, the far end fixed, at a series of
rigid-back displacements d. The 1-D methods carry the rod's own 1-D compliance L / (E A) and
treat the ball as rigid, so the approach their law needs is

    alpha(P) = d(P) - P L / (E A):

the local compression of the ball, the film and the rod end, with the 3-D spreading of the
load into the rod, all from the continuum. The load range runs up to
:data:`LOAD_MARGIN` times the peak force of the impact on a rigid rod through the case's
analytic law (the largest force the impact can reach), at displacements spaced in ratio.
The interpolation error of the ``tabulated`` law is measured by rebuilding it from every
other point and comparing at the points left out.

Where a material of the case yields, the indentation is elastic-plastic and a path
(:func:`~rodimpact.solvers.fem_axi.indentation.static_indentation` with an
:class:`~rodimpact.solvers.fem_axi.indentation.UnloadingPlan`): the loading displacements
(:data:`PLASTIC_POINTS`), and from the first that dissipates, from every fourth after it and
from the last, an unloading curve down to no force and back. The curve file then holds the
unloading curves too, and the law is the ``tabulated`` law with memory
(:class:`~rodimpact.contact.tabulated.TabulatedMemoryLaw`); the interpolation error of its
unloading curves is measured as the loading curve's, with every other curve left out.
"""

from __future__ import annotations

import dataclasses
import logging
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from rodimpact.contact.laws import bodies_contact, build_law
from rodimpact.contact.tabulated import TabulatedLaw, TabulatedMemoryLaw
from rodimpact.model.materials import Material
from rodimpact.solvers.fem_axi.indentation import UnloadingPlan, static_indentation
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.storage.atomic import atomic_directory
from rodimpact.storage.curves import ContactCurve, write_contact_curve

__all__ = ["LOAD_MARGIN", "PLASTIC_POINTS", "POINTS", "indentation_curve", "indentation_to_file", "indentations_into"]

log = logging.getLogger(__name__)

#: The curve reaches this many times the rigid-rod peak force.
LOAD_MARGIN = 1.5
#: Displacements of the rigid back, spaced in ratio from SMALLEST * d_max to d_max.
POINTS = 17
SMALLEST = 0.03
#: Where a material yields: the loading path's displacements (each about 7.6 % above the last: the
#: elastic-plastic solve is incremental), and how much deeper the first try indents than an
#: elastic contact would for the same force.
PLASTIC_POINTS = 49
PLASTIC_REACH = 1.5


def _bodies_case(case: Mapping[str, Any]) -> dict[str, Any]:
    """The case with the analytic law of its bodies (:func:`~rodimpact.contact.laws.bodies_contact`)."""
    contact = bodies_contact(case.get("contact"))
    bodies = {**case, "impactor": {**case["impactor"], "body": "cap"}, "rod": {**case["rod"], "far_end": "fixed"}}
    if contact is not None:
        bodies["contact"] = contact
    else:
        bodies.pop("contact", None)
    return bodies


def indentation_curve(case: Mapping[str, Any], settings: Mapping[str, Any] | None = None) -> ContactCurve:
    """The static indentation of ``case``'s ball, film and rod, as a contact-law curve.

    Parameters
    ----------
    case : mapping
        A resolved case (any law: its bodies are what is indented).
    settings : mapping, optional
        ``numerics.fem_axi`` settings of the continuum model (default: its defaults).

    Returns
    -------
    ContactCurve
        Datasets ``approach_m``, ``force_N``, ``contact_radius_m``, ``displacement_m``,
        ``law_approach_m``; summary: the subtracted compliance, the load range, the analytic
        law's name, the interpolation error.
    """
    bodies = _bodies_case(case)
    options = FEMAxiOptions.from_settings(settings or {})
    problem = dataclasses.replace(AxiImpact.from_case(bodies, estimate=True), body="cap")
    imp = case["impactor"]
    law = build_law(
        bodies.get("contact"),
        float(imp["radius_m"]),
        Material.from_mapping(imp["material"]),
        Material.from_mapping(case["rod"]["material"]),
    )
    peak = LOAD_MARGIN * law.rigid_impact(float(imp["mass_kg"]), float(imp["velocity_m_s"])).peak_force_N
    rod = case["rod"]
    compliance = float(rod["length_m"]) / (float(rod["material"]["youngs_modulus_pa"]) * float(rod["area_m2"]))
    d_max = 1.2 * (law.approach(peak) + compliance * peak)
    plan = UnloadingPlan() if problem.yields else None
    if plan is not None:
        d_max *= PLASTIC_REACH  # a yielding contact needs a deeper indentation for the same force
    for _ in range(6):
        displacements = d_max * np.geomspace(SMALLEST, 1.0, POINTS if plan is None else PLASTIC_POINTS)
        result = static_indentation(problem, displacements, options, unloading=plan, until_force_N=peak)
        if not result.success:
            raise RuntimeError(f"case {case['id']!r}: the indentation failed: {result.message}")
        if result.force_N[-1] >= peak:
            break
        d_max *= 1.5 * (peak / max(result.force_N[-1], 1e-300)) ** (2.0 / 3.0)
    else:
        raise RuntimeError(f"case {case['id']!r}: the indentation did not reach {peak:.4g} N")
    force = np.asarray(result.force_N, float)
    displacements = displacements[: len(force)]
    approach = displacements - compliance * force
    keep = force > 0
    if keep.sum() < 4 or np.any(np.diff(approach[keep]) <= 0) or np.any(np.diff(force[keep]) <= 0):
        raise RuntimeError(f"case {case['id']!r}: the indentation curve is not monotone")
    approach, force, radius, displacements = (
        approach[keep],
        force[keep],
        np.asarray(result.contact_radius_m)[keep],
        displacements[keep],
    )
    law_approach = np.array([law.approach(p) for p in force])
    # interpolation error: the law from every other point, at the points left out
    half = TabulatedLaw(tuple(approach[::2]), tuple(force[::2]))
    left_out = np.arange(1, len(force) - 1, 2)
    interpolation_error = float(np.max(np.abs([half.force(approach[i]) / force[i] - 1.0 for i in left_out])))
    summary = {
        "analytic_law": law.name,
        "rod_compliance_m_per_N": compliance,
        "load_margin": LOAD_MARGIN,
        "rigid_peak_force_N": peak / LOAD_MARGIN,
        "max_force_N": float(force[-1]),
        "interpolation_error_half": interpolation_error,
        "node_spacing_m": float(result.node_spacing_m),
        "elements_across": options.elements_across,
        "max_law_error": float(np.max(np.abs(law_approach / approach - 1))),
    }
    log.info(
        "case %s: %d points up to %.4g N; the %s law's approach differs by up to %.2f %%; interpolation "
        "error (every other point) %.2e",
        case["id"],
        len(force),
        force[-1],
        law.name,
        100 * summary["max_law_error"],
        interpolation_error,
    )
    data = {
        "approach_m": approach,
        "force_N": force,
        "contact_radius_m": radius,
        "displacement_m": displacements,
        "law_approach_m": law_approach,
    }
    if plan is not None:
        memory = _memory_curves(case, result, approach, force, compliance, keep)
        data.update(memory.pop("data"))
        summary.update(memory)
    return ContactCurve(case_id=str(case["id"]), data=data, summary=summary, config=dict(case))


def _memory_curves(
    case: Mapping[str, Any],
    result: Any,
    approach: np.ndarray,
    force: np.ndarray,
    compliance: float,
    keep: np.ndarray,
) -> dict[str, Any]:
    """The unloading curves of an elastic-plastic indentation as the law with memory reads them,
    the elastic limit, and the interpolation error of the unloading curves (the law rebuilt from
    every other curve, at the points of those left out, relative to each curve's largest force)."""
    work = np.asarray(result.plastic_work_J, float)[keep]
    loading_index = np.flatnonzero(keep)  # loading displacement -> its point on the kept curve
    if not np.any(work > 0):
        raise RuntimeError(f"case {case['id']!r}: a material yields but the indentation dissipated nothing")
    first = int(np.argmax(work > 0))
    elastic_limit = float(approach[first - 1]) if first > 0 else 0.5 * float(approach[0])
    curve, alpha, load = [], [], []
    tops = np.unique(result.unloading_curve)
    for k, top in enumerate(tops):
        at = int(np.searchsorted(loading_index, top))
        on = result.unloading_curve == top
        down_force = np.asarray(result.unloading_force_N, float)[on]
        down_alpha = np.asarray(result.unloading_displacement_m, float)[on] - compliance * down_force
        curve += [k] * (1 + int(on.sum()))
        alpha += [float(approach[at]), *down_alpha.tolist()]
        load += [float(force[at]), *down_force.tolist()]
    unloading = {"curve": curve, "approach_m": alpha, "force_N": load}
    error = math.nan
    if len(tops) >= 3:
        loading = TabulatedLaw(tuple(approach), tuple(force))
        index = np.asarray(curve)
        kept = np.isin(index, np.arange(0, len(tops), 2))
        half = TabulatedMemoryLaw.from_curve(
            loading,
            {
                "unloading": {key: np.asarray(value)[kept].tolist() for key, value in unloading.items()},
                "elastic_limit_m": elastic_limit,
            },
        )
        errors = []
        for k in range(1, len(tops) - 1, 2):
            on = index == k
            a, p = np.asarray(alpha)[on], np.asarray(load)[on]
            branch = half.branch(float(a[0]))
            errors += [abs(branch.force(float(x)) - y) / p[0] for x, y in zip(a[1:], p[1:])]
        error = float(max(errors))
    log.info(
        "case %s: %d unloading curves; elastic up to %.4g m; their interpolation error (every other curve) %.2e",
        case["id"],
        len(tops),
        elastic_limit,
        error,
    )
    return {
        "data": {
            "unloading_curve": np.asarray(curve, float),
            "unloading_approach_m": np.asarray(alpha, float),
            "unloading_force_N": np.asarray(load, float),
        },
        "elastic_limit_m": elastic_limit,
        "unloading_curves": len(tops),
        "unloading_interpolation_error_half": error,
    }


def indentation_to_file(case: Mapping[str, Any], path: str, settings: Mapping[str, Any] | None = None) -> None:
    """Compute :func:`indentation_curve` and write it atomically to ``path``."""
    if not math.isfinite(float(case["rod"]["length_m"])):
        raise ValueError(f"case {case['id']!r}: the indentation needs a finite rod")
    write_contact_curve(path, indentation_curve(case, settings))


def indentations_into(
    cases: Sequence[Mapping[str, Any]], directory: str | Path, settings: Mapping[str, Any] | None = None
) -> list[Path]:
    """:func:`indentation_to_file` of every case, to ``directory/{case}.h5``: the curves of one group's
    cases, the directory appearing whole or not at all
    (:func:`~rodimpact.storage.atomic.atomic_directory`); the files written."""
    directory = Path(directory)
    with atomic_directory(directory) as tmp:
        for case in cases:
            indentation_to_file(case, str(tmp / f"{case['id']}.h5"), settings)
    return [directory / f"{case['id']}.h5" for case in cases]
