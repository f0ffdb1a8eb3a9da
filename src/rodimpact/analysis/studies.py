"""The cases of the numerical studies: work-precision levels, stress references, map points.

Every study run is an ordinary resolved case (see :mod:`rodimpact.config.load`) with its
numerics changed, so that it is stored, hashed and traced like any other run; the study
and its sweep parameters go into the run's config (``run.study``).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from typing import Any

from rodimpact.model.materials import Material

__all__ = ["level_case", "map_point_case", "map_point_names", "reference_case"]

#: Numerics of the sem reference run of a stress case (its tolerance set by the study).
_REFERENCE_METHOD = "sem"
#: Tolerance of the sem reference of a map point.
MAP_REFERENCE_TOLERANCE = 1e-5
#: Step budget of every run of the map.
MAP_MAX_STEPS = 200_000


def level_case(
    case: Mapping[str, Any], method: str, global_numerics: Mapping[str, Any], overrides: Mapping[str, Any]
) -> dict[str, Any]:
    """The case run by ``method`` with its numerics overridden by one sweep level.

    The method need not be among the case's own methods; its numerics then come from the
    global ``numerics`` (with the schema's defaults filled in).
    """
    out = copy.deepcopy(dict(case))
    base = out["numerics"].get(method, global_numerics.get(method, {}))
    out["numerics"] = {method: {**base, **overrides}}
    out["methods"] = [method]
    return out


def reference_case(case: Mapping[str, Any], global_numerics: Mapping[str, Any], tolerance: float) -> dict[str, Any]:
    """The case run by ``sem`` with the automatic step at ``tolerance`` (a stress reference)."""
    return level_case(
        case,
        _REFERENCE_METHOD,
        global_numerics,
        {"dt_s": None, "steps_per_contact": None, "tolerance": float(tolerance)},
    )


def map_point_names(spec: Mapping[str, Any]) -> list[str]:
    """Names ``m{i}_z{j}`` of the map's points (i over masses, j over impedances)."""
    return [f"m{i}_z{j}" for i in range(len(spec["mass_kg"])) for j in range(len(spec["impedance_kg_s"]))]


def map_point_case(
    base: Mapping[str, Any], spec: Mapping[str, Any], name: str, method: str, global_numerics: Mapping[str, Any]
) -> dict[str, Any]:
    """One point of the stability map run by ``method`` at the map's step.

    The base case with the impactor mass ``mass_kg[i]`` and the rod's cross-section set so
    that its impedance S sqrt(E rho) is ``impedance_kg_s[j]``; the paper scheme is allowed
    to be unstable there (the map is about where it is). ``method == "reference"`` gives
    the sem run with the automatic step at :data:`MAP_REFERENCE_TOLERANCE` the points are
    checked against (a hundred times finer than the map's accuracy, 1e-2 by default). Every
    run has the step budget :data:`MAP_MAX_STEPS`.
    """
    i, j = (int(part[1:]) for part in name.split("_"))
    mass, impedance = float(spec["mass_kg"][i]), float(spec["impedance_kg_s"][j])
    rod_material = Material.from_mapping(base["rod"]["material"])
    area = impedance / math.sqrt(rod_material.youngs_modulus_pa * rod_material.density_kg_m3)
    case = copy.deepcopy(dict(base))
    case.update(
        id=f"{base['id']}.map.{name}",
        set="stability_map",
        variant=None,
        row=name,
        description=f"{base['id']} with impactor mass {mass:g} kg on a rod of impedance {impedance:g} kg/s",
        stations=[],
        outputs=["contact_force", "energy"],
        measured={},
        published={},
    )
    case["impactor"] = {**case["impactor"], "mass_kg": mass}
    case["rod"] = {**case["rod"], "area_m2": area, "radius_m": math.sqrt(area / math.pi)}
    if method == "reference":
        return level_case(
            case,
            _REFERENCE_METHOD,
            global_numerics,
            {"dt_s": None, "steps_per_contact": None, "tolerance": MAP_REFERENCE_TOLERANCE, "max_steps": MAP_MAX_STEPS},
        )
    # the energy balance is classified by the map (accurate or not), so runs fail only
    # on a gross energy gain (half the impact energy), the mark of an unstable step
    overrides = {
        "dt_s": None,
        "steps_per_contact": int(spec["steps_per_contact"]),
        "max_steps": MAP_MAX_STEPS,
        "energy_tolerance": 0.5,
    }
    if method == "sem_paper":
        overrides["allow_unstable"] = True
    return level_case(case, method, global_numerics, overrides)
