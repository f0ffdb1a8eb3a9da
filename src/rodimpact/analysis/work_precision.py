"""Error against run time: the errors of a resolution sweep against a converged reference,
and the observed orders of convergence next to the expected ones.

The reference of a method is made from the levels of its reference method (``reference``),
as that method's ``as_reference`` says:

- ``richardson``: the Richardson extrapolation, at the reference method's order p, of its
  finest two levels (resolutions n_{N-1} < n_N, ratio r = n_N / n_{N-1}),

      q_ref = q_N + (q_N - q_{N-1}) / (r^p - 1),    error estimate |q_N - q_{N-1}| / (r^p - 1);

  the estimate is the error of the finest run itself; the extrapolated value is better still
  when the levels are in the asymptotic range, which the fitted orders show;
- ``finest``: its finest level, with the uncertainty of its finest three levels
  (:func:`rodimpact.analysis.convergence.numerical_uncertainty`: Roache's grid convergence
  index where they converge monotonically at a constant ratio, else half their range). For a
  method whose convergence oscillates Richardson extrapolation is not defined.

For the whole force history the reference is the finest run, with the norm of its
difference from the next level as the estimate (divided by r^p - 1 for ``richardson``).
Errors are relative: |q - q_ref| / |q_ref|, and signed (q / q_ref - 1) for the scalars; for
histories ||P - P_ref|| / ||P_ref|| in the L2 norm over time and in the max norm, both sampled
on one grid over the reference's first contact.

Each force maximum also carries its distance from the nearest arrival of the rod's wave at the
struck end (the reference's maximum; arrivals at t - t_start = 2kL/c, c = sqrt(E / rho)), as
a fraction of 2L/c: a maximum within ``arrival_window`` of an arrival takes the method's
expected order ``max_at_arrival`` (docs/studies.md, "Error against run time").
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from rodimpact.analysis.convergence import (
    FittedOrder,
    changes_sign,
    constant_ratio,
    fitted_order,
    is_monotone,
    numerical_uncertainty,
)
from rodimpact.analysis.records import StoredRun as RunRecord
from rodimpact.analysis.signals import first_contact_maxima
from rodimpact.model.materials import Material, wave_speed

__all__ = [
    "HISTORY_SAMPLES",
    "ORDER_TOLERANCE",
    "case_spec",
    "expected_order",
    "fit_indices",
    "levels_in",
    "observed_orders",
    "quantities",
    "quantity_rank",
    "work_precision_frame",
]

#: Points of the common grid on which force histories are compared.
HISTORY_SAMPLES = 20_001
#: An observed order within this of the expected one agrees with it.
ORDER_TOLERANCE = 0.3
#: A level enters the fit when its error exceeds this many times the reference's error estimate.
FLOOR_FACTOR = 10.0


def _scalars(rec: RunRecord) -> dict[str, float]:
    summary = rec.summary
    out = {"contact_time": float(summary["contact_time_s"])}
    maxima = first_contact_maxima(summary["peak_time_s"], summary["peak_force_N"], summary["contact_end_s"])
    for k, value in enumerate(maxima, start=1):
        out[f"max_{k}"] = float(value)
    return out


def _arrival_offsets(rec: RunRecord) -> dict[str, float]:
    """Each first-contact maximum's signed distance from the nearest wave arrival, / (2L/c)."""
    summary, rod = rec.summary, rec.config["rod"]
    round_trip = 2.0 * float(rod["length_m"]) / wave_speed(Material.from_mapping(rod["material"]))
    start = float(np.atleast_1d(summary["contact_start_s"])[0])
    times = np.atleast_1d(summary["peak_time_s"])
    times = times[times <= np.atleast_1d(summary["contact_end_s"])[0]]
    phase = (times - start) / round_trip
    return {f"max_{k}": float(p - np.round(p)) for k, p in enumerate(phase, start=1)}


