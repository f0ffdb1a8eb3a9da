"""The comparison with measurements on the shipped worked example, whose records are synthetic
(fem1d's force, sampled, placed 100 us into the record, plus 1 % noise): the comparison must
recover what was put in."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rodimpact.analysis.history_compare import compare_force_histories
from rodimpact.analysis.measured import read_force_history
from rodimpact.jobs.runner import run_to_file
from rodimpact.present.compare import COLUMNS, compare_frame, compare_summary
from rodimpact.storage.runs import read_run
from rodimpact.tools.synthetic_history import SyntheticRecord, synthetic_history

from helpers.repo import ROOT


@pytest.fixture(scope="module")
def example(shipped_project, tmp_path_factory) -> dict:
    """The example's runs by both methods, stored and read back as the rule reads them."""
    out = tmp_path_factory.mktemp("example")
    cases = [shipped_project.cases[c] for c in shipped_project.sets["example"]]
    records = [
        read_run(run_to_file(case, method, out / f"{case['id']}-{method}.h5"))
        for case in cases
        for method in case["methods"]
    ]
    histories = {
        c["id"]: (
            read_force_history(ROOT / c["measured"]["force_history"]["path"], c["measured"]["force_history"]),
            0.05,
        )
        for c in cases
    }
    return {"cases": cases, "records": records, "histories": histories}


def test_the_shipped_records_are_what_the_tool_makes(example) -> None:
    """Each synthetic record is reproduced by its stated command, to the digits written."""
    for case in example["cases"]:
        times, forces, _ = synthetic_history(case, SyntheticRecord())
        history, _ = example["histories"][case["id"]]
        np.testing.assert_allclose(history.time_s, 1e-6 * np.round(times, 3), rtol=1e-12)
        np.testing.assert_allclose(history.force_N, forces, rtol=1e-5, atol=1e-5)


def test_the_alignment_finds_the_trigger_and_the_norms_the_noise(example) -> None:
    """The record was placed 100 us after the computed contact's start: the shift is -100 us to
    within a sample (1 us). Without the noise, fem1d's L2 error is the sampling's alone (1 us
    samples joined linearly); what the noise adds to it, in quadrature, is the realised noise's
    own (1 % of the peak per sample, joined linearly) and that of the misalignment the noise
    causes at the threshold's crossing, within 15 %."""
    for record in (r for r in example["records"] if r.method == "fem1d"):
        case = next(c for c in example["cases"] if c["id"] == record.case_id)
        history, threshold = example["histories"][record.case_id]
        result = compare_force_histories(
            history.time_s, history.force_N, record.series["time"], record.series["contact_force"], threshold
        )
        assert result.shift_s == pytest.approx(-100e-6, abs=1e-6)
        times, clean, _ = synthetic_history(case, SyntheticRecord(noise=0.0))
        quiet = compare_force_histories(1e-6 * times, clean, record.series["time"], record.series["contact_force"])
        inside = (history.time_s + result.shift_s >= result.time_s[0]) & (
            history.time_s + result.shift_s <= result.time_s[-1]
        )
        noisy = history.force_N
        # the realised noise, joined linearly between samples: 2/3 of its mean square on average
        expected = math.sqrt(2.0 / 3.0 * np.mean((noisy - clean)[inside] ** 2) / np.mean(noisy[inside] ** 2))
        # the noise also moves the threshold's crossing, so the records are aligned off by delta:
        # an error P'(t) delta, of relative L2 size rms(P') |delta| / rms(P)
        delta = result.shift_s - quiet.shift_s
        slope = np.gradient(result.model_N, result.time_s)
        misaligned = math.sqrt(np.trapezoid(slope**2, result.time_s) / np.trapezoid(result.model_N**2, result.time_s))
        expected = math.hypot(expected, misaligned * abs(delta))
        assert quiet.l2_error < 0.3 * result.l2_error
        # independent errors add in quadrature: what the noise adds is the noise's and the misalignment's
        assert math.sqrt(result.l2_error**2 - quiet.l2_error**2) == pytest.approx(expected, rel=0.15)


