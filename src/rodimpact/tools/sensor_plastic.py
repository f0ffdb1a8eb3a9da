"""Table 2's sensor as built, its layers yielding: the experiment re-examined with plasticity.

The six balls of Table 2 on the text's rod (the cases ``ball_*-r10_l30_sensor_cal``: the SEM
with the law the continuum's static indentation of the case's ball, sensor layers and rod gives)
four times over:

- ``elastic``: the layers elastic, as the default build computes them;
- ``nominal``: each layer with the yield stress of its material's yielding variant in
  ``config/materials.yaml`` (``silver_ink_yielding``, ``pvdf_yielding``,
  ``cyanoacrylate_yielding``): J2 plasticity in the layers near the contact, the law with memory
  (loading and unloading curves) in the SEM;
- ``low`` and ``high``: every layer's yield stress at the low (high) end of its sourced range.

For each: the contact time against the measured, the restitution, the energy the contact
dissipated and the dent; over the six balls, the exponent of the contact time against the mass
(least squares in log-log) beside the measured one. Then the dynamic check of the law with
memory on two sensor rows (the lightest and the heaviest ball): ``fem_axi``'s dynamic run with
the yielding layers against the SEM through the law the same mesh's indentation gives.

The ball and the rod stay elastic (the layers carry the yield: docs/sensor.md). The layers are
thin beside the contact radius, and their plastic zone spreads further than a solid's: the
plastic region reaches 4 estimated contact radii (``plastic_extent``; at the default 2 the stress
beyond it reaches yield, and the run says so), and the contact, flattened by the flow, 2.5
(``contact_extent``; at the default 1.5 the low yield stresses' contact reaches the last
candidate).

``make sensor-plastic`` (``python -m rodimpact.tools.sensor_plastic --out results/sensor_plastic``)
writes ``sensor_plastic.csv``, ``sensor_plastic_dynamic.csv``, ``sensor_plastic.md`` and their
provenance record; docs/sensor.md gives its cost and quotes it.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import copy
import logging
import math
import sys
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import yaml

from rodimpact.config.load import load_project
from rodimpact.jobs.indentation import indentation_curve
from rodimpact.solvers.registry import METHODS
from rodimpact.storage.atomic import atomic_output
from rodimpact.storage.sidecar import write_provenance
from rodimpact.tools.yielding_rod import dynamic_check

__all__ = [
    "MODES",
    "READING",
    "layer_yield_stresses",
    "with_layer_yield",
    "sensor_plastic_row",
    "sensor_plastic_study",
    "time_exponent",
    "main",
]

log = logging.getLogger(__name__)

#: The reading of the rod re-examined: the text's (docs/results.md: the one the data support).
READING = "r10_l30_sensor_cal"
#: The same rows with the sensor as built for ``fem_axi`` (its own stack, no tabulated law).
DYNAMIC_READING = "r10_l30_sensor"
#: The yield stresses a run takes: none, each material's nominal, or every range's low or high end.
MODES = ("elastic", "nominal", "low", "high")
#: Where the layers yield: the plastic region's radius and the contact's fine zone, in estimated
#: contact radii (the low yield stresses spread the contact past the default 1.5; every mode takes
#: the same mesh, so that the band compares like with like).
ZONES = {"plastic_extent": 4.0, "contact_extent": 2.5}
#: The dynamic check's continuum (5 elements across, 100 steps per Hertz time, a horizon of 2
#: estimated contact times), the lightest and the heaviest ball.
DYNAMIC = {"elements_across": 5, "steps_per_contact": 100, "max_time_factor": 2.0}
DYNAMIC_ROWS = ("ball_3.16mm", "ball_12.73mm")
#: A layer's material -> its yielding variant in the materials file.
YIELDING_SUFFIX = "_yielding"


def layer_yield_stresses(materials: Mapping[str, Any], names: Sequence[str]) -> dict[str, dict[str, float]]:
    """Mode -> layer material -> yield stress, Pa, from each material's yielding variant.

    Parameters
    ----------
    materials : mapping
        The materials file's ``materials`` (name -> entry).
    names : sequence of str
        The layers' material names (``pvdf``...): each needs ``{name}_yielding`` with
        ``yield_stress_pa`` and its ``ranges.yield_stress_pa``.

    Raises
    ------
    KeyError
        A layer's material has no yielding variant, or the variant no yield stress or range.
    """
    out: dict[str, dict[str, float]] = {mode: {} for mode in MODES if mode != "elastic"}
    for name in names:
        entry = materials[f"{name}{YIELDING_SUFFIX}"]
        low, high = entry["ranges"]["yield_stress_pa"]
        out["nominal"][name] = float(entry["yield_stress_pa"])
        out["low"][name], out["high"][name] = float(low), float(high)
    return out


def with_layer_yield(case: Mapping[str, Any], stresses: Mapping[str, float]) -> dict[str, Any]:
    """``case`` with each sensor layer's material given its yield stress (by material name)."""
    out = copy.deepcopy(dict(case))
    for layer in out["contact"]["stack"]["layers"]:
        material = layer["material"]
        if material["name"] in stresses:
            material["yield_stress_pa"] = stresses[material["name"]]
    return out


