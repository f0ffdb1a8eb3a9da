"""Tests of rodimpact.tools.accuracy_cost: the cheapest level that reaches a tolerance."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest

from rodimpact.tools.accuracy_cost import accuracy_cost, main


def _levels(method: str, errors: list[float], times: list[float], reference: float = 1e-10) -> list[dict]:
    return [
        {
            "method": method,
            "case_id": "c",
            "level": level,
            "resolution": f"steps={100 * 2**level}",
            "wall_time_min_s": time,
            "err_contact_time": error,
            "err_max_1": error / 2,
            "ref_err_contact_time": reference,
            "ref_err_max_1": reference,
        }
        for level, (error, time) in enumerate(zip(errors, times))
    ]


@pytest.fixture
def table() -> pd.DataFrame:
    rows = _levels("a", [1e-3, 5e-5, 3e-7, 1e-8], [1.0, 2.0, 4.0, 8.0])
    rows += _levels("noisy", [1e-3, 5e-5, 3e-7], [1.0, 3.0, 2.5])  # a finer level timed faster
    rows += _levels("self", [1e-3, 1e-5, 0.0], [1.0, 2.0, 4.0], reference=5e-4)  # its own finest level
    frame = pd.DataFrame(rows)
    frame.loc[frame.method.eq("a") & frame.level.eq(1), "err_max_1"] = 2e-4  # the maximum not yet there
    return frame


def test_the_cheapest_level_with_both_errors_within_the_tolerance(table: pd.DataFrame) -> None:
    cost = accuracy_cost(table, [1e-4, 1e-6]).set_index("method")
    assert cost.loc["a", "cost_0.0001_s"] == 4.0  # level 1's first maximum misses 1e-4
    assert cost.loc["a", "cost_1e-06_s"] == 4.0
    assert cost.loc["noisy", "cost_0.0001_s"] == 2.5  # the cheapest, not the coarsest
    assert (cost.loc["a", "finest"], cost.loc["a", "finest_s"]) == ("steps=800", 8.0)


def test_no_tolerance_is_reached_below_the_references_own_uncertainty(table: pd.DataFrame) -> None:
    cost = accuracy_cost(table, [1e-4, 1e-3]).set_index("method")
    assert math.isnan(cost.loc["self", "cost_0.0001_s"])  # its finest level's error 0 says nothing
    assert cost.loc["self", "cost_0.001_s"] == 1.0


@pytest.mark.parametrize("tolerance", [0.0, -1e-4, math.nan])
def test_a_tolerance_must_be_positive(table: pd.DataFrame, tolerance: float) -> None:
    with pytest.raises(ValueError, match="tolerances"):
        accuracy_cost(table, [tolerance])


def test_a_missing_column_is_named(table: pd.DataFrame) -> None:
    with pytest.raises(ValueError, match="ref_err_max_1"):
        accuracy_cost(table.drop(columns="ref_err_max_1"), [1e-4])


def test_the_command_prints_the_table(table: pd.DataFrame, tmp_path: Path, capsys) -> None:
    path = tmp_path / "work_precision.csv"
    table.to_csv(path, index=False)
    assert main([str(path), "--tolerance", "1e-4"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed[0].split() == ["method", "case_id", "cost_0.0001_s", "finest", "finest_s"]
    assert printed[1].split() == ["a", "c", "4", "steps=800", "8"]
    assert main([str(tmp_path / "none.csv")]) == 2
