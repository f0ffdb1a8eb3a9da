"""Strain gauges on the rod: where they sit and over what length they average.

A gauge of length g centred at x (m from the struck end) reads the mean axial strain over
x - g/2 <= s <= x + g/2, which is exactly

    (u(x + g/2) - u(x - g/2)) / g,

u the axial displacement; a point gauge (g = 0) reads du/dx at x. Each method computes it
from its own solution (:mod:`rodimpact.solvers`): the gauge here is only the geometry, checked
against the rod's length.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["Gauge", "GaugeError"]


class GaugeError(ValueError):
    """A gauge that does not fit on the rod.

    Attributes
    ----------
    field : str
        The gauge's setting at fault: ``station_m`` or ``gauge_length_m``.
    reason : str
        What is wrong, without the setting's name.
    """

    def __init__(self, field: str, reason: str) -> None:
        self.field, self.reason = field, reason
        super().__init__(f"{field} {reason}")

    def __reduce__(self):
        return GaugeError, (self.field, self.reason)


@dataclass(frozen=True)
class Gauge:
    """A strain gauge on the rod.

    Attributes
    ----------
    station_m : float
        Distance of the gauge's centre from the struck end, m.
    gauge_length_m : float
        Length over which the strain is averaged, m; 0 (default) is a point.
    """

    station_m: float
    gauge_length_m: float = 0.0

    @classmethod
    def from_settings(cls, settings: Mapping[str, Any]) -> Gauge:
        """The gauge of a mapping ``{station_m, gauge_length_m}`` (the length optional; other
        keys, e.g. a measured record's file, are not the gauge's and are ignored).

        Raises
        ------
        GaugeError
            ``station_m`` is missing, or a setting is not a number (its name in ``field``).
        """
        if "station_m" not in settings:
            raise GaugeError("station_m", "is required")
        values = {}
        for name in ("station_m", "gauge_length_m"):
            if name in settings:
                value = settings[name]
                if isinstance(value, bool) or not isinstance(value, (int, float)):
                    raise GaugeError(name, f"must be a number, got {value!r}")
                values[name] = float(value)
        return cls(**values)

    def as_settings(self) -> dict[str, float]:
        """The mapping :meth:`from_settings` reads back, m."""
        return {"station_m": float(self.station_m), "gauge_length_m": float(self.gauge_length_m)}

    def ends(self) -> tuple[float, float]:
        """The gauge's two ends (x - g/2, x + g/2), m from the struck end."""
        half = 0.5 * self.gauge_length_m
        return self.station_m - half, self.station_m + half

    def check(self, rod_length_m: float) -> Gauge:
        """The gauge itself when it lies on a rod of length ``rod_length_m`` (m, may be inf).

        Raises
        ------
        GaugeError
            ``station_m``: not finite, or outside [0, L]; ``gauge_length_m``: not finite,
            negative, longer than the rod, or overhanging an end (x - g/2 < 0 or x + g/2 > L).
        """
        x, g, length = self.station_m, self.gauge_length_m, rod_length_m
        if not (math.isfinite(x) and 0.0 <= x <= length):
            raise GaugeError("station_m", f"={x!r} m lies outside the rod [0, {length:g}] m")
        if not (math.isfinite(g) and g >= 0.0):
            raise GaugeError("gauge_length_m", f"={g!r} m must be >= 0")
        if g > length:
            raise GaugeError("gauge_length_m", f"={g:g} m is longer than the rod ({length:g} m)")
        low, high = self.ends()
        if low < 0.0 or high > length:
            raise GaugeError(
                "gauge_length_m",
                f"={g:g} m overhangs an end of the rod: the gauge spans [{low:g}, {high:g}] m, "
                f"the rod [0, {length:g}] m",
            )
        return self
