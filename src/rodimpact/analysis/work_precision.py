"""Error against run time: the errors of a resolution sweep against a converged reference,
and the observed orders of convergence.

The reference of a method is the Richardson extrapolation, at the reference method's
theoretical order p, of that method's finest two levels (resolutions n_{N-1} < n_N, ratio
r = n_N / n_{N-1}):

    q_ref = q_N + (q_N - q_{N-1}) / (r^p - 1),    error estimate |q_N - q_{N-1}| / (r^p - 1).

The estimate is the error of the finest run itself; the extrapolated value is better still
when the levels are in the asymptotic range, which the fitted orders show. For the whole
force history the reference is the finest run, with the same estimate of its error in the
norm. Errors are relative: |q - q_ref| / |q_ref|; for histories ||P - P_ref|| / ||P_ref||
in the L2 norm over time and in the max norm, both sampled on one grid over the reference's
first contact.
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd

from rodimpact.analysis.records import StoredRun as RunRecord
from rodimpact.analysis.signals import first_contact_maxima

__all__ = ["HISTORY_SAMPLES", "observed_orders", "work_precision_frame"]

#: Points of the common grid on which force histories are compared.
HISTORY_SAMPLES = 20_001


def _scalars(rec: RunRecord) -> dict[str, float]:
    summary = rec.summary
    out = {"contact_time": float(summary["contact_time_s"])}
    maxima = first_contact_maxima(summary["peak_time_s"], summary["peak_force_N"], summary["contact_end_s"])
    for k, value in enumerate(maxima, start=1):
        out[f"max_{k}"] = float(value)
    return out


def _grid(reference: RunRecord) -> np.ndarray:
    end = float(np.asarray(reference.summary["contact_end_s"])[0])
    return np.linspace(0.0, end, HISTORY_SAMPLES)


def _history(rec: RunRecord, grid: np.ndarray) -> np.ndarray:
    return np.interp(grid, rec.series["time"], rec.series["contact_force"], right=0.0)


def _norms(force: np.ndarray, reference: np.ndarray) -> tuple[float, float]:
    diff = force - reference
    return (float(np.sqrt(np.mean(diff**2)) / np.sqrt(np.mean(reference**2))),
            float(np.max(np.abs(diff)) / np.max(np.abs(reference))))


class _Reference:
    """The reference of one case for one reference method (see the module docstring)."""

    def __init__(self, runs: Sequence[RunRecord], resolution: str, order: float) -> None:
        runs = sorted(runs, key=lambda r: r.config["run"]["numerics"][resolution])
        if len(runs) < 2:
            raise ValueError(f"a reference needs two levels, got {len(runs)} of {runs[0].method if runs else '?'}")
        coarse, fine = runs[-2], runs[-1]
        ratio = fine.config["run"]["numerics"][resolution] / coarse.config["run"]["numerics"][resolution]
        factor = ratio**order - 1.0
        qc, qf = _scalars(coarse), _scalars(fine)
        self.method = fine.method
        self.values = {k: qf[k] + (qf[k] - qc[k]) / factor for k in qf if k in qc}
        self.errors = {k: abs(qf[k] - qc[k]) / factor / abs(self.values[k]) for k in self.values}
        self.grid = _grid(fine)
        self.force = _history(fine, self.grid)
        l2, mx = _norms(_history(coarse, self.grid), self.force)
        self.errors.update(history_l2=l2 / factor, history_max=mx / factor)

    def errors_of(self, rec: RunRecord) -> dict[str, float]:
        q = _scalars(rec)
        same_maxima = len([k for k in q if k.startswith("max_")]) == len([k for k in self.values if k.startswith("max_")])
        out = {}
        for key, ref in self.values.items():
            ok = key == "contact_time" or same_maxima
            out[key] = abs(q[key] / ref - 1.0) if ok and key in q else math.nan
        out["history_l2"], out["history_max"] = _norms(_history(rec, self.grid), self.force)
        return out


def work_precision_frame(records: Sequence[RunRecord], methods: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """One row per (case, method, level): resolution, cost and errors against the reference.

    Parameters
    ----------
    records : sequence of RunRecord
        The sweep's runs (``config.run.level`` set; timed, see :class:`rodimpact.jobs.runner.Timing`).
    methods : mapping
        config.yaml's ``work_precision.methods``: per method ``order``, ``reference`` and
        ``resolution``.

    Returns
    -------
    DataFrame
        ``case_id, method, level, resolution, n_steps, dt_s, wall_time_s`` (median of the
        repeats), ``wall_time_min_s, wall_time_max_s, repeats``, then ``err_<quantity>``
        for the contact time, each force maximum of the first contact (``max_k``) and the
        history norms, ``ref_err_<quantity>`` (the reference's own error estimate),
        ``energy_error`` and ``machine``.
    """
    rows = []
    for case_id in dict.fromkeys(r.case_id for r in records):
        runs = [r for r in records if r.case_id == case_id]
        references = {}
        for name in dict.fromkeys(spec["reference"] for spec in methods.values()):
            spec = methods[name]
            references[name] = _Reference([r for r in runs if r.method == name], spec["resolution"], spec["order"])
        for rec in sorted(runs, key=lambda r: (list(methods).index(r.method), r.config["run"]["level"])):
            spec = methods[rec.method]
            reference = references[spec["reference"]]
            numerics = rec.config["run"]["numerics"]
            row = {"case_id": case_id, "method": rec.method, "level": rec.config["run"]["level"],
                   "resolution": f"{spec['resolution']}={numerics[spec['resolution']]}",
                   "resolution_value": float(numerics[spec["resolution"]]),
                   "n_steps": rec.summary.get("n_steps"), "dt_s": rec.summary.get("dt_s"),
                   "wall_time_s": rec.wall_time_s,
                   "wall_time_min_s": rec.summary.get("wall_time_min_s", rec.wall_time_s),
                   "wall_time_max_s": rec.summary.get("wall_time_max_s", rec.wall_time_s),
                   "repeats": rec.summary.get("wall_time_repeats", 1),
                   "reference": f"{reference.method} (Richardson, finest two levels)"}
            row.update({f"err_{k}": v for k, v in reference.errors_of(rec).items()})
            row.update({f"ref_err_{k}": v for k, v in reference.errors.items()})
            row.update(energy_error=float(rec.summary["energy_error"]), machine=rec.summary.get("machine", ""))
            rows.append(row)
    return pd.DataFrame(rows)


def quantities(frame: pd.DataFrame) -> list[str]:
    """The error quantities of a work-precision frame (``contact_time``, ``max_1``, ...)."""
    return [c[4:] for c in frame.columns if c.startswith("err_")]


def observed_orders(frame: pd.DataFrame, methods: Mapping[str, Mapping[str, Any]], fit_levels: int = 4) -> pd.DataFrame:
    """The order of each method and quantity, fitted on the asymptotic range.

    The fit (``np.polyfit`` of log error against log h, h = 1 / resolution) takes the
    finest ``fit_levels`` levels whose error is finite and above ten times the
    reference's error estimate (below that the reference's error would be measured), and at
    least three of them.

    Returns
    -------
    DataFrame
        ``case_id, method, quantity, observed_order, theoretical_order, fitted_levels``
        (the levels used, e.g. ``3-6``; empty and order NaN when fewer than three qualify).
    """
    rows = []
    for (case_id, method), group in frame.groupby(["case_id", "method"], sort=False):
        group = group.sort_values("resolution_value")
        for quantity in quantities(frame):
            err, floor = group[f"err_{quantity}"].to_numpy(float), group[f"ref_err_{quantity}"].to_numpy(float)
            usable = np.isfinite(err) & (err > 10.0 * np.nan_to_num(floor, nan=np.inf)) & (err > 0)
            index = np.flatnonzero(usable)[-fit_levels:]
            order, levels = math.nan, ""
            if len(index) >= 3:  # two points give a ratio, not a range
                h = 1.0 / group["resolution_value"].to_numpy(float)[index]
                order = float(np.polyfit(np.log(h), np.log(err[index]), 1)[0])
                levels = f"{group['level'].iloc[index[0]]}-{group['level'].iloc[index[-1]]}"
            rows.append({"case_id": case_id, "method": method, "quantity": quantity, "observed_order": order,
                         "theoretical_order": float(methods[method]["order"]), "fitted_levels": levels})
    return pd.DataFrame(rows)