def sensor_plastic_row(
    case: Mapping[str, Any], settings: Mapping[str, Any], sem_settings: Mapping[str, Any]
) -> dict[str, Any]:
    """One row and one set of yield stresses: the indentation, its law, the SEM through it.

    Returns
    -------
    dict
        ``contact_time_us``, ``restitution``, ``dissipated_energy_J``, ``residual_approach_m``,
        ``impact_energy_J``, ``peak_force_N``, the curve's ``max_force_N``, ``unloading_curves``,
        ``unloading_interpolation_error`` (NaN when elastic) and the path's ``path_s``.
    """
    started = time.perf_counter()
    curve = indentation_curve(case, settings)
    elapsed = time.perf_counter() - started
    run_case = {**case, "contact": {**case["contact"], "curve": curve.law_curve()}}
    result = METHODS["sem"].solve(run_case, sem_settings)
    if not result.success:
        raise RuntimeError(f"case {case['id']!r}: the SEM failed: {result.message}")
    summary = result.summary()
    impactor = case["impactor"]
    return {
        "contact_time_us": 1e6 * result.contact_time_s,
        "restitution": float(result.restitution),
        "dissipated_energy_J": float(summary["dissipated_energy_J"]),
        "residual_approach_m": float(summary["residual_approach_m"]),
        "impact_energy_J": 0.5 * float(impactor["mass_kg"]) * float(impactor["velocity_m_s"]) ** 2,
        "peak_force_N": float(np.max(result.peak_force_N)),
        "max_force_N": float(curve.summary["max_force_N"]),
        "unloading_curves": int(curve.summary.get("unloading_curves", 0)),
        "unloading_interpolation_error": float(curve.summary.get("unloading_interpolation_error_half", math.nan)),
        "path_s": elapsed,
    }


def _row_job(args: tuple[dict[str, Any], str, dict[str, Any], dict[str, Any]]) -> dict[str, Any]:
    case, mode, settings, sem_settings = args
    row = sensor_plastic_row(case, settings, sem_settings)
    return {"case": case["id"], "mode": mode, **row}


def time_exponent(mass_kg: Sequence[float], time_us: Sequence[float]) -> float:
    """The exponent b of t = c m^b, least squares in log-log."""
    return float(np.polyfit(np.log(np.asarray(mass_kg, float)), np.log(np.asarray(time_us, float)), 1)[0])


def sensor_plastic_study(
    cases: Sequence[Mapping[str, Any]],
    materials: Mapping[str, Any],
    settings: Mapping[str, Any],
    sem_settings: Mapping[str, Any],
    jobs: int = 2,
) -> pd.DataFrame:
    """Every row of ``cases`` in every mode of :data:`MODES`: one row of the frame each.

    Parameters
    ----------
    cases : sequence of mapping
        Resolved cases with a ``hertz_stack``/``tabulated`` sensor stack and a measured contact time.
    materials : mapping
        The materials file's ``materials``.
    settings, sem_settings : mapping
        ``numerics.fem_axi`` (with :data:`ZONES`) and ``numerics.sem``.
    jobs : int
        Processes side by side.
    """
    names = sorted({layer["material"]["name"] for c in cases for layer in c["contact"]["stack"]["layers"]})
    stresses = layer_yield_stresses(materials, names)
    work = []
    for case in cases:
        for mode in MODES:
            run = case if mode == "elastic" else with_layer_yield(case, stresses[mode])
            work.append((run, mode, dict(settings), dict(sem_settings)))
    with concurrent.futures.ProcessPoolExecutor(max_workers=jobs) as pool:
        rows = list(pool.map(_row_job, work))
    by_id = {c["id"]: c for c in cases}
    frame = pd.DataFrame(rows)
    frame.insert(1, "mass_kg", [float(by_id[c]["impactor"]["mass_kg"]) for c in frame["case"]])
    frame.insert(2, "measured_us", [float(by_id[c]["measured"]["contact_time_us"]) for c in frame["case"]])
    frame["error_pct"] = 100 * (frame["contact_time_us"] / frame["measured_us"] - 1)
    for name in names:
        frame[f"yield_{name}_pa"] = [stresses[m][name] if m != "elastic" else math.nan for m in frame["mode"]]
    return frame