def _grid(reference: RunRecord) -> np.ndarray:
    end = float(np.asarray(reference.summary["contact_end_s"])[0])
    return np.linspace(0.0, end, HISTORY_SAMPLES)


def _history(rec: RunRecord, grid: np.ndarray) -> np.ndarray:
    """The run's force on ``grid``: linear between its nodes and the contact starts and ends it
    located (P = 0 there; a method that steps to them has them among its nodes already), so
    that the kink of the force at a contact's end is where the run put it, not smeared over
    the step that holds it."""
    time, force = np.asarray(rec.series["time"], float), np.asarray(rec.series["contact_force"], float)
    events = np.concatenate([np.atleast_1d(rec.summary.get(key, [])) for key in ("contact_start_s", "contact_end_s")])
    events = np.setdiff1d(events[np.isfinite(events)].astype(float), time)
    if events.size:
        at = np.searchsorted(time, events)
        time, force = np.insert(time, at, events), np.insert(force, at, 0.0)
    return np.interp(grid, time, force, right=0.0)


def _norms(force: np.ndarray, reference: np.ndarray) -> tuple[float, float]:
    diff = force - reference
    return (
        float(np.sqrt(np.mean(diff**2)) / np.sqrt(np.mean(reference**2))),
        float(np.max(np.abs(diff)) / np.max(np.abs(reference))),
    )


def _resolution(rec: RunRecord, resolution: str) -> float:
    return float(rec.config["run"]["numerics"][resolution])


class _Reference:
    """The reference of one case for one reference method (see the module docstring)."""

    def __init__(self, runs: Sequence[RunRecord], spec: Mapping[str, Any]) -> None:
        runs = sorted(runs, key=lambda r: _resolution(r, spec["resolution"]))
        finest = spec.get("as_reference", "richardson") == "finest"
        if len(runs) < (3 if finest else 2):
            raise ValueError(
                f"a reference ({'finest level' if finest else 'Richardson'}) needs "
                f"{3 if finest else 2} levels, got {len(runs)} of {runs[0].method if runs else '?'}"
            )
        fine = runs[-1]
        self.method, self.offsets = fine.method, _arrival_offsets(fine)
        self.grid = _grid(fine)
        self.force = _history(fine, self.grid)
        l2, mx = _norms(_history(runs[-2], self.grid), self.force)
        if finest:
            f1, f2, f3 = (_scalars(r) for r in runs[:-4:-1])
            ratio = constant_ratio([_resolution(r, spec["resolution"]) for r in runs[-3:]])
            self.values, self.label = f1, f"{self.method} (finest level)"
            self.errors = {
                k: numerical_uncertainty(f1[k], f2[k], f3[k], ratio).value if k in f2 and k in f3 else math.nan
                for k in f1
            }
            self.errors.update(history_l2=l2, history_max=mx)
            return
        ratio = _resolution(fine, spec["resolution"]) / _resolution(runs[-2], spec["resolution"])
        factor = ratio ** spec["order"] - 1.0
        qc, qf = _scalars(runs[-2]), _scalars(fine)
        self.label = f"{self.method} (Richardson, finest two levels)"
        self.values = {k: qf[k] + (qf[k] - qc[k]) / factor for k in qf if k in qc}
        self.errors = {k: abs(qf[k] - qc[k]) / factor / abs(self.values[k]) for k in self.values}
        self.errors.update(history_l2=l2 / factor, history_max=mx / factor)

    def errors_of(self, rec: RunRecord) -> tuple[dict[str, float], dict[str, float]]:
        """The relative errors of ``rec`` (history norms included) and the scalars' signed ones."""
        q = _scalars(rec)
        same_maxima = len([k for k in q if k.startswith("max_")]) == len(
            [k for k in self.values if k.startswith("max_")]
        )
        signed = {
            key: q[key] / ref - 1.0 if (key == "contact_time" or same_maxima) and key in q else math.nan
            for key, ref in self.values.items()
        }
        out = {key: abs(value) for key, value in signed.items()}
        out["history_l2"], out["history_max"] = _norms(_history(rec, self.grid), self.force)
        return out, signed


