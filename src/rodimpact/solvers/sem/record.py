"""What an SEM run stores at its nodes besides the force and the motions (:func:`run_histories`:
the energies, the contact radius and the stations, from d'Alembert's solution driven by the
run's force), and a completed run's histories continued after its last node with no force
(:func:`extended_record`), for the gauges and the far end's velocity."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.sem.history import ForceHistory
from rodimpact.solvers.stepping import Nodes, contact_series

__all__ = ["extended_record", "run_histories"]


def run_histories(
    mass: float,
    law: Any,
    history: ForceHistory,
    length: float,
    nodes: Nodes,
    stations: tuple[float, ...],
    rod_energy: np.ndarray,
) -> tuple[dict, dict]:
    """Station histories (d'Alembert from ``history``, the run's force) and energies at the
    ``nodes`` as extra series; station positions. ``mass`` is the impactor's (kg), ``law`` the
    contact law, ``length`` the rod's (m), ``rod_energy`` the work done on the rod at the nodes (J)."""
    t, alpha = nodes.time, nodes.alpha
    series = {
        "impactor_kinetic_energy": (0.5 * mass * nodes.w**2, "J", "kinetic energy of the impactor"),
        **contact_series(law, alpha),
        "rod_energy": (rod_energy, "J", "energy in the rod: work done on it by the contact force"),
    }
    extra = {}
    if stations:
        xs = [s * length for s in stations]
        series["station_displacement"] = (
            np.column_stack([history.displacement_at(x, t) for x in xs]),
            "m",
            "axial displacement of the cross-sections at station_x_m (d'Alembert, from the contact force)",
        )
        series["station_strain"] = (
            np.column_stack([history.strain_at(x, t) for x in xs]),
            "1",
            "axial strain du/dx at station_x_m (negative in compression; d'Alembert)",
        )
        extra["station_x_m"] = np.asarray(xs)
    return series, extra


def extended_record(
    result: ImpactResult, problem: ImpactProblem, stations: tuple[float, ...], until: float
) -> ImpactResult:
    """A completed run's result continued past its last node to ``until`` (s), at its step.

    The force is zero after the run's last contact (no further contact is possible), so the run
    is continued without stepping: nodes at the run's step ``dt_s`` after its last one, up to the
    first at or beyond ``until``; at each, the force 0, the impactor moving freely at its rebound
    velocity (x = x_last + w_last (t - t_last), as the scheme's step moves it with no force), the
    rod end's displacement from d'Alembert's solution driven by the run's force (the run's own
    end displacement, :meth:`ForceHistory.rod_displacement`), the approach x - u_end, and every
    extra series (energies, stations) as the run computes it. Its summary (contacts, maxima,
    rebound, energy balance, status, ``n_steps``: the steps taken) is the run's own.
    """
    t_last, h = float(result.time[-1]), float(result.dt_s)
    count = max(math.ceil((until - t_last) / h), 0)
    while t_last + count * h < until:
        count += 1
    if count == 0:
        return result
    times = t_last + h * np.arange(1, count + 1, dtype=float)
    history = ForceHistory.of_nodes(problem.rod, result.scheme == "implicit", result.time, result.contact_force)
    u_end = history.rod_displacement(times)
    w = np.full(count, result.impactor_velocity[-1])
    x = result.impactor_displacement[-1] + w * (times - t_last)
    tail = Nodes(time=times, force=np.zeros(count), x=x, w=w, u_end=u_end, alpha=x - u_end)
    rod_energy = np.full(count, result.extra_series["rod_energy"][0][-1])
    series, _ = run_histories(
        problem.mass_kg, problem.contact, history, problem.rod.length_m, tail, stations, rod_energy
    )
    if series.keys() != result.extra_series.keys():
        raise AssertionError(f"extended series {sorted(series)} differ from the run's {sorted(result.extra_series)}")
    extra_series = {
        name: (np.concatenate([values, series[name][0]]), units, description)
        for name, (values, units, description) in result.extra_series.items()
    }
    return dataclasses.replace(
        result,
        time=np.concatenate([result.time, tail.time]),
        contact_force=np.concatenate([result.contact_force, tail.force]),
        approach=np.concatenate([result.approach, tail.alpha]),
        impactor_displacement=np.concatenate([result.impactor_displacement, tail.x]),
        impactor_velocity=np.concatenate([result.impactor_velocity, tail.w]),
        rod_end_displacement=np.concatenate([result.rod_end_displacement, tail.u_end]),
        extra_series=extra_series,
    )
