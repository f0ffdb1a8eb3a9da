"""Regenerate tests/golden/runs.csv from the shipped configuration.

    .venv/bin/python tests/golden/regenerate.py

A change of method that moves these numbers must update the golden file in the same commit
and say why in the commit message (see docs/verification.md, "Regression of the published numbers").
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from rodimpact.config.load import load_global_config, load_project
from rodimpact.jobs.runner import run_case

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = Path(__file__).with_name("runs.csv")
#: Methods too slow to regress on every case in CI: method -> the cases that are (fem_axi's
#: 24 Table 2 runs take minutes; its numerics are covered by tests/test_fem_axi.py).
EXPENSIVE = {"fem_axi": ("model",)}
#: Contact laws whose runs need a job's output (the tabulated law's curve is fem_axi's static
#: indentation, minutes per case): not regressed here; tests/test_film_law.py covers the law.
NEEDS_JOB_OUTPUT = ("tabulated",)


def golden_frame() -> pd.DataFrame:
    """Contact time, force maxima and rebound velocity of every run (every method) of the paper's cases."""
    config = load_global_config(ROOT / "config" / "config.yaml")
    project = load_project(config, root=ROOT)
    rows = []
    # the paper's sets (config.yaml targets.sets); the stress set is checked by the
    # stability study against its own tolerances (tests/test_studies.py, stability.csv)
    for case in (c for name in config["targets"]["sets"] for c in project.cases_in(name)):
        if (case.get("contact") or {}).get("law") in NEEDS_JOB_OUTPUT:
            continue
        for method in case["methods"]:
            if method in EXPENSIVE and case["id"] not in EXPENSIVE[method]:
                continue
            result = run_case(case, method)
            rows.append(
                {
                    "case_id": case["id"],
                    "method": method,
                    "n_contacts": result.n_contacts,
                    "contact_time_s": result.contact_time_s,
                    "peak_force_N": " ".join(f"{p:.12g}" for p in result.peak_force_N),
                    "rebound_velocity_m_s": result.rebound_velocity_m_s,
                }
            )
    return pd.DataFrame(rows)


def parse_peaks(text: str) -> np.ndarray:
    return np.array([float(v) for v in str(text).split()])


if __name__ == "__main__":
    frame = golden_frame()
    frame.to_csv(GOLDEN, index=False, float_format="%.12g")
    print(f"wrote {GOLDEN} ({len(frame)} runs)", file=sys.stderr)