def test_the_table_sets_each_measured_value_against_each_method(example) -> None:
    frame = compare_frame(example["records"], {c: {"force_history": h} for c, (h, _) in example["histories"].items()})
    assert tuple(frame.columns) == COLUMNS and frame[["case_id", "method", "quantity", "unit"]].notna().all().all()
    per_case = {
        "contact_time_us",
        "peak_force_n",
        "rebound_velocity_m_s",
        "restitution",
        "signal_contact_time_us",
        "history_l2_pct",
        "history_max_pct",
    }
    for (case_id, method), rows in frame.groupby(["case_id", "method"]):
        assert set(rows["quantity"]) == per_case, (case_id, method)
        # the restitution is the rebound over the impact velocity, measured and computed alike
        rebound, restitution = (rows[rows["quantity"] == q].iloc[0] for q in ("rebound_velocity_m_s", "restitution"))
        impact = next(r.config for r in example["records"] if r.case_id == case_id)["impactor"]["velocity_m_s"]
        assert restitution["measured"] == pytest.approx(rebound["measured"] / impact, rel=1e-15)
        assert restitution["computed"] == pytest.approx(rebound["computed"] / impact, rel=1e-12)
        assert restitution["error_pct"] == pytest.approx(rebound["error_pct"], rel=1e-9)
    # the measured scalars are fem1d's, rounded as written: its errors are the rounding's
    fem1d = frame[(frame["method"] == "fem1d") & frame["quantity"].isin(["contact_time_us", "peak_force_n"])]
    assert (fem1d["error_pct"].abs() < 0.2).all()
    summary = compare_summary(frame)
    row = summary[(summary["method"] == "sem") & (summary["quantity"] == "contact_time_us")].iloc[0]
    errors = frame[(frame["method"] == "sem") & (frame["quantity"] == "contact_time_us")]["error_pct"]
    assert row["cases"] == 2 and row["max_abs_error_pct"] == pytest.approx(errors.abs().max(), rel=1e-12)
    assert row["mean_signed_error_pct"] == pytest.approx(errors.mean(), rel=1e-12)


def test_a_set_needs_no_name_in_the_code() -> None:
    """Nothing under workflow/ or src/ names the example set: it is compared because its cases
    carry measurements."""
    for path in [*Path(ROOT, "workflow").rglob("*.smk"), *Path(ROOT, "src").rglob("*.py")]:
        assert '"example"' not in path.read_text(encoding="utf-8"), path


def test_a_measurement_past_the_rigid_wall_is_flagged_in_the_table(example) -> None:
    """The shipped example's measurements lie within what the law allows: no warning. A contact
    time shorter, or a peak higher, than the same law gives on a rigid wall is flagged in its
    row (the rod only lengthens the contact and lowers its peak), and nothing else changes."""
    from rodimpact.model.problem import ImpactProblem
    from rodimpact.present.compare import RIGID_MARGIN, rigid_wall_warnings

    frame = compare_frame(example["records"], {c: {"force_history": h} for c, (h, _) in example["histories"].items()})
    assert frame["warning"].isna().all()
    record = example["records"][0]
    rigid = ImpactProblem.from_case(record.config).rigid_contact
    measured = {
        **record.config["measured"],
        "contact_time_us": 0.5 * 1e6 * rigid.contact_time_s,
        "peak_force_n": 1.5 * rigid.peak_force_N,
    }
    warnings = rigid_wall_warnings({**record.config, "measured": measured})
    assert set(warnings) == {"contact_time_us", "peak_force_n"}
    assert warnings["contact_time_us"].startswith("shorter than the ") and "rigid wall" in warnings["contact_time_us"]
    just_inside = {**measured, "contact_time_us": (1 - 0.5 * RIGID_MARGIN) * 1e6 * rigid.contact_time_s}
    assert "contact_time_us" not in rigid_wall_warnings({**record.config, "measured": just_inside})
