"""How a timed run is repeated (the work-precision study times its solves)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Timing"]


@dataclass(frozen=True)
class Timing:
    """How a run is timed: repeated until ``min_repeats`` runs and ``min_total_s`` seconds,
    but no more once ``max_total_s`` seconds are spent (a long run is timed once)."""

    min_repeats: int = 1
    min_total_s: float = 0.0
    max_total_s: float = 0.0

    def __post_init__(self) -> None:
        if int(self.min_repeats) != self.min_repeats or self.min_repeats < 1:
            raise ValueError(f"min_repeats must be an integer >= 1, got {self.min_repeats!r}")
        if not (self.min_total_s >= 0 and self.max_total_s >= 0):
            raise ValueError(
                f"min_total_s and max_total_s must be >= 0, got {self.min_total_s!r}, {self.max_total_s!r}"
            )
