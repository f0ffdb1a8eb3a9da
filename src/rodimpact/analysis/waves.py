"""Waves in the rod: the paths of the wave fronts (characteristics) over a space-time map.

A disturbance that leaves the struck end (x = 0) at t0 travels at the bar wave speed a,
x = a (t - t0), to the far end (x = l), is reflected there (with its sign kept at a fixed
end and reversed at a free one) and travels back, x = l - a (t - t0 - l / a), to the struck
end, where it is reflected again: the path is the same zig-zag for either end condition.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["characteristic"]


def characteristic(
    t0: float, length_m: float, wave_speed_m_s: float, t_end: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The path of the wave front that leaves the struck end at ``t0``, reflected at both ends.

    Parameters
    ----------
    t0 : float
        Time the front leaves the struck end, s.
    length_m : float
        Length of the rod l, m (finite, > 0).
    wave_speed_m_s : float
        Bar wave speed a, m/s (> 0).
    t_end : float
        Last time of the path, s.

    Returns
    -------
    t, x : ndarray, shape (p,)
        The path's vertices (s, m from the struck end): t0 and every arrival at an end up to
        ``t_end``, then its point at ``t_end``; empty when ``t_end <= t0``.
    """
    if not (math.isfinite(length_m) and length_m > 0 and wave_speed_m_s > 0):
        raise ValueError(
            f"a characteristic needs a finite length and a positive wave speed, got "
            f"l = {length_m!r} m, a = {wave_speed_m_s!r} m/s"
        )
    if t_end <= t0:
        return np.empty(0), np.empty(0)
    transit = length_m / wave_speed_m_s
    count = math.floor((t_end - t0) / transit)
    t = t0 + transit * np.arange(count + 1, dtype=float)
    x = np.where(np.arange(count + 1) % 2 == 0, 0.0, length_m)
    if t[-1] < t_end:
        rest = (t_end - t[-1]) * wave_speed_m_s
        t = np.append(t, t_end)
        x = np.append(x, rest if count % 2 == 0 else length_m - rest)
    return t, x
