"""The sensor re-examined with yielding layers (make sensor-plastic): what it takes from the
configuration, and its exponent. The study itself is the named target (about a quarter of an hour);
the law with memory and the dynamic continuum it compares are tested in test_tabulated_memory.py,
test_plastic_indentation.py and test_plastic_dynamic.py."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from rodimpact.tools.sensor_plastic import (
    MODES,
    READING,
    layer_yield_stresses,
    main,
    time_exponent,
    with_layer_yield,
)


@pytest.fixture(scope="module")
def materials(root):
    return yaml.safe_load((root / "config" / "materials.yaml").read_text())["materials"]


@pytest.fixture(scope="module")
def rows(shipped_project):
    return [c for c in shipped_project.cases.values() if c.get("variant") == READING]


def test_the_yield_stresses_come_from_each_layers_yielding_variant(materials, rows):
    """Every sensor layer's material has a yielding variant; nominal inside its range, the range's
    ends as the low and high modes."""
    names = sorted({layer["material"]["name"] for c in rows for layer in c["contact"]["stack"]["layers"]})
    assert names == ["cyanoacrylate", "pvdf", "silver_ink"]
    stresses = layer_yield_stresses(materials, names)
    assert set(stresses) == set(MODES) - {"elastic"}
    for name in names:
        entry = materials[f"{name}_yielding"]
        assert stresses["nominal"][name] == entry["yield_stress_pa"]
        assert [stresses["low"][name], stresses["high"][name]] == entry["ranges"]["yield_stress_pa"]
        assert stresses["low"][name] <= stresses["nominal"][name] <= stresses["high"][name]


def test_only_the_layers_yield(materials, rows):
    """The case with yield stresses: each layer's material gains its own, the ball and the rod stay
    elastic, and the shipped case is left as it was."""
    case = next(c for c in rows if c["id"].startswith("ball_3.16mm"))
    stresses = layer_yield_stresses(materials, ["cyanoacrylate", "pvdf", "silver_ink"])["low"]
    plastic = with_layer_yield(case, stresses)
    for layer in plastic["contact"]["stack"]["layers"]:
        assert layer["material"]["yield_stress_pa"] == stresses[layer["material"]["name"]]
    assert "yield_stress_pa" not in plastic["impactor"]["material"]
    assert "yield_stress_pa" not in plastic["rod"]["material"]
    assert all("yield_stress_pa" not in layer["material"] for layer in case["contact"]["stack"]["layers"])


def test_the_time_exponent_of_a_power_law():
    """t = c m^b sampled exactly gives b back (rtol 1e-12); the measured Table 2 times give 0.272."""
    mass = np.array([0.13, 0.44, 0.71, 1.04, 3.5, 8.4]) * 1e-3
    assert time_exponent(mass, 3.0 * mass**0.2) == pytest.approx(0.2, rel=1e-12)


def test_the_measured_exponent(rows):
    """The measured contact times of the six balls grow as m^0.272 (docs/sensor.md)."""
    mass = [float(c["impactor"]["mass_kg"]) for c in rows]
    measured = [float(c["measured"]["contact_time_us"]) for c in rows]
    assert len(rows) == 6
    assert time_exponent(mass, measured) == pytest.approx(0.2724, abs=5e-4)


def test_the_markdown_says_what_the_tables_hold(rows, root, tmp_path, monkeypatch):
    """From CSV files of power-law times (b = 0.25, 0.26, 0.24, 0.27 by mode) the table states each
    mode's exponent and each row's shift by yield; where the default build's band is missing, its
    column holds a dash, and the provenance record lists what was written."""
    monkeypatch.chdir(root)
    exponents = {"elastic": 0.25, "nominal": 0.26, "low": 0.24, "high": 0.27}
    records = []
    for case in rows:
        mass = float(case["impactor"]["mass_kg"])
        for mode, b in exponents.items():
            records.append(
                {
                    "case": case["id"],
                    "mass_kg": mass,
                    "measured_us": float(case["measured"]["contact_time_us"]),
                    "mode": mode,
                    "contact_time_us": 300.0 * mass**b,
                    "restitution": 1.0 if mode == "elastic" else 0.7,
                    "dissipated_energy_J": 0.0 if mode == "elastic" else 1e-6,
                    "impact_energy_J": 2e-6,
                    "residual_approach_m": 0.0 if mode == "elastic" else 2e-6,
                    "error_pct": 100 * (300.0 * mass**b / float(case["measured"]["contact_time_us"]) - 1),
                }
            )
    pd.DataFrame(records).to_csv(tmp_path / "sensor_plastic.csv", index=False)
    assert main(["--out", str(tmp_path), "--markdown-only", "--band", str(tmp_path / "none.csv")]) == 0
    text = (tmp_path / "sensor_plastic.md").read_text()
    assert "elastic sensor 0.250; yielding layers 0.260 (low yield stresses 0.240, high 0.270)" in text
    assert "measured b = 0.272" in text
    light = 0.13e-3
    shift = 100 * (light**0.26 / light**0.25 - 1)
    assert f"| {shift:+.1f} % |" in text and "| – |" in text
    record = json.loads((tmp_path / "sensor_plastic.provenance.json").read_text())
    assert sorted(Path(a).name for a in record["artifacts"]) == ["sensor_plastic.csv", "sensor_plastic.md"]
