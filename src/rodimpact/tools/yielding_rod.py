"""Table 2's balls on a yielding rod: the continuum's law with memory, and the dynamic continuum
against the SEM through that law.

The shipped cases ``ball_*-r10_l30`` (and ``ball_12.73mm-r10_l30_cal``) with the yield stresses of
the materials file's yielding variants (the balls 2.03 GPa, the rod 276 MPa), not shipped as
cases of their own:

1. the indentation rule's curve of the 12.73 mm ball (the shipped ``fem_axi`` numerics with
   ``plastic_extent: 4``, ``contact_extent: 2.5``): its unloading curves, their interpolation
   error, the elastic limit, and the rigid impact of the law with memory it makes;
2. for the 4.75 mm and the 12.73 mm ball, ``fem_axi``'s dynamic run (5 elements across, 100 steps
   per Hertz time, a horizon of 2 estimated contact times) against the SEM through the law the
   same mesh's indentation gives: contact time, restitution, energy balance, dissipated energy.

``python -m rodimpact.tools.yielding_rod`` prints both (about 6 minutes on the machine
``docs/setup.md`` names); docs/contact-laws.md and docs/verification.md quote them.
"""

from __future__ import annotations

import argparse
import copy
import dataclasses
import logging
import sys
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import yaml

from rodimpact.config.load import load_project
from rodimpact.contact.laws import DEFAULT_LAW
from rodimpact.contact.tabulated import TabulatedLaw
from rodimpact.jobs.indentation import indentation_curve
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.fem_axi.solver import solve_fem_axi
from rodimpact.solvers.registry import METHODS
from rodimpact.solvers.sem.solver import solve_sem

__all__ = ["YIELD_STRESSES", "dynamic_check", "yielding", "law_of_curve", "main"]

#: The yield stresses of the yielding variants (config/materials.yaml), Pa.
YIELD_STRESSES = {"impactor": 2.03e9, "rod": 2.76e8}
#: The plastic region and the contact zone a yielding contact needs, in estimated contact radii.
ZONES = {"plastic_extent": 4.0, "contact_extent": 2.5}
#: The dynamic comparison's coarse continuum.
DYNAMIC = {"elements_across": 5, "steps_per_contact": 100, "max_time_factor": 2.0}


def yielding(case: Mapping[str, Any]) -> dict[str, Any]:
    """The case with its ball and rod given :data:`YIELD_STRESSES`."""
    out = copy.deepcopy(dict(case))
    for body, stress in YIELD_STRESSES.items():
        out[body]["material"]["yield_stress_pa"] = stress
    return out


def law_of_curve(case: Mapping[str, Any], settings: Mapping[str, Any]) -> tuple[TabulatedLaw, dict[str, Any], float]:
    """The law the indentation rule's curve of ``case`` makes, the curve's summary and its time, s."""
    started = time.perf_counter()
    curve = indentation_curve(case, settings)
    elapsed = time.perf_counter() - started
    spec = {"from": "fem_axi_indentation", "curve": curve.law_curve()}
    return TabulatedLaw.from_bodies(spec, float(case["impactor"]["radius_m"]), None, None), curve.summary, elapsed


def dynamic_check(case: Mapping[str, Any], settings: Mapping[str, Any]) -> dict[str, Any]:
    """``fem_axi``'s dynamic run of ``case`` (a material of it yielding) against the SEM through
    the law the same mesh's indentation gives: contact time, restitution, energy.

    Raises
    ------
    RuntimeError
        ``fem_axi`` failed (a status other than completed or truncated at its horizon).
    """
    started = time.perf_counter()
    problem = dataclasses.replace(AxiImpact.from_case(case), body="cap")
    run = solve_fem_axi(problem, FEMAxiOptions.from_settings(settings))
    if run.status not in ("completed", "truncated"):
        raise RuntimeError(f"case {case['id']!r}: fem_axi failed: {run.message}")
    continuum_s = time.perf_counter() - started
    law, _, path_s = law_of_curve(case, settings)
    one_d = {**case, "contact": {"law": DEFAULT_LAW}}  # its law replaced by the table's below
    sem = solve_sem(dataclasses.replace(ImpactProblem.from_case(one_d), contact=law), METHODS["sem"].options())
    impact = 0.5 * problem.mass_kg * problem.velocity_m_s**2
    return {
        "case": case["id"],
        "fem_axi_contact_time_us": 1e6 * run.contact_time_s,
        "sem_contact_time_us": 1e6 * sem.contact_time_s,
        "contact_time_difference_pct": 100 * (sem.contact_time_s / run.contact_time_s - 1),
        "fem_axi_restitution": float(run.restitution),
        "sem_restitution": float(sem.restitution),
        "restitution_difference_pct": 100 * (sem.restitution / run.restitution - 1),
        "fem_axi_energy_error": float(run.energy_error),
        "fem_axi_dissipated_fraction": float(run.summary()["dissipated_energy_J"]) / impact,
        "impact_energy_J": impact,
        "fem_axi_status": run.status,
        "fem_axi_s": continuum_s,
        "indentation_s": path_s,
    }


def main(argv: Sequence[str] | None = None) -> int:
    """Print the example's law and the dynamic comparison."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", type=Path, default=Path("config/config.yaml"))
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="%(message)s")
    project = load_project(yaml.safe_load(args.config.read_text()))
    shipped = project.config["numerics"]["fem_axi"]
    out = sys.stdout

    case = yielding(project.cases["ball_12.73mm-r10_l30_cal"])
    law, summary, elapsed = law_of_curve(case, {**shipped, **ZONES})
    impact = law.rigid_impact(float(case["impactor"]["mass_kg"]), float(case["impactor"]["velocity_m_s"]))
    out.write(
        f"12.73 mm ball, shipped numerics: {summary['unloading_curves']} unloading curves, interpolation error "
        f"{summary['unloading_interpolation_error_half']:.3g} (loading {summary['interpolation_error_half']:.3g}), "
        f"elastic up to {summary['elastic_limit_m']:.4g} m; rigid restitution {impact.restitution:.4f}, dent "
        f"{impact.residual_approach_m:.4g} m; path {elapsed:.0f} s\n"
    )
    settings = {**shipped, **ZONES, **DYNAMIC}
    for row in ("ball_4.75mm", "ball_12.73mm"):
        check = dynamic_check(yielding(project.cases[f"{row}-r10_l30"]), settings)
        kinetic = check["impact_energy_J"]
        out.write(
            f"{row}: fem_axi {check['fem_axi_contact_time_us']:.2f} us, e {check['fem_axi_restitution']:.4f}, "
            f"energy balance {check['fem_axi_energy_error']:.2g}, dissipated "
            f"{check['fem_axi_dissipated_fraction'] * kinetic * 1e6:.3g} of {kinetic * 1e6:.3g} uJ "
            f"({check['fem_axi_status']}); sem {check['sem_contact_time_us']:.2f} us, "
            f"e {check['sem_restitution']:.4f}; "
            f"difference {check['contact_time_difference_pct']:+.2f} %, {check['restitution_difference_pct']:+.2f} %\n"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
