"""The stability study: stress runs checked against stated tolerances, and the map of where
each SEM scheme is stable and accurate at one step."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.records import StoredRun as RunRecord
from rodimpact.analysis.signals import ZIGZAG_UNSTABLE
from rodimpact.model.problem import ImpactProblem

__all__ = ["MAP_CLASSES", "StudyViolation", "enforced_limit_line", "map_frame", "stability_frame", "violations"]


class StudyViolation(RuntimeError):
    """A study run gave a wrong answer without saying so."""


#: Classes of a map point, in the order they are drawn.
MAP_CLASSES = ("accurate", "stable, inaccurate", "zig-zag or failed", "no converged reference")


def _finite(rec: RunRecord) -> bool:
    return all(np.all(np.isfinite(values)) for values in rec.series.values())


def _intervals(rec: RunRecord) -> str:
    starts, ends = np.asarray(rec.summary["contact_start_s"]), np.asarray(rec.summary["contact_end_s"])
    return "; ".join(f"{1e6 * a:.6g}-{1e6 * b:.6g}" for a, b in zip(starts, ends))


def stability_frame(
    records: Sequence[RunRecord], references: Mapping[str, RunRecord], tolerances: Mapping[str, Mapping[str, float]]
) -> pd.DataFrame:
    """One row per stress run: what it gave, the checks, and a verdict.

    Parameters
    ----------
    records : sequence of RunRecord
        Stress runs (failures stored as data, see ``run_to_file(keep_failed=True)``).
    references : mapping
        case id -> the sem reference run of that case.
    tolerances : mapping
        method -> ``{"contact_time": rtol, "energy": tol}`` (config.yaml ``stability``).

    Returns
    -------
    DataFrame
        ``verdict`` is ``ok`` (finite, force never negative, energy balance and first
        contact time within the method's tolerances), ``failed: <message>`` (the method
        refused or gave up, saying why) or ``VIOLATION: <what>`` (a wrong answer that did
        not say so: the study's failure). Contact intervals are listed in us.
    """
    rows = []
    for rec in records:
        tol = tolerances[rec.method]
        ref = references[rec.case_id]
        ref_ok = bool(ref.summary["success"])
        tc, tc_ref = float(rec.summary["contact_time_s"]), float(ref.summary["contact_time_s"])
        force = rec.series.get("contact_force", np.zeros(1))
        row = {
            "case_id": rec.case_id,
            "method": rec.method,
            "status": rec.summary["status"],
            "success": bool(rec.summary["success"]),
            "finite": _finite(rec),
            "min_force_N": float(np.min(force)),
            "energy_error": float(rec.summary["energy_error"]),
            "energy_tolerance": tol["energy"],
            "contact_time_s": tc,
            "reference_contact_time_s": tc_ref if ref_ok else math.nan,
            "contact_time_error": abs(tc / tc_ref - 1.0) if ref_ok else math.nan,
            "contact_time_tolerance": tol["contact_time"],
            "n_contacts": int(rec.summary["n_contacts"]),
            "contact_intervals_us": _intervals(rec),
            "wall_time_s": rec.wall_time_s,
            "message": str(rec.summary["message"]),
        }
        row["verdict"] = _verdict(row, ref_ok)
        rows.append(row)
    return pd.DataFrame(rows)


def _verdict(row: dict[str, Any], reference_ok: bool) -> str:
    if not row["success"]:
        return f"failed: {row['message']}" if row["message"].strip() else "VIOLATION: failed without a message"
    wrong = []
    if not row["finite"]:
        wrong.append("non-finite values")
    if row["min_force_N"] < 0:
        wrong.append(f"negative force {row['min_force_N']:.3g} N")
    if not abs(row["energy_error"]) <= row["energy_tolerance"]:
        kind = "gain" if row["energy_error"] < 0 else "loss"
        wrong.append(f"energy {kind} {abs(row['energy_error']):.3g} > {row['energy_tolerance']:.3g}")
    if not reference_ok:
        wrong.append("no converged reference to check the contact time against")
    elif not row["contact_time_error"] <= row["contact_time_tolerance"]:
        wrong.append(f"contact time off by {row['contact_time_error']:.3g} > {row['contact_time_tolerance']:.3g}")
    return "ok" if not wrong else "VIOLATION: " + "; ".join(wrong)


def violations(frame: pd.DataFrame) -> list[str]:
    """``case/method: verdict`` of every row that is a violation."""
    bad = frame[frame["verdict"].str.startswith("VIOLATION")]
    return [f"{r.case_id}/{r.method}: {r.verdict}" for r in bad.itertuples()]


def map_frame(records: Sequence[RunRecord], references: Mapping[str, RunRecord], accuracy: float) -> pd.DataFrame:
    """One row per (map point, method): its groups, the step against the limits, its class.

    A run is ``zig-zag or failed`` when it failed (diverged, energy gain beyond half the
    impact energy, step budget) or its force alternates up and down at every step over
    ``ZIGZAG_UNSTABLE`` steps or more; ``accurate`` when its
    first contact time and its energy balance are both within ``accuracy``.

    ``h_over_limit`` is the step over the enforced limit 2 Z / k_c(alpha_H);
    ``h_over_sharp_limit`` over the limit at the reference's largest approach.
    ``rigidity`` is P_H / (Z v0), the rigid-rod contact force over the largest force the
    rod's impedance can take at the impact velocity (the group the instability depends on).
    """
    rows = []
    for rec in records:
        summary, ref = rec.summary, references[rec.config["row"]]
        impedance = float(summary["rod_impedance_kg_s"])
        law = ImpactProblem.from_case(rec.config).contact
        alpha_ref = law.approach(float(np.max(ref.series["contact_force"])))
        sharp = 2.0 * impedance / law.stiffness(alpha_ref)
        dt = float(summary.get("dt_s", math.nan))
        success = bool(summary["success"])
        error = abs(float(summary["contact_time_s"]) / float(ref.summary["contact_time_s"]) - 1.0)
        energy = abs(float(summary["energy_error"]))
        unstable = not success or int(summary.get("zigzag_steps", 0)) >= ZIGZAG_UNSTABLE
        cls = MAP_CLASSES[2] if unstable else MAP_CLASSES[0] if max(error, energy) <= accuracy else MAP_CLASSES[1]
        if success and not ref.summary["success"]:
            cls = MAP_CLASSES[3]
        velocity = float(rec.config["impactor"]["velocity_m_s"])
        rows.append(
            {
                "point": rec.config["row"],
                "method": rec.method,
                "mass_kg": float(rec.config["impactor"]["mass_kg"]),
                "impedance_kg_s": impedance,
                "rigidity": float(summary["rigid_contact_force_N"]) / (impedance * velocity),
                "dt_s": dt,
                "h_over_limit": dt / float(summary["paper_step_limit_s"]),
                "h_over_sharp_limit": dt / sharp,
                "contact_time_error": error,
                "energy_error": float(summary["energy_error"]),
                "zigzag_steps": int(summary.get("zigzag_steps", 0)),
                "status": summary["status"],
                "class": cls,
                "message": str(summary["message"]),
            }
        )
    return pd.DataFrame(rows)


def enforced_limit_line(frame: pd.DataFrame) -> pd.DataFrame:
    """Per mass of a map, the rod impedance at which the map's step equals the enforced limit.

    The limit 2 Z / k_c(alpha_H) is proportional to Z at a given mass (k_c(alpha_H) and the
    Hertz time depend on the mass only), so Z_crit = Z h / h_limit from any point of that
    mass: below Z_crit the paper scheme is refused unless a case allows it.
    """
    line = frame.assign(z_crit=frame["impedance_kg_s"] * frame["h_over_limit"])
    return line.groupby("mass_kg", as_index=False)["z_crit"].median()
