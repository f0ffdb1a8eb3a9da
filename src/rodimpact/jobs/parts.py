"""A study's runs cut into jobs of about a target cost: the parts of a sweep.

A job costs seconds to start (snakemake parses the workflow, the process imports the stack), so
the paper's small sweeps run each in one job; a sweep of thousands of points in one job runs on
one core whatever ``-j`` says. :func:`cut` divides a sequence of runs, in their order, into
consecutive parts whose typical cost is about ``target_s`` (``batch.target_s`` in config.yaml):

* ``n = ceil(total / target_s)`` parts (at least one, at most one per run), each a window of
  ``total / n`` seconds (at most the target) of the runs' cumulative cost;
* a run belongs to the window that holds the middle of its own cost, so a part costs at most
  its window plus its largest run: at most twice the target when no run costs more than the
  target alone (a run that does is never split), and, when the runs cost more than the target
  in all, at least about half the target (no part smaller than a job is worth);
* a window that holds no run's middle (a run costlier than a window) is no part.

The costs are the cost models' typical times (:attr:`rodimpact.solvers.cost.Cost.typical_s`),
known when the workflow is parsed: the cut is a pure function of the study and the target, the
same on every machine, executor and ``-j``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from rodimpact.jobs.resources import JobResources, job_resources
from rodimpact.solvers.cost import Cost

__all__ = ["MAX_PARTS", "Part", "RunsPart", "TooManyParts", "cut", "cut_runs"]

#: The most jobs one batch is cut into (a target that would cut more is refused).
MAX_PARTS = 100_000


class TooManyParts(ValueError):
    """A target that cuts a batch into more than :data:`MAX_PARTS` jobs (``parts``,
    ``target_s``, ``total_s``: the batch's typical cost, s)."""

    def __init__(self, parts: int, target_s: float, total_s: float) -> None:
        self.parts, self.target_s, self.total_s = parts, target_s, total_s
        super().__init__(
            f"a target of {target_s:g} s cuts {total_s:.4g} s of runs into {parts:,} jobs, more than "
            f"{MAX_PARTS:,}: raise the target"
        )


@dataclass(frozen=True)
class Part:
    """One job of a cut batch: the runs ``start`` to ``stop - 1`` (indices into the batch) and
    their typical cost ``typical_s`` (s)."""

    start: int
    stop: int
    typical_s: float

    @property
    def runs(self) -> range:
        """The indices of its runs."""
        return range(self.start, self.stop)


def cut(costs: Sequence[float], target_s: float) -> tuple[Part, ...]:
    """Cut runs of typical costs ``costs`` (s, in their order) into consecutive parts of about
    ``target_s`` each (the rule in the module docstring).

    Parameters
    ----------
    costs : sequence of float
        The typical cost of each run, s (finite, >= 0); at least one.
    target_s : float
        The typical cost of a part, s (finite, > 0).

    Returns
    -------
    tuple of Part
        Consecutive, non-empty, covering every run once, in order.

    Raises
    ------
    ValueError
        No cost, a cost negative or not finite, or a target not finite and positive.
    TooManyParts
        The cut would make more than :data:`MAX_PARTS` parts.
    """
    if isinstance(target_s, bool) or not isinstance(target_s, (int, float)) or not (0 < target_s < math.inf):
        raise ValueError(f"target_s: must be a finite number > 0 s, got {target_s!r}")
    costs = [float(c) for c in costs]
    if not costs:
        raise ValueError("costs: no run to cut")
    if any(not (0.0 <= c < math.inf) for c in costs):
        bad = next(c for c in costs if not (0.0 <= c < math.inf))
        raise ValueError(f"costs: a run's cost must be finite and >= 0 s, got {bad!r}")
    total = math.fsum(costs)
    count = min(len(costs), max(1, math.ceil(total / target_s)))
    if count > MAX_PARTS:
        raise TooManyParts(count, float(target_s), total)
    width = total / count if total > 0 else 1.0
    windows, before = [], 0.0
    for c in costs:
        windows.append(min(count - 1, int((before + 0.5 * c) / width)))
        before += c
    parts, start = [], 0
    for index in range(1, len(costs) + 1):
        if index == len(costs) or windows[index] != windows[start]:
            parts.append(Part(start, index, math.fsum(costs[start:index])))
            start = index
    return tuple(parts)


@dataclass(frozen=True)
class RunsPart:
    """One job of a cut batch of named runs: their names (in order), their typical cost (s) and
    the job's resources (their upper-side costs summed, :func:`rodimpact.jobs.resources.job_resources`)."""

    names: tuple[str, ...]
    typical_s: float
    resources: JobResources


def cut_runs(costs: Mapping[str, Sequence[Cost]], target_s: float) -> tuple[RunsPart, ...]:
    """:func:`cut` of named runs by their typical costs, each part with its job's resources.

    Parameters
    ----------
    costs : mapping of str to sequence of Cost
        Run name (in the batch's order) -> what its job computes for it: its solve, and what else
        (the curve of its law, when the batch computes it); at least one run.
    target_s : float
        The typical cost of a part, s.

    Raises
    ------
    ValueError, TooManyParts
        As :func:`cut`; a run with no cost.
    """
    names = list(costs)
    if any(not costs[name] for name in names):
        raise ValueError(f"costs: run {next(n for n in names if not costs[n])!r} has no cost")
    parts = cut([math.fsum(c.typical_s for c in costs[name]) for name in names], target_s)
    return tuple(
        RunsPart(
            tuple(names[p.start : p.stop]),
            p.typical_s,
            job_resources([(c, 1.0) for name in names[p.start : p.stop] for c in costs[name]]),
        )
        for p in parts
    )