def work_precision_frame(records: Sequence[RunRecord], methods: Mapping[str, Mapping[str, Any]]) -> pd.DataFrame:
    """One row per (case, method, level): resolution, cost and errors against the reference.

    Parameters
    ----------
    records : sequence of RunRecord
        The sweep's runs (``config.run.level`` set; timed, see :class:`rodimpact.jobs.runner.Timing`).
    methods : mapping
        config.yaml's ``work_precision.methods``: per method ``order``, ``reference``,
        ``resolution`` and (of a reference method) ``as_reference``.

    Returns
    -------
    DataFrame
        ``case_id, method, level, resolution, resolution_value, n_steps, dt_s, wall_time_s``
        (median of the repeats), ``wall_time_min_s, wall_time_max_s, repeats, reference``, then
        ``err_<quantity>`` for the contact time, each force maximum of the first contact
        (``max_k``) and the history norms, ``ref_err_<quantity>`` (the reference's own error
        estimate), ``signed_err_<quantity>`` (q / q_ref - 1, for the contact time and the
        maxima), ``arrival_offset_max_k`` (the reference's maximum's distance from the nearest
        wave arrival at the struck end, a fraction of 2L/c), ``energy_error`` and ``machine``.
    """
    rows = []
    for case_id in dict.fromkeys(r.case_id for r in records):
        runs = [r for r in records if r.case_id == case_id]
        swept = dict.fromkeys(r.method for r in runs)  # a case need not run every method
        references = {
            name: _Reference([r for r in runs if r.method == name], methods[name])
            for name in dict.fromkeys(methods[m]["reference"] for m in swept)
        }
        for rec in sorted(runs, key=lambda r: (list(methods).index(r.method), r.config["run"]["level"])):
            spec = methods[rec.method]
            reference = references[spec["reference"]]
            numerics = rec.config["run"]["numerics"]
            row = {
                "case_id": case_id,
                "method": rec.method,
                "level": rec.config["run"]["level"],
                "resolution": f"{spec['resolution']}={numerics[spec['resolution']]}",
                "resolution_value": float(numerics[spec["resolution"]]),
                "n_steps": rec.summary.get("n_steps"),
                "dt_s": rec.summary.get("dt_s"),
                "wall_time_s": rec.wall_time_s,
                "wall_time_min_s": rec.summary.get("wall_time_min_s", rec.wall_time_s),
                "wall_time_max_s": rec.summary.get("wall_time_max_s", rec.wall_time_s),
                "repeats": rec.summary.get("wall_time_repeats", 1),
                "reference": reference.label,
            }
            errors, signed = reference.errors_of(rec)
            row.update({f"err_{k}": v for k, v in errors.items()})
            row.update({f"ref_err_{k}": v for k, v in reference.errors.items()})
            row.update({f"signed_err_{k}": v for k, v in signed.items()})
            row.update({f"arrival_offset_{k}": v for k, v in reference.offsets.items()})
            row.update(energy_error=float(rec.summary["energy_error"]), machine=rec.summary.get("machine", ""))
            rows.append(row)
    return pd.DataFrame(rows)


def quantity_rank(quantity: str) -> tuple[int, int]:
    """Contact time, the maxima in order, then the histories (L2 before max)."""
    if quantity == "contact_time":
        return (0, 0)
    if quantity.startswith("max_") and quantity[4:].isdigit():
        return (1, int(quantity[4:]))
    return (2, ("history_l2", "history_max").index(quantity) if quantity in ("history_l2", "history_max") else 9)


def quantities(frame: pd.DataFrame) -> list[str]:
    """The error quantities of a work-precision frame, in :func:`quantity_rank`'s order."""
    return sorted((c[4:] for c in frame.columns if c.startswith("err_")), key=quantity_rank)


