"""CI regression: our numbers (every method) for every shipped case against a committed golden file.

The solver is deterministic; the tolerance only absorbs floating-point differences between
machines and library builds. A method change that moves the numbers must regenerate the
file (tests/golden/regenerate.py) in the same commit, with the reason.
"""

import importlib.util
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

RTOL = 1e-6  # relative; the methods' own discretisation errors at the shipped settings are ~1e-7 to 1e-5

_spec = importlib.util.spec_from_file_location("regenerate", Path(__file__).parent / "golden" / "regenerate.py")
regenerate = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(regenerate)


@pytest.fixture(scope="module")
def frames():
    golden = pd.read_csv(regenerate.GOLDEN)
    return golden, regenerate.golden_frame()


def test_every_shipped_run_is_in_the_golden_file(frames):
    golden, ours = frames
    assert sorted(zip(golden.case_id, golden.method)) == sorted(zip(ours.case_id, ours.method))


def test_numbers_match_the_golden_file(frames):
    golden, ours = frames
    merged = golden.merge(ours, on=["case_id", "method"], suffixes=("_golden", "_now"))
    for _, row in merged.iterrows():
        label = f"{row.case_id}/{row.method}"
        assert row.n_contacts_now == row.n_contacts_golden, label
        assert row.contact_time_s_now == pytest.approx(row.contact_time_s_golden, rel=RTOL), label
        assert row.rebound_velocity_m_s_now == pytest.approx(row.rebound_velocity_m_s_golden, rel=RTOL), label
        now, gold = regenerate.parse_peaks(row.peak_force_N_now), regenerate.parse_peaks(row.peak_force_N_golden)
        assert len(now) == len(gold), label
        np.testing.assert_allclose(now, gold, rtol=RTOL, err_msg=label)


def test_model_case_matches_the_papers_figure_2_shape(frames):
    """Fig. 2 of the paper: one contact with three maxima, the middle one the largest."""
    _, ours = frames
    for method in ("sem", "sem_paper", "fem1d", "fem_axi"):
        row = ours[(ours.case_id == "model") & (ours.method == method)].iloc[0]
        peaks = regenerate.parse_peaks(row.peak_force_N)
        assert row.n_contacts == 1 and len(peaks) == 3 and np.argmax(peaks) == 1
