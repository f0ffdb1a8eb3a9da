"""The case file: the first stage of the chain case -> runs -> tables and figures.

``results/cases/{name}.yaml`` holds what every run of the cases of one group (the cases whose
runs are batched together: a reading of a set with variants, else a set) computes and why it
costs what it does: for each case the resolved case (defaults filled in, the variant applied),
the scales derived from it (contact law, rod impedance and wave speed, the wave round trip,
the impact on a rigid rod, the contact-time estimate) and, per method, the time step, the
number of steps, the solve time and memory of the cost model, and the job's request. A sweep
case has a file of its own, which lists the same for each point of its grid.

Every solver rule takes the file as an input and every run records it (``run.case_file`` in
the run's config: its path, its SHA-256 and the hash of the run's case in it), so a run traces
back to it; a change of a case rewrites its group's file and reruns that group's runs only.
The costs are the cost model's estimates: a new calibration rewrites the files, and reruns the
runs whose file changed.
"""

from __future__ import annotations

import copy
import logging
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rodimpact.analysis.sweeps import sweep_point_case, sweep_points
from rodimpact.jobs.resources import estimate_resources
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.casefile import write_case_records
from rodimpact.storage.provenance import config_sha256

__all__ = ["case_file_record", "case_scales", "write_case_file"]

log = logging.getLogger(__name__)


def _plain(value: float) -> float | None:
    """A float YAML writes and reads back exactly (None for NaN or infinity)."""
    value = float(value)
    return value if math.isfinite(value) else None


def case_scales(case: Mapping[str, Any]) -> dict[str, Any]:
    """The scales of a resolved case and the cost of each of its methods.

    Returns
    -------
    dict
        ``contact`` (the law's name and parameters), ``rod`` (impedance, kg/s; wave speed,
        m/s; round trip 2 l / a, s; static compliance, m/N), ``rigid_rod`` (the impact on a
        rigid rod through the law: largest approach, m; contact time, s; peak force, N;
        contact radius, m), ``contact_time_estimate_s`` and, per method, ``time_step_s``,
        ``steps``, ``solve_time_s``, ``memory_MiB`` and the job's ``threads``, ``mem_mb``,
        ``runtime_min``.
    """
    problem = ImpactProblem.from_case(case, estimate=True)
    rod, rigid = problem.rod, problem.rigid_contact
    radius = problem.contact.contact_radius(rigid.max_approach_m)
    methods = {}
    for name in case["methods"]:
        spec = METHODS[name]
        cost = spec.estimate(case, case["numerics"][name])
        job = estimate_resources(case, name)
        methods[name] = {
            "label": spec.label,
            "time_step_s": _plain(cost.time_step_s),
            "steps": _plain(cost.steps),
            "solve_time_s": _plain(cost.solve_s),
            "memory_MiB": _plain(cost.mem_mib),
            "job": {"threads": job.threads, "mem_mb": job.mem_mb, "runtime_min": job.runtime_min},
        }
    return {
        "contact": {
            key: value if isinstance(value, str) else _plain(value) for key, value in problem.contact.summary().items()
        },
        "rod": {
            "impedance_kg_s": _plain(rod.impedance),
            "wave_speed_m_s": _plain(rod.wave_speed),
            "round_trip_s": _plain(rod.reflection_period),
            "static_compliance_m_N": _plain(rod.static_compliance),
        },
        "rigid_rod": {
            "max_approach_m": _plain(rigid.max_approach_m),
            "contact_time_s": _plain(rigid.contact_time_s),
            "peak_force_N": _plain(rigid.peak_force_N),
            "contact_radius_m": None if radius is None else _plain(radius),
        },
        "contact_time_estimate_s": _plain(problem.contact_time_estimate()),
        "methods": methods,
    }


def case_file_record(case: Mapping[str, Any]) -> dict[str, Any]:
    """The content of a case file (see the module docstring).

    Parameters
    ----------
    case : mapping
        A resolved case (``rodimpact.config.load``), or a resolved sweep case (with ``sweep``).
    """
    case = copy.deepcopy(dict(case))
    record: dict[str, Any] = {"case_id": case["id"], "config_sha256": config_sha256(case), "case": case}
    if "sweep" in case:
        record["points"] = {}
        for point in sweep_points(case["sweep"]):
            name = "_".join(f"{key}~{value}" for key, value in point.items())
            record["points"][name] = {
                "values": {k: float(v) for k, v in point.items()},
                "derived": case_scales(sweep_point_case(case, point, name)),
            }
    else:
        record["derived"] = case_scales(case)
    return record


def write_case_file(name: str, cases: Sequence[Mapping[str, Any]], path: str | Path) -> Path:
    """Write the case file ``name`` of ``cases`` (a group's cases, or one sweep case) to ``path``
    (YAML, atomically); returns the path."""
    write_case_records(name, [case_file_record(case) for case in cases], path)
    log.info("wrote the case file %s (%d case(s)) to %s", name, len(cases), path)
    return Path(path)