def expected_order(spec: Mapping[str, Any], quantity: str, at_arrival: bool = False) -> float:
    """The order a method's ``expected_orders`` states for a quantity, NaN where none is stated.

    Every force maximum ``max_k`` takes ``max``, or ``max_at_arrival`` when it lies at a wave
    arrival and the method states one.
    """
    orders = spec.get("expected_orders") or {}
    key = quantity
    if quantity.startswith("max_"):
        key = "max_at_arrival" if at_arrival and "max_at_arrival" in orders else "max"
    value = orders.get(key)
    return math.nan if value is None else float(value)


def case_spec(spec: Mapping[str, Any], method: str, case: Mapping[str, Any] | None) -> Mapping[str, Any]:
    """A method's sweep settings on one case: its ``expected_orders`` replaced by the case's own
    for the method (config.yaml ``work_precision.per_case.<case>.expected_orders.<method>``)."""
    orders = ((case or {}).get("expected_orders") or {}).get(method)
    return spec if orders is None else {**spec, "expected_orders": orders}


def fit_indices(error: np.ndarray, floor: np.ndarray, fit_levels: int) -> np.ndarray:
    """Indices (coarse to fine) of the levels an order is fitted on: the finest ``fit_levels``
    whose error is finite, > 0 and above :data:`FLOOR_FACTOR` times the reference's estimate."""
    usable = np.isfinite(error) & (error > 0) & (error > FLOOR_FACTOR * np.nan_to_num(floor, nan=np.inf))
    return np.flatnonzero(usable)[-fit_levels:]


def _levels_text(levels: Sequence[int]) -> str:
    """Level numbers as runs: ``3-6``, or ``2-3, 5`` when a level is left out."""
    runs: list[list[int]] = []
    for level in levels:
        if runs and level == runs[-1][-1] + 1:
            runs[-1].append(level)
        else:
            runs.append([level])
    return ", ".join(f"{r[0]}-{r[-1]}" if len(r) > 1 else f"{r[0]}" for r in runs)


def levels_in(text: str) -> set[int]:
    """The level numbers of a ``fitted_levels`` text (``3-6``, ``2-3, 5``; empty: none)."""
    out: set[int] = set()
    for part in filter(None, (p.strip() for p in str(text).split(","))):
        first, _, last = part.partition("-")
        out.update(range(int(first), int(last or first) + 1))
    return out


#: The three-level columns of a method that is not its own reference by its finest level.
_NO_INDEX = {"gci_order": math.nan, "gci_pct": math.nan, "oscillatory": None, "u_osc_pct": math.nan}


def _uncertainty_columns(group: pd.DataFrame, quantity: str) -> dict[str, Any]:
    """The three-level index of a method that is its own reference by its finest level."""
    signed = group.get(f"signed_err_{quantity}")
    if signed is None or len(group) < 3 or not np.all(np.isfinite(signed.to_numpy(float)[-3:])):
        return dict(_NO_INDEX)
    f1, f2, f3 = 1.0 + signed.to_numpy(float)[:-4:-1]
    found = numerical_uncertainty(f1, f2, f3, constant_ratio(group["resolution_value"].to_numpy(float)[-3:]))
    return {
        "gci_order": found.index.order,
        "gci_pct": 100.0 * found.index.gci,
        "oscillatory": found.oscillatory,
        "u_osc_pct": 100.0 * found.half_range if not math.isfinite(found.index.gci) else math.nan,
    }


