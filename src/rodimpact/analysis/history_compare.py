"""A computed contact force against a measured one: alignment, error norms, contact times.

A measured record starts at an arbitrary time (the trigger's), and its first micro-seconds are
lost in noise, so its start of contact cannot be read where the force leaves zero. Both
histories are therefore aligned where they first rise through the same fraction ``threshold``
of their own peak (:func:`threshold_crossings`, linear between samples): the measured time is
shifted so that its crossing falls on the computed one's. A fraction of each one's own peak
makes the alignment independent of the sensor's gain: a record equal to a run, shifted by
tau and scaled by s, is aligned exactly (shift -tau) and its errors are |1 - s| / s.

After alignment, the measured force is interpolated linearly onto the computed time points
within both records, and the errors are relative to the measured history: the L2 error
sqrt(int (P - P_m)^2 dt / int P_m^2 dt) (trapezoidal) and the max-norm error
max |P - P_m| / max |P_m|. The contact time read from a signal is the time between its first
rise through and its last fall through ``threshold`` of its peak: what an experimenter reads
from a trace, computed the same way for the model so the two compare like with like.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "DEFAULT_THRESHOLD",
    "HistoryComparison",
    "aligned_errors",
    "compare_force_histories",
    "crossing",
    "threshold_crossings",
]

#: The fraction of a signal's peak at which its contact starts and ends, by default: above a
#: few per cent of noise on a piezo or gauge trace, low enough to lose little of the contact.
DEFAULT_THRESHOLD = 0.05


@dataclass(frozen=True)
class HistoryComparison:
    """A computed force history against a measured one (see the module docstring).

    Attributes
    ----------
    threshold : float
        Fraction of each peak at which contact starts and ends.
    shift_s : float
        Added to the measured times to align the records, s.
    l2_error, max_error : float
        Relative errors of the computed force (L2, max norm), 1.
    measured_contact_time_s, model_contact_time_s : float
        Contact times read at ``threshold`` from each signal, s.
    measured_peak_N, model_peak_N : float
        Peaks, N.
    time_s : ndarray, shape (n,)
        The computed time points where both records overlap, s.
    measured_N, model_N : ndarray, shape (n,)
        The aligned measured force and the computed one there, N.
    """

    threshold: float
    shift_s: float
    l2_error: float
    max_error: float
    measured_contact_time_s: float
    model_contact_time_s: float
    measured_peak_N: float
    model_peak_N: float
    time_s: NDArray[np.float64]
    measured_N: NDArray[np.float64]
    model_N: NDArray[np.float64]


def crossing(t: NDArray[np.float64], f: NDArray[np.float64], i: int, level: float) -> float:
    """Where f crosses ``level`` between samples i and i + 1 (linear), in the unit of ``t``."""
    return float(t[i] + (level - f[i]) * (t[i + 1] - t[i]) / (f[i + 1] - f[i]))


def threshold_crossings(time_s: ArrayLike, force_N: ArrayLike, threshold: float) -> tuple[float, float]:
    """The first rise through and the last fall through ``threshold`` times the peak, s.

    Raises
    ------
    ValueError
        ``threshold`` is not in (0, 1), or the signal never rises through it (no positive peak,
        or it starts or ends above it).
    """
    if not 0.0 < threshold < 1.0:
        raise ValueError(f"threshold: must lie in (0, 1), got {threshold!r}")
    t, f = np.asarray(time_s, float), np.asarray(force_N, float)
    peak = float(f.max()) if len(f) else 0.0
    if peak <= 0.0:
        raise ValueError("force: no positive force to read a contact from")
    level = threshold * peak
    above = f >= level
    rises = np.flatnonzero(~above[:-1] & above[1:])
    falls = np.flatnonzero(above[:-1] & ~above[1:])
    if not len(rises) or not len(falls) or falls[-1] < rises[0]:
        raise ValueError(
            f"force: the signal must start and end below {threshold:g} of its peak "
            f"({level:.4g} N) to read a contact from it"
        )
    return crossing(t, f, int(rises[0]), level), crossing(t, f, int(falls[-1]), level)


def aligned_errors(
    measured_time_s: NDArray[np.float64],
    measured: NDArray[np.float64],
    model_time_s: NDArray[np.float64],
    model: NDArray[np.float64],
    shift_s: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float, float]:
    """A record shifted by ``shift_s`` against a computed signal (module docstring): the computed
    time points inside the shifted record, the record interpolated there, the computed values,
    and the relative L2 and max-norm errors of the computed signal (L2: NaN for a record that is
    zero there).

    Raises
    ------
    ValueError
        The shifted record and the computed signal overlap in fewer than two time points.
    """
    aligned = measured_time_s + shift_s
    inside = (model_time_s >= aligned[0]) & (model_time_s <= aligned[-1])
    if inside.sum() < 2:
        raise ValueError("the aligned records do not overlap")
    t, computed = model_time_s[inside], model[inside]
    record = np.interp(t, aligned, measured)
    difference = computed - record
    norm = float(np.sqrt(np.trapezoid(record**2, t)))
    l2_error = float(np.sqrt(np.trapezoid(difference**2, t))) / norm if norm > 0 else float("nan")
    return t, record, computed, l2_error, float(np.max(np.abs(difference))) / float(np.max(np.abs(measured)))


def compare_force_histories(
    measured_time_s: ArrayLike,
    measured_N: ArrayLike,
    model_time_s: ArrayLike,
    model_N: ArrayLike,
    threshold: float = DEFAULT_THRESHOLD,
) -> HistoryComparison:
    """Align a measured force history on a computed one and measure their difference.

    Parameters
    ----------
    measured_time_s, measured_N : array_like, shape (m,)
        The measured record (increasing times, s; force, N).
    model_time_s, model_N : array_like, shape (n,)
        The computed contact force (increasing times, s; force, N).
    threshold : float
        Fraction of each peak where contact starts and ends (default :data:`DEFAULT_THRESHOLD`).

    Returns
    -------
    HistoryComparison

    Raises
    ------
    ValueError
        Either signal has no contact to read at ``threshold``, or the aligned records do not
        overlap.
    """
    tm, fm = np.asarray(measured_time_s, float), np.asarray(measured_N, float)
    tc, fc = np.asarray(model_time_s, float), np.asarray(model_N, float)
    m_start, m_end = threshold_crossings(tm, fm, threshold)
    c_start, c_end = threshold_crossings(tc, fc, threshold)
    shift = c_start - m_start
    t, measured, model, l2_error, max_error = aligned_errors(tm, fm, tc, fc, shift)
    return HistoryComparison(
        threshold=threshold,
        shift_s=shift,
        l2_error=l2_error,
        max_error=max_error,
        measured_contact_time_s=m_end - m_start,
        model_contact_time_s=c_end - c_start,
        measured_peak_N=float(fm.max()),
        model_peak_N=float(fc.max()),
        time_s=t,
        measured_N=measured,
        model_N=model,
    )
