"""What a run says about what was measured: every compared quantity of one case and one run.

One place turns a case's ``measured`` block (its scalars and records,
:mod:`rodimpact.analysis.measured`) and a run's histories and summary into the quantities the
comparison tables list and a calibration fits (:func:`observed`). A run is given as two
mappings, so a stored run (:class:`~rodimpact.storage.runs.RunRecord`) and a result still in
memory (:class:`~rodimpact.solvers.result.ImpactResult`) are read alike:

* the scalars (:data:`SCALARS`): the contact time, the peak force, the rebound velocity, and
  with the rebound, the coefficient of restitution (the run's ``restitution``);
* a force history (:mod:`.history_compare`): the contact time read from both signals at the
  record's threshold, and the L2 and max-norm errors after alignment;
* a strain history at a gauge and the far end's velocity (:mod:`.wave_compare`): the first
  pulse's arrival (with x/c, or L/c, in its words), peak and integral, and the norms after
  aligning the arrivals;
* the impactor's velocity: the norms on the record's own clock (no pulse to align on).

A value's error is signed, in % of the measured one: (computed - measured) / |measured|. A
norm is an error already: its ``measured`` is NaN and its ``error_pct`` the norm in %.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.analysis.errors import relative_error_pct
from rodimpact.analysis.history_compare import DEFAULT_THRESHOLD, HistoryComparison, compare_force_histories
from rodimpact.analysis.measured import MeasuredHistory
from rodimpact.analysis.wave_compare import SignalComparison, compare_signals

__all__ = [
    "NEEDS",
    "NORMS",
    "QUANTITIES",
    "QUANTITY_ORDER",
    "Quantity",
    "SCALARS",
    "Observed",
    "bar_speed",
    "force_comparison",
    "gauge_column",
    "gives",
    "observed",
    "quantity_words",
    "signal_comparison",
]

#: Measured scalars a case may give: key -> the computed value from a run's summary.
SCALARS: dict[str, Callable[[Mapping[str, Any]], float]] = {
    "contact_time_us": lambda s: 1e6 * float(s["contact_time_s"]),
    "peak_force_n": lambda s: float(np.max(s["peak_force_N"])) if len(s["peak_force_N"]) else math.nan,
    "rebound_velocity_m_s": lambda s: -float(s["rebound_velocity_m_s"]),
}


@dataclass(frozen=True)
class Quantity:
    """What a measured quantity is: its words (``{threshold}``: the force record's threshold),
    its unit, the key of the ``measured`` block it comes from (a scalar's own key, or a record's)
    and, for a velocity record, whose velocity (``of``); a norm is an error already."""

    words: str
    unit: str
    record: str
    of: str | None = None
    norm: bool = False


def _norm_of(words: str, record: str, of: str | None = None) -> Quantity:
    return Quantity(words, "%", record, of, norm=True)


#: Every quantity :func:`observed` gives, in the order tables list them.
QUANTITIES: dict[str, Quantity] = {
    "contact_time_us": Quantity("contact time", "µs", "contact_time_us"),
    "peak_force_n": Quantity("peak force", "N", "peak_force_n"),
    "rebound_velocity_m_s": Quantity("rebound velocity", "m/s", "rebound_velocity_m_s"),
    "restitution": Quantity("coefficient of restitution, rebound over impact velocity", "1", "rebound_velocity_m_s"),
    "signal_contact_time_us": Quantity(
        "contact time read from the signal at {threshold:g} of its peak", "µs", "force_history"
    ),
    "history_l2_pct": _norm_of("force history, L2 error after alignment", "force_history"),
    "history_max_pct": _norm_of("force history, max-norm error after alignment", "force_history"),
    "strain_arrival_us": Quantity("arrival of the first wave at the gauge, at half its crest", "µs", "strain_history"),
    "strain_peak_microstrain": Quantity("peak strain of the first pulse", "microstrain", "strain_history"),
    "strain_integral_microstrain_us": Quantity(
        "time integral of the first pulse's strain", "µstrain·µs", "strain_history"
    ),
    "strain_l2_pct": _norm_of("strain at the gauge, L2 error after alignment", "strain_history"),
    "strain_max_pct": _norm_of("strain at the gauge, max-norm error after alignment", "strain_history"),
    "far_end_arrival_us": Quantity(
        "arrival of the first wave at the far end, at half its crest", "µs", "velocity_history", "far_end"
    ),
    "far_end_peak_velocity_m_s": Quantity(
        "peak velocity of the far end's first pulse", "m/s", "velocity_history", "far_end"
    ),
    "far_end_displacement_um": Quantity(
        "the far end's displacement over the first pulse", "µm", "velocity_history", "far_end"
    ),
    "far_end_velocity_l2_pct": _norm_of("far end's velocity, L2 error after alignment", "velocity_history", "far_end"),
    "far_end_velocity_max_pct": _norm_of(
        "far end's velocity, max-norm error after alignment", "velocity_history", "far_end"
    ),
    "impactor_velocity_l2_pct": _norm_of("impactor's velocity, L2 error", "velocity_history", "impactor"),
    "impactor_velocity_max_pct": _norm_of("impactor's velocity, max-norm error", "velocity_history", "impactor"),
}
#: The quantities, in the order tables list them.
QUANTITY_ORDER: tuple[str, ...] = tuple(QUANTITIES)
#: Which record (or scalar) of the ``measured`` block each quantity comes from: quantity ->
#: (key, the velocity record's ``of`` or None).
NEEDS: dict[str, tuple[str, str | None]] = {name: (q.record, q.of) for name, q in QUANTITIES.items()}
#: The quantities that are error norms (nothing measured to set a value against).
NORMS = frozenset(name for name, q in QUANTITIES.items() if q.norm)


def gives(config: Mapping[str, Any], quantity: str) -> bool:
    """Whether the case's ``measured`` block gives ``quantity`` (:data:`NEEDS`)."""
    key, of = NEEDS[quantity]
    value = (config.get("measured") or {}).get(key)
    return value is not None and (of is None or value.get("of") == of)


@dataclass(frozen=True)
class Observed:
    """One measured quantity against the computed one.

    Attributes
    ----------
    quantity : str
        Its key (:data:`QUANTITY_ORDER`).
    words, unit : str
        What it is, in words (with the record's threshold or x/c where they matter), and its unit.
    measured, computed : float
        The values (NaN for a norm).
    error_pct : float
        (computed - measured) / |measured| in %, or the norm in %.
    measured_sd : float
        The standard uncertainty the record's noise gives the measured value, in its unit
        (:class:`~rodimpact.analysis.wave_compare.FirstPulse`); NaN where none is known.
    """

    quantity: str
    words: str
    unit: str
    measured: float
    computed: float
    error_pct: float
    measured_sd: float = math.nan

    @property
    def is_norm(self) -> bool:
        """True for an error norm (nothing measured to set a value against)."""
        return math.isnan(self.measured)


def quantity_words(quantity: str, config: Mapping[str, Any], *, transit: bool = True) -> str:
    """A quantity of a case in words: its declared words (:data:`QUANTITIES`) with the force
    record's threshold, and for an arrival the wave's transit x/c at the case's modulus
    (``transit=False`` leaves it out: a calibration varies the modulus)."""
    measured = config.get("measured") or {}
    threshold = float((measured.get("force_history") or {}).get("threshold", DEFAULT_THRESHOLD))
    words = QUANTITIES[quantity].words.format(threshold=threshold)
    if transit and quantity.endswith("_arrival_us"):
        if quantity.startswith("strain"):
            x = float(measured["strain_history"]["station_m"])
        else:
            x = float(config["rod"]["length_m"])
        words += f" (x/c = {1e6 * x / bar_speed(config):.4g} µs at x = {x:g} m)"
    return words


def _value(
    config: Mapping[str, Any], quantity: str, measured: float, computed: float, measured_sd: float = math.nan
) -> Observed:
    words, unit = quantity_words(quantity, config), QUANTITIES[quantity].unit
    return Observed(quantity, words, unit, measured, computed, relative_error_pct(computed, measured), measured_sd)


def _norm(config: Mapping[str, Any], quantity: str, error: float) -> Observed:
    return Observed(quantity, quantity_words(quantity, config), "%", math.nan, math.nan, 100.0 * error)


def bar_speed(config: Mapping[str, Any]) -> float:
    """The rod's bar speed sqrt(E/rho) of a resolved case, m/s."""
    material = config["rod"]["material"]
    return math.sqrt(float(material["youngs_modulus_pa"]) / float(material["density_kg_m3"]))


def gauge_column(summary: Mapping[str, Any], station_m: float, gauge_length_m: float) -> int:
    """The column of a run's ``gauge_strain`` that holds the gauge at ``station_m`` of
    ``gauge_length_m`` (the summary's ``gauge_x_m`` and ``gauge_length_m``).

    Raises
    ------
    KeyError
        The run recorded no such gauge.
    """
    xs = np.atleast_1d(np.asarray(summary.get("gauge_x_m", []), float))
    lengths = np.atleast_1d(np.asarray(summary.get("gauge_length_m", np.zeros_like(xs)), float))
    for index, (x, length) in enumerate(zip(xs, lengths, strict=True)):
        if math.isclose(x, station_m, rel_tol=1e-9, abs_tol=1e-12) and math.isclose(
            length, gauge_length_m, rel_tol=1e-9, abs_tol=1e-12
        ):
            return index
    raise KeyError(f"no gauge at {station_m:g} m of length {gauge_length_m:g} m in the run (gauges at {list(xs)})")


def force_comparison(
    series: Mapping[str, NDArray[np.float64]], record: MeasuredHistory, threshold: float
) -> HistoryComparison:
    """The run's contact force against a measured force history."""
    if "contact_force" not in series:
        raise KeyError("the run stored no contact_force to compare with the measured force history")
    return compare_force_histories(record.time_s, record.values, series["time"], series["contact_force"], threshold)


def signal_comparison(
    key: str,
    spec: Mapping[str, Any],
    series: Mapping[str, NDArray[np.float64]],
    summary: Mapping[str, Any],
    record: MeasuredHistory,
) -> SignalComparison:
    """The run's signal a strain or velocity record measures, against it (the record's block
    ``spec`` says which gauge or whose velocity)."""
    threshold = float(spec.get("threshold", DEFAULT_THRESHOLD))
    if key == "strain_history":
        if "gauge_strain" not in series:
            raise KeyError("the run stored no gauge_strain to compare with the measured strain history")
        column = gauge_column(summary, float(spec["station_m"]), float(spec.get("gauge_length_m", 0.0)))
        model = np.asarray(series["gauge_strain"]).reshape(len(series["time"]), -1)[:, column]
        return compare_signals(record.time_s, record.values, series["time"], model, threshold)
    name = "impactor_velocity" if spec["of"] == "impactor" else "far_end_velocity"
    if name not in series:
        raise KeyError(f"the run stored no {name} to compare with the measured velocity history")
    return compare_signals(
        record.time_s, record.values, series["time"], series[name], threshold, pulses=spec["of"] != "impactor"
    )


def observed(
    config: Mapping[str, Any],
    series: Mapping[str, NDArray[np.float64]],
    summary: Mapping[str, Any],
    records: Mapping[str, MeasuredHistory] | None = None,
) -> list[Observed]:
    """Every measured quantity of a case against one run of it (see the module docstring).

    Parameters
    ----------
    config : mapping
        The resolved case (its ``measured`` block, its rod).
    series : mapping
        The run's histories by dataset name, ``time`` included (only those the records need).
    summary : mapping
        The run's summary (``contact_time_s``, ``peak_force_N``, ``rebound_velocity_m_s``,
        ``gauge_x_m``...).
    records : mapping, optional
        The case's records, read, by their key in the ``measured`` block.

    Returns
    -------
    list of Observed
        In the order of :data:`QUANTITY_ORDER`.
    """
    measured, records = config.get("measured") or {}, dict(records or {})
    rows = [
        _value(config, key, float(measured[key]), computed_of(summary))
        for key, computed_of in SCALARS.items()
        if measured.get(key) is not None
    ]
    if measured.get("rebound_velocity_m_s") is not None:  # and the restitution it gives
        impact = float(config["impactor"]["velocity_m_s"])
        rows.append(
            _value(
                config, "restitution", float(measured["rebound_velocity_m_s"]) / impact, float(summary["restitution"])
            )
        )
    if "force_history" in records:
        threshold = float(measured["force_history"].get("threshold", DEFAULT_THRESHOLD))
        result = force_comparison(series, records["force_history"], threshold)
        signal, model = 1e6 * result.measured_contact_time_s, 1e6 * result.model_contact_time_s
        rows.append(_value(config, "signal_contact_time_us", signal, model))
        rows.append(_norm(config, "history_l2_pct", result.l2_error))
        rows.append(_norm(config, "history_max_pct", result.max_error))
    if "strain_history" in records:
        spec = measured["strain_history"]
        result = signal_comparison("strain_history", spec, series, summary, records["strain_history"])
        rows += _pulse_rows(config, "strain", result)
    velocity = measured.get("velocity_history")
    if "velocity_history" in records and velocity["of"] == "far_end":
        result = signal_comparison("velocity_history", velocity, series, summary, records["velocity_history"])
        rows += _pulse_rows(config, "far_end", result)
    elif "velocity_history" in records:
        result = signal_comparison("velocity_history", velocity, series, summary, records["velocity_history"])
        rows.append(_norm(config, "impactor_velocity_l2_pct", result.l2_error))
        rows.append(_norm(config, "impactor_velocity_max_pct", result.max_error))
    return rows


#: A wave signal's quantities (``strain``: the strain at a gauge; ``far_end``: the far end's
#: velocity): arrival, peak, integral, the two norms, each with its scale from SI.
_PULSES = {
    "strain": (
        "strain_arrival_us",
        ("strain_peak_microstrain", 1e6),
        ("strain_integral_microstrain_us", 1e12),
        "strain",
    ),
    "far_end": (
        "far_end_arrival_us",
        ("far_end_peak_velocity_m_s", 1.0),
        ("far_end_displacement_um", 1e6),
        "far_end_velocity",
    ),
}


def _pulse_rows(config: Mapping[str, Any], prefix: str, result: SignalComparison) -> list[Observed]:
    """The first pulse's rows and the norms of a wave signal (``prefix`` ``strain``: the strain at a
    gauge; ``far_end``: the far end's velocity)."""
    measured, model = result.measured_pulse, result.model_pulse
    if measured is None or model is None:
        raise ValueError("a wave signal is compared with its first pulses")
    arrival, (peak, peak_scale), (integral, integral_scale), norm = _PULSES[prefix]
    return [
        _value(config, arrival, 1e6 * measured.arrival_s, 1e6 * model.arrival_s, 1e6 * measured.arrival_sd_s),
        _value(config, peak, peak_scale * measured.peak, peak_scale * model.peak, peak_scale * measured.peak_sd),
        _value(
            config,
            integral,
            integral_scale * measured.integral,
            integral_scale * model.integral,
            integral_scale * measured.integral_sd,
        ),
        _norm(config, f"{norm}_l2_pct", result.l2_error),
        _norm(config, f"{norm}_max_pct", result.max_error),
    ]