def _dynamic_job(args: tuple[dict[str, Any], dict[str, Any]]) -> dict[str, Any]:
    return dynamic_check(*args)


def _markdown(frame: pd.DataFrame, dynamic: pd.DataFrame, band: pd.DataFrame | None = None) -> str:
    """The comparison as one table, the exponents, and the dynamic check; with ``band`` (the
    default build's ``sensor_band.csv``), the elastic constants' band of each row beside the yield
    stresses'."""
    nominal = frame[frame["mode"] == "nominal"].set_index("case")
    elastic = frame[frame["mode"] == "elastic"].set_index("case")
    low = frame[frame["mode"] == "low"].set_index("case")
    high = frame[frame["mode"] == "high"].set_index("case")
    order = elastic.sort_values("mass_kg").index
    lines = [
        "# Table 2's sensor as built, elastic and with its layers yielding",
        "",
        "The text's rod (10.0 mm radius, 30.1 mm); the SEM through the contact law the continuum's",
        "static indentation of each ball on the sensor's layers and the rod gives; yield stresses of the",
        "layers from config/materials.yaml (nominal, and every layer at the low or high end of its range:",
        "the contact time is not monotone in the yield stress, so the two ends do not bound the nominal).",
        "",
        "| Ball | Mass, g | Measured, µs | Elastic, µs (error) | Yielding, µs (error) | Shift by yield | "
        "Yielding, low / high yield stresses, µs | Elastic over the elastic constants' ranges, µs | Restitution "
        "| Dissipated, % of impact energy | Dent, µm |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    elastic_band = {} if band is None else band.set_index("case_id")[["band_min_us", "band_max_us"]].to_dict("index")
    for case in order:
        e, n = elastic.loc[case], nominal.loc[case]
        lines.append(
            f"| {case.split('-')[0].removeprefix('ball_').replace('mm', ' mm')} | {1000 * e['mass_kg']:.2f} "
            f"| {e['measured_us']:.2f} | {e['contact_time_us']:.2f} ({e['error_pct']:+.1f} %) "
            f"| {n['contact_time_us']:.2f} ({n['error_pct']:+.1f} %) "
            f"| {100 * (n['contact_time_us'] / e['contact_time_us'] - 1):+.1f} % "
            f"| {low.loc[case, 'contact_time_us']:.2f} / {high.loc[case, 'contact_time_us']:.2f} "
            f"| {_band_cell(elastic_band.get(case))} | {n['restitution']:.3f} "
            f"| {100 * n['dissipated_energy_J'] / n['impact_energy_J']:.0f} | {1e6 * n['residual_approach_m']:.2f} |"
        )
    measured = time_exponent(elastic.loc[order, "mass_kg"], elastic.loc[order, "measured_us"])
    exponents = {m: time_exponent(g["mass_kg"], g["contact_time_us"]) for m, g in frame.groupby("mode")}
    lines += [
        "",
        f"Contact time against mass, t ∝ m^b over the six balls: measured b = {measured:.3f}; elastic sensor "
        f"{exponents['elastic']:.3f}; yielding layers {exponents['nominal']:.3f} (low yield stresses "
        f"{exponents['low']:.3f}, high {exponents['high']:.3f}).",
        "",
        "Mean absolute error against the measured times: "
        + "; ".join(f"{m} {frame[frame['mode'] == m]['error_pct'].abs().mean():.1f} %" for m in MODES)
        + ".",
    ]
    if len(dynamic):
        lines += [
            "",
            "## The law with memory against the dynamic continuum",
            "",
            "fem_axi's dynamic run with the yielding layers (5 elements across, 100 steps per Hertz time)",
            "against the SEM through the law the same mesh's indentation gives.",
            "",
            "| Ball | fem_axi, µs | SEM, µs | Difference | fem_axi restitution | SEM restitution | Difference "
            "| fem_axi energy balance | Dissipated, % |",
            "|---|---|---|---|---|---|---|---|---|",
        ]
        for _, d in dynamic.iterrows():
            lines.append(
                f"| {d['case'].split('-')[0].removeprefix('ball_').replace('mm', ' mm')} "
                f"| {d['fem_axi_contact_time_us']:.2f} | {d['sem_contact_time_us']:.2f} "
                f"| {d['contact_time_difference_pct']:+.2f} % | {d['fem_axi_restitution']:.4f} "
                f"| {d['sem_restitution']:.4f} | {d['restitution_difference_pct']:+.2f} % "
                f"| {d['fem_axi_energy_error']:.1e} | {100 * d['fem_axi_dissipated_fraction']:.0f} |"
            )
    return "\n".join(lines) + "\n"


def _band_cell(entry: Mapping[str, float] | None) -> str:
    """The elastic constants' band of a row, or a dash where the default build has not made it."""
    return "–" if entry is None else f"{entry['band_min_us']:.2f} to {entry['band_max_us']:.2f}"


def main(argv: Sequence[str] | None = None) -> int:
    """Run the re-examination and the dynamic check; write the tables under ``--out``."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", type=Path, default=Path("config/config.yaml"))
    parser.add_argument("--out", type=Path, default=Path("results/sensor_plastic"))
    parser.add_argument("--jobs", type=int, default=2, help="processes side by side (default 2)")
    parser.add_argument("--no-dynamic", action="store_true", help="leave out the dynamic check")
    parser.add_argument(
        "--markdown-only", action="store_true", help="write sensor_plastic.md from the existing CSV files"
    )
    parser.add_argument(
        "--band",
        type=Path,
        default=Path("results/tables/sensor_band.csv"),
        help="the default build's band of the elastic constants, shown beside (when it exists)",
    )
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="%(message)s")
    config = yaml.safe_load(args.config.read_text())
    project = load_project(config)
    materials_file = Path(project.config["materials"])
    materials = yaml.safe_load(materials_file.read_text())["materials"]
    numerics = project.config["numerics"]
    cases = sorted(
        (c for c in project.cases.values() if c.get("variant") == READING),
        key=lambda c: float(c["impactor"]["mass_kg"]),
    )
    settings = {**numerics["fem_axi"], **ZONES}
    if args.markdown_only:
        frame = pd.read_csv(args.out / "sensor_plastic.csv")
        dynamic_file = args.out / "sensor_plastic_dynamic.csv"
        dynamic = pd.read_csv(dynamic_file) if dynamic_file.is_file() else pd.DataFrame()
    else:
        frame = sensor_plastic_study(cases, materials, settings, numerics["sem"], args.jobs)
        dynamic = pd.DataFrame()
    if not (args.no_dynamic or args.markdown_only):
        names = sorted({layer["material"]["name"] for c in cases for layer in c["contact"]["stack"]["layers"]})
        nominal = layer_yield_stresses(materials, names)["nominal"]
        work = [
            (with_layer_yield(project.cases[f"{row}-{DYNAMIC_READING}"], nominal), {**settings, **DYNAMIC})
            for row in DYNAMIC_ROWS
        ]
        with concurrent.futures.ProcessPoolExecutor(max_workers=args.jobs) as pool:
            dynamic = pd.DataFrame(list(pool.map(_dynamic_job, work)))
    args.out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, table in (("sensor_plastic.csv", frame), ("sensor_plastic_dynamic.csv", dynamic)):
        if args.markdown_only and len(table):
            written.append(args.out / name)
        elif len(table):
            with atomic_output(args.out / name) as tmp:
                table.to_csv(tmp, index=False, float_format="%.8g")
            written.append(args.out / name)
    band = pd.read_csv(args.band) if args.band.is_file() else None
    text = _markdown(frame, dynamic, band)
    with atomic_output(args.out / "sensor_plastic.md") as tmp:
        tmp.write_text(text, encoding="utf-8")
    written.append(args.out / "sensor_plastic.md")
    case_files = sorted({c["source_file"] for c in cases if c.get("source_file")})
    write_provenance(
        args.out / "sensor_plastic.provenance.json",
        [],
        written,
        {
            "config": [args.config, materials_file],
            "cases": case_files,
            **({"band": [args.band]} if band is not None else {}),
        },
    )
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
