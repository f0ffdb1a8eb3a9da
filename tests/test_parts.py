"""A batch cut into jobs of about a target cost (rodimpact.jobs.parts.cut): the bounds the module
states, on random costs and on the edge cases."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rodimpact.jobs.parts import MAX_PARTS, Part, TooManyParts, cut


def _check_cover(parts: tuple[Part, ...], costs: list[float]) -> None:
    """Consecutive, non-empty parts covering every run once, in order, each with its runs' cost."""
    assert parts[0].start == 0 and parts[-1].stop == len(costs)
    for before, after in zip(parts, parts[1:]):
        assert before.stop == after.start
    for part in parts:
        assert part.stop > part.start
        assert part.typical_s == pytest.approx(math.fsum(costs[part.start : part.stop]), rel=1e-12, abs=0.0)


@pytest.mark.parametrize("seed", range(20))
def test_parts_cover_the_runs_in_order_within_the_stated_bounds(seed: int) -> None:
    """ceil(total / target) windows at most (one per run at most); a part costs at most its window
    plus its largest run, so at most twice the target when no run exceeds the target; when the
    runs cost more than the target in all, no part is below half of it minus its neighbours'
    largest run."""
    rng = np.random.default_rng(seed)
    count = int(rng.integers(1, 3000))
    costs = list(rng.lognormal(mean=-3.0, sigma=1.0, size=count))  # sem-like points, ~0.05 s
    target = float(rng.uniform(0.05, 30.0))
    parts = cut(costs, target)
    _check_cover(parts, costs)
    total = math.fsum(costs)
    windows = min(count, max(1, math.ceil(total / target)))
    assert len(parts) <= windows
    width = total / windows
    largest = max(costs)
    for part in parts:
        assert part.typical_s <= width + max(costs[part.start : part.stop]) * (1 + 1e-12)
        if largest <= target:
            assert part.typical_s <= 2.0 * target
    if total > target and largest <= target / 4:
        assert min(p.typical_s for p in parts) >= width - 2 * largest


def test_a_batch_within_the_target_is_one_part_and_a_large_one_many() -> None:
    assert cut([0.01] * 25, 30.0) == (Part(0, 25, pytest.approx(0.25)),)
    assert len(cut([0.0] * 10, 1.0)) == 1  # nothing to spread
    parts = cut([0.04] * 10_000, 30.0)  # 400 s of points
    assert len(parts) == 14 and {p.stop - p.start for p in parts} <= {714, 715}


def test_a_run_costlier_than_the_target_is_a_part_of_its_own_and_never_split() -> None:
    costs = [1.0, 1.0, 100.0, 1.0, 1.0]
    parts = cut(costs, 10.0)
    _check_cover(parts, costs)
    assert any(p.start == 2 and p.stop == 3 for p in parts)
    assert len(cut([5.0] * 4, 1.0)) == 4  # at most one part per run


def test_the_cut_is_a_function_of_the_costs_and_the_target_only() -> None:
    costs = list(np.random.default_rng(7).uniform(0.0, 2.0, size=500))
    assert cut(costs, 12.5) == cut(list(costs), 12.5) == cut(tuple(costs), 12.5)


def test_too_many_parts_are_refused_with_the_count() -> None:
    with pytest.raises(TooManyParts) as raised:
        cut([1.0] * (MAX_PARTS + 1), 1.0)
    assert raised.value.parts == MAX_PARTS + 1 and raised.value.target_s == 1.0
    assert "100,001 jobs, more than 100,000: raise the target" in str(raised.value)
    assert len(cut([1.0] * MAX_PARTS, 1.0)) == MAX_PARTS


@pytest.mark.parametrize("target", [0, -1.0, math.nan, math.inf, True, "30"])
def test_a_target_that_is_not_a_positive_number_is_refused(target: object) -> None:
    with pytest.raises(ValueError, match="target_s"):
        cut([1.0], target)  # type: ignore[arg-type]


@pytest.mark.parametrize("costs", [[], [1.0, -0.5], [math.nan], [math.inf]])
def test_costs_must_be_finite_and_not_negative(costs: list[float]) -> None:
    with pytest.raises(ValueError, match="costs"):
        cut(costs, 1.0)


def test_named_runs_are_cut_by_their_typical_costs_and_ask_for_their_upper_side_ones() -> None:
    """cut_runs: the parts of cut() by name, a run's costs summed (its solve and its curve), and
    each part's job asking for the sum of its runs' upper-side times and their largest memory."""
    from rodimpact.jobs.parts import cut_runs
    from rodimpact.jobs.resources import job_resources
    from rodimpact.solvers.cost import Cost

    def cost(solve_s: float, mem_mib: float = 10.0) -> Cost:
        return Cost(time_step_s=1e-7, steps=100.0, solve_s=solve_s, mem_mib=mem_mib, typical_share=0.1)

    costs = {f"p{i}": [cost(100.0)] for i in range(6)}
    costs["p5"] = [cost(100.0), cost(200.0, mem_mib=500.0)]  # a point whose job computes its curve
    parts = cut_runs(costs, 25.0)  # typical: 10 s a point, 30 s the last; 4 windows of 20 s
    assert [p.names for p in parts] == [("p0", "p1"), ("p2", "p3"), ("p4",), ("p5",)]
    assert [p.typical_s for p in parts] == pytest.approx([20.0, 20.0, 10.0, 30.0])
    assert parts[3].resources == job_resources([(cost(100.0), 1.0), (cost(200.0, mem_mib=500.0), 1.0)])
    with pytest.raises(ValueError, match="run 'x' has no cost"):
        cut_runs({"x": []}, 1.0)
