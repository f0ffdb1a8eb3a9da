"""A computed wave signal against a measured one: the strain at a gauge, or a velocity.

A gauge on the rod at x from the struck end sees nothing until the contact's wave arrives, at
x/c after the impact (c = sqrt(E/rho), the rod's bar speed), then a first pulse whose shape is
the contact force's, delayed: before the first reflection reaches the gauge, the 1-D rod's
strain there is -P(t - x/c)/(E A). Three numbers of that first pulse check three things:

* its **arrival**, where |value| first rises through half of the signal's largest crest
  (:data:`ARRIVAL_FRACTION`, on the least-squares parabola through the samples around the
  first one above it): against x/c, a check of the wave speed and of the station's position.
  It is read on the record's own clock, so the record's time zero must be the impact
  (``time_offset_s`` puts it there); the model's arrival differs from x/c by the time its force
  takes to rise to half its peak. The pulse itself starts where |value| first rises through
  ``threshold`` of the largest crest;
* its **peak**, the extreme value between the pulse's start and its end (where |value| next
  falls below the threshold), signed: the vertex of the least-squares parabola through the
  samples within :data:`PEAK_BAND` of the largest one (the sample's own value where fewer than
  three lie there). A record's largest sample is biased by its noise (the largest of several
  noisy samples overshoots); the parabola averages the noise over the pulse's crest, and the
  model is read the same way, so the parabola's own error on a smooth crest (a few 1e-4 of the
  peak on a half-sine) is the same in both;
* its **integral** from its start to its end, trapezoidal with the crossings as end points: for
  the strain, -(1/(E A)) times the impulse the pulse carries (a check of the momentum
  transferred); for the far end's velocity, the displacement the pulse gives the end.

Each is read the same way from the record and from the model, the model on its own time
points (far denser than a record's samples, so that what is read from it moves smoothly with
the model's constants, as a calibration's finite differences need). The crossing and the crest
are read from least-squares parabolas, not from single samples, so that a record's sampling
and noise bias neither (the largest of noisy samples overshoots; the sample below a noisy
crossing is selected for being low). The whole signals are then compared as force histories are
(:mod:`.history_compare`): aligned where their first pulses arrive (or, for ``align=False``,
on their own clocks, as the impactor's velocity is, which has no pulse to align on), the
record interpolated onto the computed time points inside it, and the L2 and max-norm errors
taken relative to the record. The model's signal is read over the record's span only: a
reflection the record did not see does not set the model's threshold.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact.analysis.history_compare import aligned_errors
from rodimpact.analysis.history_compare import crossing as _crossing

__all__ = [
    "ARRIVAL_FRACTION",
    "ARRIVAL_SAMPLES",
    "MIN_NOISE_SAMPLES",
    "PEAK_BAND",
    "FirstPulse",
    "SignalComparison",
    "compare_signals",
    "first_pulse",
]

#: The crest of a pulse whose samples fit the parabola of its peak: within this fraction of the
#: largest sample. On a half-sine that is the middle 29 % of the pulse; 1 % noise on a record
#: sampled 100 times over a pulse then leaves about 0.2 % in the peak, not the +1.5 % to +2 %
#: the largest sample gives.
PEAK_BAND = 0.10
#: Where a pulse's arrival is read: at this fraction of its largest crest (its half maximum,
#: the usual time mark of a pulse: the rise is steepest there against the noise, and least
#: curved, so that its crossing is read without bias and its uncertainty is what noise/slope
#: says; at a few % of the crest, where a pulse leaves the noise, both fail by factors of 2-3).
ARRIVAL_FRACTION = 0.5
#: The samples either side of the first one above the threshold through which the rise's
#: parabola is fitted (9 in all: 4 µs of a record sampled every 0.5 µs).
ARRIVAL_SAMPLES = 4
#: The fewest samples before the arrival from which a record's noise is estimated.
MIN_NOISE_SAMPLES = 8


@dataclass(frozen=True)
class FirstPulse:
    """The first pulse of a signal (see the module docstring).

    Attributes
    ----------
    arrival_s : float
        Where |value| first rises through half the largest crest, s.
    end_s : float
        Where |value| next falls through the threshold after the pulse's start (its first rise
        through the threshold), s.
    peak : float
        The extreme value between the start and the end, signed, in the signal's unit.
    integral : float
        The value's trapezoidal integral between them, signal's unit times s.
    sign : int
        +1 or -1: the sign of the pulse.
    noise : float
        The standard deviation of the samples before the arrival (their first 80 %), in the
        signal's unit; NaN with fewer than :data:`MIN_NOISE_SAMPLES` of them.
    arrival_sd_s, peak_sd, integral_sd : float
        The standard uncertainties that noise gives the arrival, the peak and the integral
        (linearised: the crossing's two samples, the crest parabola's vertex, the trapezoid's
        weights), in their units; NaN without a noise estimate, 0 for a signal without noise.
    """

    arrival_s: float
    end_s: float
    peak: float
    integral: float
    sign: int
    noise: float = float("nan")
    arrival_sd_s: float = float("nan")
    peak_sd: float = float("nan")
    integral_sd: float = float("nan")


@dataclass(frozen=True)
class SignalComparison:
    """A computed signal against a measured one.

    Attributes
    ----------
    threshold : float
        Fraction of each signal's largest |value| at which a pulse starts and ends.
    measured_pulse, model_pulse : FirstPulse or None
        The first pulses (None for a comparison made with ``pulses=False``).
    shift_s : float
        Added to the measured times to align the records, s (0 without alignment).
    l2_error, max_error : float
        Relative errors of the computed signal (L2, max norm), 1.
    time_s : ndarray, shape (n,)
        The computed time points inside the (shifted) record, s.
    measured, model : ndarray, shape (n,)
        The record interpolated there, and the computed signal.
    """

    threshold: float
    measured_pulse: FirstPulse | None
    model_pulse: FirstPulse | None
    shift_s: float
    l2_error: float
    max_error: float
    time_s: NDArray[np.float64]
    measured: NDArray[np.float64]
    model: NDArray[np.float64]


def _crest(t: NDArray[np.float64], g: NDArray[np.float64], noise: float, top: int | None = None) -> tuple[float, float]:
    """The peak of a positive pulse's samples and its standard uncertainty for samples of noise
    ``noise``: the vertex of the least-squares parabola through the contiguous samples within
    :data:`PEAK_BAND` of the largest (module docstring; or of sample ``top``), or that sample itself."""
    top = int(np.argmax(g)) if top is None else top
    level = (1.0 - PEAK_BAND) * g[top]
    low = top
    while low > 0 and g[low - 1] >= level:
        low -= 1
    high = top
    while high < len(g) - 1 and g[high + 1] >= level:
        high += 1
    if high - low < 3:
        return float(g[top]), noise
    x = t[low : high + 1] - t[top]
    (a, b, c), unscaled = np.polyfit(x, g[low : high + 1], 2, cov="unscaled")
    vertex = -b / (2.0 * a) if a < 0.0 else math.nan
    if not x[0] <= vertex <= x[-1]:  # not a crest, or its top lies outside its samples
        return float(g[top]), noise
    gradient = np.array([b * b / (4.0 * a * a), -b / (2.0 * a), 1.0])
    return float(c - b * b / (4.0 * a)), noise * float(np.sqrt(gradient @ unscaled @ gradient))


def _rise(
    t: NDArray[np.float64], g: NDArray[np.float64], start: int, level: float, noise: float
) -> tuple[float, float]:
    """Where a positive pulse first rises through ``level``, and its standard uncertainty for
    samples of noise ``noise``: the crossing of the least-squares parabola through the
    :data:`ARRIVAL_SAMPLES` samples either side of the first sample at or above it (the two
    samples around a noisy crossing alone are biased: the one below is selected for being
    low); the linear crossing of those two where the parabola does not cross there."""
    low, high = max(start - ARRIVAL_SAMPLES, 0), min(start + ARRIVAL_SAMPLES, len(g) - 1)
    linear = _crossing(t, g, start - 1, level)
    if high - low >= 3:
        x = t[low : high + 1] - t[start]
        (a, b, c), unscaled = np.polyfit(x, g[low : high + 1], 2, cov="unscaled")
        roots = np.roots([a, b, c - level])
        slope = 2.0 * a * roots + b
        inside = [
            (float(r.real), float(d.real))
            for r, d in zip(roots, slope, strict=True)
            if abs(r.imag) < 1e-30 and x[0] <= r.real <= x[-1] and d.real > 0.0
        ]
        if len(inside) == 1:
            root, rising = inside[0]
            gradient = np.array([root * root, root, 1.0]) / rising
            return float(t[start] + root), noise * float(np.sqrt(gradient @ unscaled @ gradient))
    step, rise = t[start] - t[start - 1], g[start] - g[start - 1]
    share = (level - g[start - 1]) / rise  # where the crossing lies between its two samples
    return linear, noise * step / rise * math.hypot(1.0 - share, share)


def _noise(t: NDArray[np.float64], f: NDArray[np.float64], arrival: float) -> float:
    """The standard deviation of the samples in the first 80 % of the time before the arrival."""
    quiet = f[t <= t[0] + 0.8 * (arrival - t[0])]
    return float(np.std(quiet, ddof=1)) if len(quiet) >= MIN_NOISE_SAMPLES else math.nan


def first_pulse(time_s: ArrayLike, values: ArrayLike, threshold: float) -> FirstPulse:
    """The first pulse of a signal, bounded at ``threshold`` of its largest crest, its arrival
    at half of it.

    Parameters
    ----------
    time_s, values : array_like, shape (n,)
        Increasing times, s, and the signal.
    threshold : float
        In (0, 1).

    Raises
    ------
    ValueError
        ``threshold`` is not in (0, 1), the signal is zero throughout, or it starts above the
        threshold (no arrival to read).
    """
    if not 0.0 < threshold < 1.0:
        raise ValueError(f"threshold: must lie in (0, 1), got {threshold!r}")
    t, f = np.asarray(time_s, float), np.asarray(values, float)
    if not len(f) or float(np.max(np.abs(f))) <= 0.0:
        raise ValueError("the signal is zero throughout: no pulse to read")
    # the threshold is a fraction of the largest crest, read as the peak is (its largest
    # sample, biased by the noise, would raise the level and delay the arrival)
    top = int(np.argmax(np.abs(f)))
    largest, _ = _crest(t, np.sign(f[top]) * f, 0.0, top)
    level, mark = threshold * largest, max(ARRIVAL_FRACTION, threshold) * largest
    # the pulse is the run of samples above the threshold that holds the first one above half
    # the crest: a noise spike through the threshold before it starts no pulse
    first = int(np.argmax(np.abs(f) >= mark))
    sign = 1 if f[first] > 0 else -1
    g = sign * f  # the pulse made positive
    start = first
    while start > 0 and g[start - 1] >= level:
        start -= 1
    if start == 0:
        raise ValueError(f"the signal starts above {threshold:g} of its largest crest: no arrival to read")
    begin = _crossing(t, g, start - 1, level)  # the pulse's start
    noise = _noise(t, f, begin)
    # the arrival is read at half the crest, where the rise is steepest against the noise
    arrival, arrival_sd = _rise(t, g, first, mark, noise)
    stop = first
    while stop < len(g) and g[stop] >= level:
        stop += 1  # the first sample after the pulse
    inside_t, inside_g = t[start:stop], g[start:stop]
    if stop < len(g):
        end = _crossing(t, g, stop - 1, level)
        inside_t, inside_g = np.append(inside_t, end), np.append(inside_g, level)
    else:
        end = float(t[-1])
    peak, peak_sd = _crest(t[start:stop], g[start:stop], noise)
    inside_t, inside_g = np.insert(inside_t, 0, begin), np.insert(inside_g, 0, level)
    weights = 0.5 * (inside_t[2:] - inside_t[:-2])  # the trapezoid's weight of each inner sample
    return FirstPulse(
        arrival_s=arrival,
        end_s=end,
        peak=sign * peak,
        integral=sign * float(np.trapezoid(inside_g, inside_t)),
        sign=sign,
        noise=noise,
        arrival_sd_s=arrival_sd,
        peak_sd=peak_sd,
        integral_sd=noise * float(np.sqrt(np.sum(weights**2))),
    )


def compare_signals(
    measured_time_s: ArrayLike,
    measured: ArrayLike,
    model_time_s: ArrayLike,
    model: ArrayLike,
    threshold: float,
    *,
    pulses: bool = True,
) -> SignalComparison:
    """Compare a computed signal with a measured one (see the module docstring).

    Parameters
    ----------
    measured_time_s, measured : array_like, shape (m,)
        The record: increasing times (time zero at the impact), s, and its values.
    model_time_s, model : array_like, shape (n,)
        The computed signal on its own time points, s (time zero at the impact).
    threshold : float
        Fraction of each signal's largest |value| at which a pulse starts and ends.
    pulses : bool
        Read the first pulses and align the records on their arrivals (a wave signal); False
        compares on the records' own clocks (the impactor's velocity).

    Raises
    ------
    ValueError
        A signal has no pulse to read, or the records do not overlap.
    """
    tm, fm = np.asarray(measured_time_s, float), np.asarray(measured, float)
    tc, fc = np.asarray(model_time_s, float), np.asarray(model, float)
    window = (tc >= tm[0]) & (tc <= tm[-1])
    measured_pulse = model_pulse = None
    shift = 0.0
    if pulses:
        if window.sum() < 2:
            raise ValueError("the computed signal does not reach into the record's span")
        measured_pulse = first_pulse(tm, fm, threshold)
        model_pulse = first_pulse(tc[window], fc[window], threshold)
        shift = model_pulse.arrival_s - measured_pulse.arrival_s
    t, record, computed, l2_error, max_error = aligned_errors(tm, fm, tc, fc, shift)
    return SignalComparison(
        threshold=threshold,
        measured_pulse=measured_pulse,
        model_pulse=model_pulse,
        shift_s=shift,
        l2_error=l2_error,
        max_error=max_error,
        time_s=t,
        measured=record,
        model=computed,
    )
