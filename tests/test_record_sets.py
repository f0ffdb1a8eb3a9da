"""Every combination of records the docs allow builds its comparison and figures: a set measured
only by force records, only by strain records, only by velocity records (the impactor's and a
free far end's), and one that mixes them with a scalar, each through the workflow from its YAML
alone (config/README.md, "Comparing with your experiment")."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from helpers.copies import copy_project, git_commit
from helpers.snakemake_cli import BUILD_TIMEOUT_S, snakemake

pytestmark = pytest.mark.workflow

#: The gauge example's two lightest balls on its steel rod, with a free far end.
BALLS = ("gauge_8mm", "gauge_12mm")
STATION_M, GAUGE_M = 0.25, 0.005
OUTPUTS = ["contact_force", "gauge_strain", "impactor_velocity", "far_end_velocity"]

#: set -> per ball, the records (and scalars) its case gives: force, strain, impactor, far_end, time
SETS = {
    "lab_force": [("force",), ("force",)],
    "lab_strain": [("strain",), ("strain",)],
    "lab_velocity": [("impactor",), ("far_end",)],
    "lab_mixed": [("force", "strain", "far_end"), ("impactor", "time")],
}


def _records(shipped_project, directory: Path) -> dict[str, dict]:
    """Each ball's records, made from its own SEM run with 1 % noise, sampled every 0.5 µs from
    20 µs before the impact, written beside the case files; ball -> its bodies and record blocks."""
    from rodimpact.jobs.runner import run_case

    made = {}
    rng = np.random.default_rng(5)
    for ball in BALLS:
        case = copy.deepcopy(shipped_project.cases[ball])
        case["rod"]["far_end"], case["outputs"] = "free", OUTPUTS
        result = run_case(case, "sem")
        series = {name: array for name, (array, _, _) in result.series(OUTPUTS).items()}
        t = series["time"]
        t_us = np.arange(-20.0, 1e6 * t[-1], 0.5)
        strain = np.asarray(series["gauge_strain"]).reshape(len(t), -1)[:, 0]
        signals = {
            "force": ("time_us,force_N", series["contact_force"], 0.0),
            "strain": ("time_us,strain_microstrain", 1e6 * strain, 0.0),
            "impactor": ("time_us,velocity_m_s", series["impactor_velocity"], series["impactor_velocity"][0]),
            "far_end": ("time_us,velocity_m_s", series["far_end_velocity"], 0.0),
        }
        blocks = {}
        for kind, (header, values, before) in signals.items():
            sampled = np.interp(1e-6 * t_us, t, values, left=before)
            noisy = sampled + rng.normal(0.0, 0.01 * float(np.max(np.abs(sampled - before))), len(t_us))
            name = f"{ball}_{kind}.csv"
            (directory / name).write_text(
                header + "\n" + "".join(f"{a:.3f},{float(b)!r}\n" for a, b in zip(t_us, noisy, strict=True))
            )
            blocks[kind] = {"file": f"lab/{name}"}
        blocks["strain"].update(station_m=STATION_M, gauge_length_m=GAUGE_M)
        blocks["impactor"]["of"], blocks["far_end"]["of"] = "impactor", "far_end"
        made[ball] = {
            "impactor": {k: case["impactor"][k] for k in ("mass_kg", "radius_m", "velocity_m_s")},
            "blocks": blocks,
            "contact_time_us": 1e6 * float(result.summary()["contact_time_s"]),
        }
    return made


def _measured(ball: dict, gives: tuple[str, ...]) -> dict:
    measured = {"source": "the SEM's own run, with 1 % noise (a test)"}
    for kind in gives:
        if kind == "time":
            measured["contact_time_us"] = round(ball["contact_time_us"], 3)
        else:
            key = {"force": "force_history", "strain": "strain_history"}.get(kind, "velocity_history")
            measured[key] = ball["blocks"][kind]
    return measured


def test_every_combination_of_records_builds_its_comparison(shipped_project, tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    cases_dir = project / "config" / "cases"
    (cases_dir / "lab").mkdir()
    balls = _records(shipped_project, cases_dir / "lab")
    for name, rows in SETS.items():
        document = {
            "set": name,
            "description": f"A test set measured by {name[4:]} records.",
            "defaults": {"rod": {"length_m": 0.5, "radius_m": 0.005, "material": "steel", "far_end": "free"}},
            "cases": [
                {
                    "id": f"{name}_{ball}",
                    "description": f"{ball} on a free steel rod",
                    "impactor": {**balls[ball]["impactor"], "material": "steel"},
                    "methods": ["sem"],
                    "measured": _measured(balls[ball], gives),
                }
                for ball, gives in zip(BALLS, rows, strict=True)
            ],
        }
        (cases_dir / f"{name}.yaml").write_text(yaml.safe_dump(document, sort_keys=False))
    config = project / "config" / "config.yaml"
    document = yaml.safe_load(config.read_text())
    document["targets"]["sets"] += list(SETS)
    config.write_text(yaml.safe_dump(document, sort_keys=False))
    git_commit(project)
    endings = {
        "lab_force": ["force"],
        "lab_strain": ["strain"],
        "lab_velocity": ["velocity"],
        "lab_mixed": ["force", "strain", "velocity"],
    }
    targets = [f"results/tables/compare_{name}.csv" for name in SETS]
    targets += [f"results/figures/compare_{name}.png" for name in SETS]
    targets += [f"results/figures/compare_{name}_{e}.png" for name, ends in endings.items() for e in ends]
    run = snakemake(project, "-j2", *targets, timeout=BUILD_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    for target in targets:
        assert (project / target).stat().st_size > 0, target
    expected = {
        "lab_force": {"signal_contact_time_us", "history_l2_pct"},
        "lab_strain": {"strain_arrival_us", "strain_peak_microstrain", "strain_l2_pct"},
        "lab_velocity": {"impactor_velocity_l2_pct", "far_end_arrival_us", "far_end_peak_velocity_m_s"},
        "lab_mixed": {"contact_time_us", "signal_contact_time_us", "strain_peak_microstrain", "far_end_arrival_us"},
    }
    for name, quantities in expected.items():
        frame = pd.read_csv(project / f"results/tables/compare_{name}.csv")
        assert quantities <= set(frame["quantity"]), (name, sorted(set(frame["quantity"])))
        # each record was made from the SEM's own run: its values agree with it within the noise
        values = frame[frame["quantity"].isin(["strain_peak_microstrain", "far_end_peak_velocity_m_s"])]
        assert (values["error_pct"].abs() < 3.0).all(), values
