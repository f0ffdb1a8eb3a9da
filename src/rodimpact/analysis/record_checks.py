"""What a measured record can show of the impact it measures, checked before any job.

A record that reads well as a file (:func:`.measured.read_history`) can still be wrong for its
case in ways that no later step would notice: a record of noise alone, a gauge wired with the
opposite sign, a header whose unit is off by a thousand, a trigger that missed the start. Each
is refused here, from the record and the case alone, with one
:class:`~.measured.HistoryError` that names the block's key at fault: ``sign``, ``every``,
``time_offset_s``, the unit (``time_unit``, ``strain_unit``...; or ``file`` when the header
names the unit, since the header is then what to mend) or ``file`` for the record itself.
The checks, in the order they run:

1. **A pulse above the record's noise.** The noise is read from the scatter of the samples'
   second differences (:func:`record_noise`), which a pulse sampled more than a few times over
   its rise barely touches, so it needs no quiet stretch to be found. The largest |value| (for
   the impactor's velocity, the largest change from its first samples) must stand
   :data:`MIN_SIGNAL_TO_NOISE` times above it: the largest of n samples of Gaussian noise
   alone is about 3 (n = 200) to 5 (n = 10^6) times its standard deviation.
2. **The sign of the first pulse** (where |value| first reaches half its largest value): a
   contact force pushes (positive); the impact's first wave compresses the rod (a negative
   strain at a gauge); a free far end moves away from the struck end (positive); the impactor
   approaches the rod before the impact (positive). A record of the other sign names ``sign``.
3. **A pre-trigger**: at least :data:`~.wave_compare.MIN_NOISE_SAMPLES` samples in the first
   80 % of the time before the first pulse starts (where it first rises through the block's
   ``threshold`` of its largest value), which is where the comparison reads the noise and the
   calibration its weights; a force record must also end below its threshold, after the
   contact, or its contact time would be read short.
4. **Size**, against what the impact can give (:class:`ImpactBounds`), by
   :data:`MAGNITUDE_FACTOR`: a contact force against the peak force of the same impact on a
   rigid wall through the case's law (the largest any rod allows: the contact's energy cannot
   exceed the impactor's); a strain against twice that force over EA (a fixed end doubles an
   incident wave); a far end's velocity against twice the impact velocity (a free end moves at
   twice the particle velocity, which the impactor's own velocity bounds while it loads the
   rod); the impactor's velocity against the impact velocity, and its first samples at least
   the impact velocity over the factor. A size that another unit of the same kind would bring
   within the bound blames the unit.
5. **Timing**, on the record's clock, whose zero must be the impact for a wave or the
   impactor's velocity (``time_offset_s`` puts it there): the first pulse at a gauge (or at the
   far end) reaches half its crest no earlier than the dilatational wave reaches the gauge's
   near edge, less the contact's rise on a rigid wall (the fastest it can rise), and no later
   than the bar wave reaches its far edge plus :data:`LATE_FACTOR` times the contact time's
   upper-side estimate (:meth:`~rodimpact.model.problem.ImpactProblem.contact_time_estimate`);
   the impactor's velocity loses half its change within the same times of the impact; a force
   record (which the comparison aligns on itself, so its clock is free) lasts between the
   rigid wall's contact time over :data:`LATE_FACTOR` and that factor times the estimate. A
   time that another time unit would bring inside blames the unit, else ``time_offset_s``.

Nothing here knows the configuration: :mod:`rodimpact.config.measured` builds the bounds from
a resolved case and turns an error into a line naming the file, the case and the field.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.analysis.history_compare import DEFAULT_THRESHOLD
from rodimpact.analysis.measured import RECORDS, TIME_UNITS, HistoryError, MeasuredHistory
from rodimpact.analysis.wave_compare import MIN_NOISE_SAMPLES
from rodimpact.model.problem import ImpactProblem

__all__ = [
    "LATE_FACTOR",
    "MAGNITUDE_FACTOR",
    "MIN_SIGNAL_TO_NOISE",
    "ImpactBounds",
    "check_record",
    "impact_bounds",
    "record_noise",
]

#: A record's largest |value| must be at least this many times its noise (:func:`record_noise`).
MIN_SIGNAL_TO_NOISE = 10.0
#: A record may exceed what the impact can give (module docstring, 4) by at most this factor,
#: room for a sensor's calibration and for a case's constants known only roughly.
MAGNITUDE_FACTOR = 2.0
#: The latest a pulse may arrive, or the longest a contact may last, in contact-time estimates;
#: also the shortest contact, as a fraction of the rigid wall's (module docstring, 5).
LATE_FACTOR = 2.0
#: 1 / Phi^-1(3/4): the median absolute deviation of Gaussian noise times this is its standard deviation.
_MAD_TO_SD = 1.482602218505602


@dataclass(frozen=True)
class ImpactBounds:
    """What an impact allows its records to show (:func:`impact_bounds`).

    Attributes
    ----------
    velocity_m_s : float
        The impact velocity v0, m/s.
    rigid_peak_force_N : float
        The peak force of the same impact on a rigid wall through the case's law, N.
    rigid_rise_s : float
        The time that force takes to rise to its peak on a rigid wall, s (half the rigid
        wall's contact time: an elastic law loads and unloads along one curve).
    rigid_contact_time_s : float
        The contact time on a rigid wall, s.
    contact_time_bound_s : float
        An upper-side estimate of the contact time on the case's rod, s.
    bar_speed_m_s, dilatational_speed_m_s : float
        The rod's bar speed sqrt(E/rho) and dilatational speed
        sqrt(E (1 - nu) / ((1 + nu) (1 - 2 nu) rho)), m/s: no wave in the rod outruns the
        second, and the first pulse's crest travels at most at the first.
    axial_stiffness_N : float
        E A, N.
    rod_length_m : float
        The rod's length, m.
    """

    velocity_m_s: float
    rigid_peak_force_N: float
    rigid_rise_s: float
    rigid_contact_time_s: float
    contact_time_bound_s: float
    bar_speed_m_s: float
    dilatational_speed_m_s: float
    axial_stiffness_N: float
    rod_length_m: float


def impact_bounds(problem: ImpactProblem) -> ImpactBounds:
    """The bounds of :class:`ImpactBounds` for an impact."""
    rigid, material = problem.rigid_contact, problem.rod.material
    nu = material.poisson_ratio
    young, density = material.youngs_modulus_pa, material.density_kg_m3
    return ImpactBounds(
        velocity_m_s=problem.velocity_m_s,
        rigid_peak_force_N=rigid.peak_force_N,
        rigid_rise_s=0.5 * rigid.contact_time_s,
        rigid_contact_time_s=rigid.contact_time_s,
        contact_time_bound_s=problem.contact_time_estimate(),
        bar_speed_m_s=math.sqrt(young / density),
        dilatational_speed_m_s=math.sqrt(young * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * density)),
        axial_stiffness_N=young * problem.rod.area_m2,
        rod_length_m=problem.rod.length_m,
    )


def record_noise(values: NDArray[np.float64]) -> float:
    """The standard deviation of a record's noise, from its samples' second differences: the
    median absolute deviation of the differences, times 1.4826 (Gaussian), over sqrt(6) (the
    standard deviation of a second difference of independent samples). A pulse sampled many
    times over its rise adds little to most second differences, and the median ignores the
    few it does change (its start, its crest, its end)."""
    second = np.diff(np.asarray(values, float), 2)
    if not len(second):
        return 0.0
    return _MAD_TO_SD * float(np.median(np.abs(second - np.median(second)))) / math.sqrt(6.0)


@dataclass(frozen=True)
class _Signal:
    """A record as the checks see it: a pulse from zero (the impactor's velocity as its change
    from its first samples), the sign its first pulse must have, and its words."""

    time_s: NDArray[np.float64]
    pulse: NDArray[np.float64]
    expected_sign: int
    kind: str  # "force", "strain", "far_end" or "impactor"
    what: str  # "the force", "the strain at the gauge", ...
    display: float  # the factor from SI to the unit shown in messages
    unit: str


def _signal(history: MeasuredHistory, spec: Mapping[str, Any]) -> _Signal:
    t, v = history.time_s, history.values
    if history.kind == "force_history":
        return _Signal(t, v, 1, "force", "the force", 1.0, "N")
    if history.kind == "strain_history":
        return _Signal(t, v, -1, "strain", "the strain at the gauge", 1e6, "microstrain")
    if spec.get("of") == "far_end":
        return _Signal(t, v, 1, "far_end", "the far end's velocity", 1.0, "m/s")
    start = float(np.median(v[:MIN_NOISE_SAMPLES]))
    return _Signal(t, start - v, 1, "impactor", "the impactor's velocity", 1.0, "m/s")


@dataclass(frozen=True)
class _Pulse:
    """The first pulse of a signal: its crest (largest |value|), where it first reaches half of
    it (the sample ``first`` and the linear crossing ``half_s``), its sign, and where it starts
    (the sample ``start``, the first of its run above the threshold)."""

    crest: float
    first: int
    half_s: float
    sign: int
    start: int


def _crossing(t: NDArray[np.float64], g: NDArray[np.float64], i: int, level: float) -> float:
    """Where g rises through ``level`` between samples i - 1 and i (linear); t[i] for i = 0."""
    if i == 0 or g[i] == g[i - 1]:
        return float(t[i])
    return float(t[i - 1] + (level - g[i - 1]) * (t[i] - t[i - 1]) / (g[i] - g[i - 1]))


def _first_pulse(signal: _Signal, threshold: float) -> _Pulse:
    f = signal.pulse
    crest = float(np.max(np.abs(f)))
    first = int(np.argmax(np.abs(f) >= 0.5 * crest))
    sign = 1 if f[first] > 0 else -1
    g = sign * f
    start = first
    while start > 0 and g[start - 1] >= threshold * crest:
        start -= 1
    return _Pulse(crest, first, _crossing(signal.time_s, g, first, 0.5 * crest), sign, start)


def _us(seconds: float) -> str:
    return f"{1e6 * seconds:.4g} µs"


def _flip(spec: Mapping[str, Any]) -> str:
    return "remove sign: -1" if spec.get("sign") == -1 else "declare sign: -1"


def _unit_at_fault(history: MeasuredHistory, column: int) -> tuple[str, str]:
    """The field to blame for a unit (the header's cell, or the block's key) and its words."""
    quantity = "time" if column == 0 else RECORDS[history.kind].quantity
    unit = history.time_unit if column == 0 else history.value_unit
    if history.unit_from_header(column):
        return (
            "file",
            f"is the header's unit {history.header[column].strip()!r} ({history.path.name} line 1, column "
            f"{column + 1}) right?",
        )
    return f"{quantity}_unit", f"is {quantity}_unit: {unit} right?"


def _other_unit(history: MeasuredHistory, column: int, value: float, inside) -> tuple[str, float] | None:
    """The first other unit of ``column`` in which ``value`` (read in the record's unit, SI)
    would satisfy ``inside``, with the value it would then have; None when none does."""
    units = TIME_UNITS if column == 0 else RECORDS[history.kind].units
    used = units[history.time_unit if column == 0 else history.value_unit]
    for name, scale in units.items():
        candidate = value * scale / used
        if scale != used and inside(candidate):
            return name, candidate
    return None


def check_record(history: MeasuredHistory, spec: Mapping[str, Any], bounds: ImpactBounds) -> None:
    """Check that a record can be a record of its case's impact (see the module docstring).

    Parameters
    ----------
    history : MeasuredHistory
        The record, read (:func:`.measured.read_history`).
    spec : mapping
        Its block in the case's ``measured`` block (``sign``, ``threshold``, ``time_offset_s``,
        ``every``; a strain's ``station_m`` and ``gauge_length_m``; a velocity's ``of``).
    bounds : ImpactBounds
        What the case's impact allows (:func:`impact_bounds`).

    Raises
    ------
    HistoryError
        The first check the record fails, naming the block's key at fault.
    """
    signal = _signal(history, spec)
    threshold = float(spec.get("threshold", DEFAULT_THRESHOLD))
    name = history.path.name
    noise = record_noise(signal.pulse)
    pulse = _first_pulse(signal, threshold)
    if pulse.crest < MIN_SIGNAL_TO_NOISE * noise:
        raise HistoryError(
            "file",
            f"{name}: no pulse above the record's noise: {signal.what} reaches at most "
            f"{signal.display * pulse.crest:.4g} {signal.unit}"
            + (" from its first samples" if signal.kind == "impactor" else "")
            + f", {pulse.crest / noise:.3g} times its noise ({signal.display * noise:.3g} {signal.unit}, read from the "
            f"scatter of its samples); a record's pulse must stand at least {MIN_SIGNAL_TO_NOISE:g} times above it",
        )
    _check_sign(history, spec, signal, pulse)
    _check_pretrigger(history, spec, signal, pulse, threshold)
    _check_size(history, signal, pulse, bounds)
    _check_timing(history, spec, signal, pulse, bounds, threshold)


def _check_sign(history: MeasuredHistory, spec: Mapping[str, Any], signal: _Signal, pulse: _Pulse) -> None:
    t, v = signal.time_s, history.values
    at = _us(float(t[pulse.first]))
    if signal.kind == "impactor":
        start = float(np.median(v[:MIN_NOISE_SAMPLES]))
        if start < 0.0:
            raise HistoryError(
                "sign",
                f"{history.path.name}: the impactor's velocity starts at {start:.4g} m/s, away from the rod: it is "
                f"positive towards the rod; if the vibrometer reads the approach as negative, {_flip(spec)}",
            )
        return
    if pulse.sign == signal.expected_sign:
        return
    value = signal.display * float(signal.pulse[pulse.first])
    why = {
        "force_history": "a contact force pushes (positive); if the sensor reads compression as negative",
        "strain_history": "the impact's first wave compresses the rod (negative strain); if the gauge reads "
        "compression as positive",
        "velocity_history": "a free far end first moves away from the struck end (positive); if the vibrometer "
        "reads that as negative",
    }[history.kind]
    raise HistoryError(
        "sign",
        f"{history.path.name}: the first pulse of {signal.what} has the wrong sign ({value:+.4g} {signal.unit} "
        f"at {at}): {why}, {_flip(spec)}",
    )


def _check_pretrigger(
    history: MeasuredHistory, spec: Mapping[str, Any], signal: _Signal, pulse: _Pulse, threshold: float
) -> None:
    t, g = signal.time_s, pulse.sign * signal.pulse
    level = threshold * pulse.crest
    name = history.path.name
    if pulse.start == 0:
        quiet = 0
    else:
        begin = _crossing(t, g, pulse.start, level)
        quiet = int(np.count_nonzero(t <= t[0] + 0.8 * (begin - t[0])))
    if quiet < MIN_NOISE_SAMPLES:
        every = int(spec.get("every") or 1)
        where = "starts inside the first pulse" if pulse.start == 0 else f"has {quiet} quiet samples before it"
        if every > 1 and quiet * every >= MIN_NOISE_SAMPLES and pulse.start > 0:
            raise HistoryError(
                "every",
                f"every: {every} leaves {name} {quiet} samples before its first pulse (at "
                f"{_us(float(t[pulse.start]))}), fewer than the {MIN_NOISE_SAMPLES} its noise is read from; "
                "thin it less",
            )
        raise HistoryError(
            "file",
            f"{name} {where} (above {threshold:g} of its largest value from {_us(float(t[pulse.start]))}): a record "
            f"needs a pre-trigger of at least {MIN_NOISE_SAMPLES} quiet samples before its first pulse, to read its "
            "noise and where the pulse starts",
        )
    if history.kind == "force_history" and g[-1] >= level:
        raise HistoryError(
            "file",
            f"{name} ends inside a contact (its last sample at {g[-1] / pulse.crest:.2g} of the peak, above the "
            f"threshold {threshold:g}): the contact time would be read short; record past the contact's end",
        )


def _check_size(history: MeasuredHistory, signal: _Signal, pulse: _Pulse, bounds: ImpactBounds) -> None:
    v0, factor = bounds.velocity_m_s, MAGNITUDE_FACTOR
    rigid = f"its peak force on a rigid wall, {bounds.rigid_peak_force_N:.4g} N"
    shown = f"{signal.display * pulse.crest:.4g} {signal.unit}"
    if history.kind == "force_history":
        largest, limit = pulse.crest, bounds.rigid_peak_force_N
        what = f"a peak force of {shown} is more than {factor:g} times {rigid} (the largest any rod allows)"
    elif history.kind == "strain_history":
        largest, limit = pulse.crest, 2.0 * bounds.rigid_peak_force_N / bounds.axial_stiffness_N
        what = (
            f"a strain of {shown} is more than {factor:g} times the largest this impact can give at a gauge, "
            f"{1e6 * limit:.4g} microstrain (twice {rigid}, over EA: a fixed end doubles a wave)"
        )
    elif signal.kind == "far_end":
        largest, limit = pulse.crest, 2.0 * v0
        what = (
            f"a velocity of {shown} is more than {factor:g} times twice the impact velocity of {v0:.4g} m/s (a free "
            "end moves at twice the particle velocity, which the impact velocity bounds)"
        )
    else:
        values = history.values
        start = float(np.median(values[:MIN_NOISE_SAMPLES]))
        largest, limit = float(np.max(np.abs(values))), v0
        what = (
            f"a velocity of {largest:.4g} m/s is more than {factor:g} times the impact velocity of {v0:.4g} m/s (the "
            "impactor never moves faster than it struck)"
        )
        if largest <= factor * limit and start < limit / factor:
            what = (
                f"the impactor's velocity starts at {start:.4g} m/s, less than 1/{factor:g} of the impact velocity of "
                f"{v0:.4g} m/s"
            )
            _blame_value(history, signal, start, lambda x: limit / factor <= x <= factor * limit, what)
    if largest > factor * limit:
        _blame_value(history, signal, largest, lambda x: x <= factor * limit, what)


def _blame_value(history: MeasuredHistory, signal: _Signal, value: float, inside, what: str) -> None:
    name = history.path.name
    other = _other_unit(history, 1, value, inside)
    if other is not None:
        field, question = _unit_at_fault(history, 1)
        raise HistoryError(
            field,
            f"{name}: {what}; read in {other[0]}, it would be {signal.display * other[1]:.4g} {signal.unit}: "
            f"{question}",
        )
    raise HistoryError(
        "file", f"{name}: {what}: check the record's values and the case's impact (velocity, mass, nose radius)"
    )


def _check_timing(
    history: MeasuredHistory,
    spec: Mapping[str, Any],
    signal: _Signal,
    pulse: _Pulse,
    bounds: ImpactBounds,
    threshold: float,
) -> None:
    name, offset = history.path.name, float(spec.get("time_offset_s") or 0.0)
    late = LATE_FACTOR * bounds.contact_time_bound_s
    if signal.kind == "force":
        g = pulse.sign * signal.pulse
        level = threshold * pulse.crest
        above = np.flatnonzero(g >= level)
        duration = float(signal.time_s[above[-1]] - signal.time_s[above[0]])
        low, high = bounds.rigid_contact_time_s / LATE_FACTOR, late
        if low <= duration <= high:
            return
        what = (
            f"{name}: the force stays above {threshold:g} of its peak for {_us(duration)}, but a contact of this "
            f"impact lasts between {_us(low)} ({1 / LATE_FACTOR:g} of the rigid wall's "
            f"{_us(bounds.rigid_contact_time_s)}) and {_us(high)} ({LATE_FACTOR:g} times the contact time's "
            "upper-side estimate)"
        )
        other = _other_unit(history, 0, duration, lambda x: low <= x <= high)
        if other is not None:
            field, question = _unit_at_fault(history, 0)
            raise HistoryError(field, f"{what}; read in {other[0]}, it would last {_us(other[1])}: {question}")
        raise HistoryError("file", f"{what}: check the record's times")
    if signal.kind == "strain":
        x, length = float(spec["station_m"]), float(spec.get("gauge_length_m") or 0.0)
        where = f"the gauge at {x:g} m"
    elif signal.kind == "far_end":
        x, length = bounds.rod_length_m, 0.0
        where = f"the far end ({x:g} m)"
    else:
        x, length, where = 0.0, 0.0, None
    low = max(x - 0.5 * length, 0.0) / bounds.dilatational_speed_m_s - bounds.rigid_rise_s
    high = (x + 0.5 * length) / bounds.bar_speed_m_s + late
    if low <= pulse.half_s <= high:
        return
    if where is None:
        what = (
            f"{name}: the impactor's velocity loses half its change at {_us(pulse.half_s)} on the record's clock, but "
            f"it does so between {_us(low)} and {_us(high)} after the impact"
        )
    else:
        what = (
            f"{name}: the first pulse reaches half its crest at {where} at {_us(pulse.half_s)} on the record's clock, "
            f"but on this rod it does so between {_us(low)} and {_us(high)} after the impact "
            f"(x/c = {_us(x / bounds.bar_speed_m_s)})"
        )
    other = _other_unit(history, 0, pulse.half_s - offset, lambda t: low <= t + offset <= high)
    if other is not None:
        field, question = _unit_at_fault(history, 0)
        raise HistoryError(field, f"{what}; read in {other[0]}, at {_us(other[1] + offset)}: {question}")
    raise HistoryError(
        "time_offset_s",
        f"{what}: the record's time zero must be the impact; set time_offset_s (now {offset:g} s) to put it there",
    )
