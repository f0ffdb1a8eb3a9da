"""Features of a sampled force history: its maxima, and the step-to-step zig-zag of an
unstable explicit step. Pure functions of arrays; the solvers and the studies use them."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "ZIGZAG_UNSTABLE",
    "first_contact_maxima",
    "local_maxima",
    "peak_prominences",
    "sawtooth_amplitude",
    "zigzag_steps",
]

#: A force alternating up and down at every step over this many steps (:func:`zigzag_steps`)
#: marks an unstable step.
ZIGZAG_UNSTABLE = 10


def first_contact_maxima(peak_time_s: Any, peak_force_N: Any, contact_end_s: Any) -> NDArray[np.float64]:
    """The force maxima (N) that fall within the first contact (all of them if none ended)."""
    times, peaks = np.atleast_1d(peak_time_s), np.atleast_1d(peak_force_N)
    ends = np.atleast_1d(contact_end_s)
    return peaks[times <= ends[0]] if len(ends) else peaks


def sawtooth_amplitude(force: Any) -> float:
    """Largest step-to-step zig-zag of a force history, relative to its largest value.

    max |P_{n+1} - 2 P_n + P_{n-1}| / (4 max P): about h^2 |P''| / (4 max P) on a smooth
    history, close to 1 when the force alternates between zero and its peak.
    """
    p = np.asarray(force, dtype=float)
    if len(p) < 3 or not np.max(p) > 0:
        return 0.0
    return float(np.max(np.abs(p[2:] - 2.0 * p[1:-1] + p[:-2])) / (4.0 * np.max(p)))


def zigzag_steps(force: Any, threshold: float = 0.05) -> int:
    """Longest run of steps over which the force alternates up, down, up, ...

    Counts consecutive increments dP_n that change sign at every step while each exceeds
    ``threshold`` times the largest force. An explicit scheme's instability (a root of its
    step below -1) makes such a run as long as the contact; a smooth but under-resolved
    force (a few steps per rise) does not alternate at every step.
    """
    p = np.asarray(force, dtype=float)
    if len(p) < 3 or not np.max(p) > 0:
        return 0
    d = np.diff(p)
    big = np.abs(d) > threshold * np.max(p)
    alternating = big[1:] & big[:-1] & (np.sign(d[1:]) == -np.sign(d[:-1]))
    if not alternating.any():
        return 0
    # longest run of True: the distance between the falses around it
    edges = np.flatnonzero(np.diff(np.concatenate([[0], alternating.astype(np.int8), [0]])))
    return int(np.max(edges[1::2] - edges[::2]) + 1)


def peak_prominences(values: NDArray[np.float64], peaks: NDArray[np.intp]) -> NDArray[np.float64]:
    """How far each peak rises above the higher of its two bases (topographic prominence).

    A base is the lowest sample between the peak and the nearest sample higher than it on
    that side (or the signal's end): the definition of :func:`scipy.signal.peak_prominences`
    without a window, to the same values, without loading :mod:`scipy.signal` (half a second
    of every job that reads a force's maxima).

    Parameters
    ----------
    values : ndarray, shape (n,)
        The sampled signal.
    peaks : ndarray of int, shape (k,)
        Indices of its peaks.

    Returns
    -------
    ndarray, shape (k,)
        The prominences, in the unit of ``values``.
    """
    x = np.asarray(values, dtype=float)
    out = np.empty(len(peaks))
    for j, k in enumerate(peaks):
        higher_left = np.flatnonzero(x[:k] > x[k])
        higher_right = np.flatnonzero(x[k + 1 :] > x[k])
        start = higher_left[-1] + 1 if len(higher_left) else 0
        stop = k + 1 + higher_right[0] if len(higher_right) else len(x)
        out[j] = x[k] - max(x[start : k + 1].min(), x[k:stop].min())
    return out


def local_maxima(
    time: NDArray[np.float64], force: NDArray[np.float64], min_prominence: float = 0.0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Every strict local maximum of a sampled force, refined by a parabola.

    Parameters
    ----------
    time, force : ndarray, shape (n,)
        Nodes (increasing times, s) and force values, N.
    min_prominence : float
        Keep only maxima that rise at least this much (N) above the higher of the two
        minima that separate them from higher ground (:func:`peak_prominences`); 0
        keeps every maximum.

    Returns
    -------
    peak_time_s, peak_force_N : ndarray, shape (k,)
        The vertex of the parabola through each interior maximum and its two neighbours
        (the node itself where the parabola is degenerate).
    """
    t = np.asarray(time, dtype=float)
    p = np.asarray(force, dtype=float)
    if len(p) < 3:
        return np.empty(0), np.empty(0)
    i = np.flatnonzero((p[1:-1] > p[:-2]) & (p[1:-1] >= p[2:]) & (p[1:-1] > 0)) + 1
    if min_prominence > 0 and len(i):
        i = i[peak_prominences(p, i) >= min_prominence]
    times, values = [], []
    for k in i:
        t0, t1, t2 = t[k - 1], t[k], t[k + 1]
        p0, p1, p2 = p[k - 1], p[k], p[k + 1]
        # Newton form of the interpolating parabola through the three nodes
        d01 = (p1 - p0) / (t1 - t0)
        d12 = (p2 - p1) / (t2 - t1)
        curv = (d12 - d01) / (t2 - t0)
        if curv < 0:
            tv = 0.5 * (t0 + t1) - d01 / (2.0 * curv)
            tv = min(max(tv, t0), t2)
            pv = p0 + d01 * (tv - t0) + curv * (tv - t0) * (tv - t1)
        else:
            tv, pv = t1, p1
        times.append(tv)
        values.append(max(pv, p1))
    return np.asarray(times), np.asarray(values)