def _order_columns(
    group: pd.DataFrame, quantity: str, spec: Mapping[str, Any], fit_levels: int, arrival_window: float
) -> dict[str, Any]:
    """The expected and the fitted order of one quantity of one method's levels (coarse to fine)."""
    err = group[f"err_{quantity}"].to_numpy(float)
    index = fit_indices(err, group[f"ref_err_{quantity}"].to_numpy(float), fit_levels)
    fitted = len(index) >= 3  # two points give a ratio, not a range
    fit = (
        fitted_order(1.0 / group["resolution_value"].to_numpy(float)[index], err[index])
        if fitted
        else FittedOrder(math.nan, math.nan, len(index))
    )
    signed, offset = group.get(f"signed_err_{quantity}"), group.get(f"arrival_offset_{quantity}")
    offset = float(offset.iloc[-1]) if offset is not None else math.nan
    expected = expected_order(spec, quantity, at_arrival=abs(offset) <= arrival_window)
    within = abs(fit.order - expected) <= ORDER_TOLERANCE if fitted and math.isfinite(expected) else None
    monotone = is_monotone(err[index]) if fitted else None
    return {
        "expected_order": expected,
        "observed_order": fit.order,
        "order_stderr": fit.stderr,
        "fitted_levels": _levels_text(group["level"].to_numpy(int)[index]) if fitted else "",
        "monotone": monotone,
        "sign_change": changes_sign(signed.to_numpy(float)[index]) if fitted and signed is not None else None,
        "within_expected": within,
        "asymptotic": bool(monotone and within) if within is not None else None,
        "arrival_offset": offset,
    }


def observed_orders(
    frame: pd.DataFrame,
    methods: Mapping[str, Mapping[str, Any]],
    fit_levels: int,
    *,
    arrival_window: float,
    per_case: Mapping[str, Mapping[str, Any]] | None = None,
) -> pd.DataFrame:
    """The order of each method and quantity, fitted on the asymptotic range, against the expected.

    The fit (:func:`rodimpact.analysis.convergence.fitted_order`: log error against log h,
    h = 1 / resolution) takes the levels of :func:`fit_indices`, at least three of them.

    Parameters
    ----------
    frame : DataFrame
        :func:`work_precision_frame`.
    methods : mapping
        config.yaml's ``work_precision.methods`` (``expected_orders``, ``reference``,
        ``as_reference``).
    fit_levels : int
        At most this many levels are fitted.
    arrival_window : float
        A maximum within this fraction of 2L/c of a wave arrival takes ``max_at_arrival``.
    per_case : mapping, optional
        config.yaml's ``work_precision.per_case``: a case's own expected orders per method
        (:func:`case_spec`).

    Returns
    -------
    DataFrame
        One row per case, method and quantity it has: ``expected_order`` (NaN: none stated),
        ``observed_order`` and ``order_stderr`` (NaN when fewer than three levels qualify),
        ``fitted_levels`` (e.g. ``3-6``), ``monotone`` (the errors fall at every fitted level),
        ``sign_change`` (the signed errors cross zero there; scalars only),
        ``within_expected`` (within :data:`ORDER_TOLERANCE` of the expected order),
        ``asymptotic`` (monotone and within it), ``arrival_offset`` (maxima: the distance from
        a wave arrival, / 2L/c), and for a method that is its own reference by its finest level
        the index of its finest three levels: ``gci_order``, ``gci_pct``, ``oscillatory``,
        ``u_osc_pct`` (half the range, where no index is defined); flags are None where they
        do not apply.
    """
    rows = []
    for (case_id, method), group in frame.groupby(["case_id", "method"], sort=False):
        group = group.sort_values("resolution_value")
        spec = case_spec(methods[method], method, (per_case or {}).get(case_id))
        own_finest = spec["reference"] == method and spec.get("as_reference", "richardson") == "finest"
        for quantity in quantities(frame):
            if not np.isfinite(group[f"err_{quantity}"].to_numpy(float)).any():
                continue  # the method finds no such maximum on this case
            rows.append(
                {
                    "case_id": case_id,
                    "method": method,
                    "quantity": quantity,
                    **_order_columns(group, quantity, spec, fit_levels, arrival_window),
                    **(_uncertainty_columns(group, quantity) if own_finest else _NO_INDEX),
                }
            )
    return pd.DataFrame(rows)
