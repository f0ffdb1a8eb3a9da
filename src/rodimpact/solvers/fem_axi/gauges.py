"""Where ``fem_axi`` reads its stations' and gauges' strain, and how far its continuum must reach.

The strain at a station, and at a point gauge, is a difference of axial displacements
between the sections :data:`STATION_HALF_SPAN` L either side of it, over their distance (a
section beyond the rod's end is taken at the end, and the difference at an end is one-sided,
over its own, halved, span); a gauge of length g reads the difference between its two ends,
over g (:func:`gauge_spans`). A gauge reads the axial displacement at the rod's surface
r = a, as a real gauge bonded there does; the mean over the cross-section is stored next to
it. Its reading means something only where the rod is a continuum: with gauges, the continuum
reaches :data:`GAUGE_COVER_DIAMETERS` rod diameters beyond the last gauge's far end
(:func:`continuum_cover_m`, :func:`~.farbar.continuum_length`).

This module imports numpy only: the cost model reads it.
"""

from __future__ import annotations

from collections.abc import Sequence

from rodimpact.model.gauges import Gauge

__all__ = ["GAUGE_COVER_DIAMETERS", "STATION_HALF_SPAN", "continuum_cover_m", "gauge_spans", "station_span"]

#: Half the span of a station's (and a point gauge's) strain, as a fraction of the rod's
#: length: the strain is the difference of the axial displacement between the sections this
#: far either side of the station, over their distance (a section beyond the rod's end is
#: taken at the end, and the difference at an end is one-sided, over half the span).
STATION_HALF_SPAN = 1e-4
#: With gauges, the continuum reaches this many rod diameters beyond the last gauge's far end.
GAUGE_COVER_DIAMETERS = 1.0


def station_span(x_m: float, length_m: float) -> tuple[float, float]:
    """The sections (z1, z2), m, whose displacements give the strain at ``x_m`` on a rod of
    ``length_m``: x -/+ :data:`STATION_HALF_SPAN` L, clipped to the rod."""
    delta = STATION_HALF_SPAN * length_m
    return max(x_m - delta, 0.0), min(x_m + delta, length_m)


def gauge_spans(gauges: Sequence[Gauge], length_m: float) -> list[tuple[float, float]]:
    """The sections (z1, z2), m, each gauge's strain is the displacement difference of, over
    z2 - z1: its ends (g > 0), or a station's span (a point gauge, :func:`station_span`)."""
    return [gauge.ends() if gauge.gauge_length_m > 0.0 else station_span(gauge.station_m, length_m) for gauge in gauges]


def continuum_cover_m(gauges: Sequence[Gauge], radius_m: float, length_m: float) -> float:
    """How far from the struck end the continuum must reach for ``gauges``, m:
    :data:`GAUGE_COVER_DIAMETERS` diameters 2a beyond the furthest section a gauge reads;
    0 without gauges."""
    if not gauges:
        return 0.0
    return max(high for _, high in gauge_spans(gauges, length_m)) + GAUGE_COVER_DIAMETERS * 2.0 * radius_m
