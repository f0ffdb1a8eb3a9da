"""What a measured record can show of its case's impact (rodimpact.analysis.record_checks):
records made from a closed-form contact force pass; each fault a lab makes by mistake (noise
alone, the wrong sign, no pre-trigger, a unit off by a thousand, a clock not started at the
impact) is one error naming the block's key at fault."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from rodimpact.analysis.measured import HistoryError, MeasuredHistory, read_history
from rodimpact.analysis.record_checks import (
    LATE_FACTOR,
    MAGNITUDE_FACTOR,
    MIN_SIGNAL_TO_NOISE,
    ImpactBounds,
    check_record,
    impact_bounds,
    record_noise,
)
from rodimpact.model.problem import ImpactProblem

#: The gauge example's 8 mm ball on its steel rod, gauge at 0.25 m (config/cases/worked_example_gauge.yaml).
CASE = "gauge_8mm"
STATION_M, GAUGE_M = 0.25, 0.005
#: The closed-form contact: a half-sine of this duration from the impact, its impulse 1.8 m v0
#: (a restitution of 0.8), sampled every 0.5 µs from 20 µs before the impact.
DURATION_S, RESTITUTION = 30e-6, 0.8
SAMPLE_US = np.arange(-20.0, 250.0, 0.5)


@pytest.fixture(scope="module")
def impact(shipped_project) -> tuple[ImpactProblem, ImpactBounds]:
    problem = ImpactProblem.from_case(shipped_project.cases[CASE])
    return problem, impact_bounds(problem)


def _force(problem: ImpactProblem, t: np.ndarray) -> np.ndarray:
    peak = problem.mass_kg * problem.velocity_m_s * (1 + RESTITUTION) * math.pi / (2 * DURATION_S)
    inside = (t >= 0) & (t <= DURATION_S)
    return np.where(inside, peak * np.sin(math.pi * np.clip(t, 0, DURATION_S) / DURATION_S), 0.0)


def _signals(problem: ImpactProblem) -> dict[str, np.ndarray]:
    """Each kind of record of the closed-form contact in SI, on the sample times: the force, the
    1-D rod's strain at the gauge (its incident wave, -P(t - x/c)/(EA)), a free far end's
    velocity (2 P(t - L/c) / Z) and the impactor's velocity (v0 less its impulse over m)."""
    rod = problem.rod
    c = math.sqrt(rod.material.youngs_modulus_pa / rod.material.density_kg_m3)
    ea = rod.material.youngs_modulus_pa * rod.area_m2
    t = 1e-6 * SAMPLE_US
    fine = np.linspace(-20e-6, 250e-6, 54001)
    impulse = np.concatenate(
        [[0.0], np.cumsum(0.5 * (_force(problem, fine)[1:] + _force(problem, fine)[:-1]) * np.diff(fine))]
    )
    return {
        "force_history": _force(problem, t),
        "strain_history": -_force(problem, t - STATION_M / c) / ea,
        "far_end": 2.0 * _force(problem, t - rod.length_m / c) * c / ea,
        "impactor": problem.velocity_m_s - np.interp(t, fine, impulse) / problem.mass_kg,
    }


#: kind -> (the record's key, its header in SI-ish units, the scale from SI to them, its block)
KINDS = {
    "force_history": ("force_history", "time_us,force_N", 1.0, {}),
    "strain_history": (
        "strain_history",
        "time_us,strain_microstrain",
        1e6,
        {"station_m": STATION_M, "gauge_length_m": GAUGE_M},
    ),
    "far_end": ("velocity_history", "time_us,velocity_m_s", 1.0, {"of": "far_end"}),
    "impactor": ("velocity_history", "time_us,velocity_m_s", 1.0, {"of": "impactor"}),
}


def _record(
    tmp_path: Path,
    kind: str,
    values_si: np.ndarray,
    *,
    times_us: np.ndarray = SAMPLE_US,
    header: str | None = None,
    scale: float | None = None,
    noise: float = 0.01,
    **spec,
) -> tuple[MeasuredHistory, dict]:
    """The record of ``kind`` written as a lab would (1 % noise of its largest value), read back."""
    key, default_header, default_scale, block = KINDS[kind]
    values = values_si * (default_scale if scale is None else scale)
    rng = np.random.default_rng(7)
    noisy = values + rng.normal(0.0, noise * float(np.max(np.abs(values))), len(values))
    path = tmp_path / f"{kind}.csv"
    rows = "".join(f"{float(t)!r},{float(v)!r}\n" for t, v in zip(times_us, noisy, strict=True))
    path.write_text(f"{header or default_header}\n{rows}", encoding="utf-8")
    spec = {**block, "file": path.name, **spec}
    return read_history(path, spec, key), spec


def _refused(history: MeasuredHistory, spec: dict, bounds: ImpactBounds) -> HistoryError:
    with pytest.raises(HistoryError) as caught:
        check_record(history, spec, bounds)
    assert "\n" not in str(caught.value)
    return caught.value


@pytest.mark.parametrize("kind", list(KINDS))
def test_a_record_of_the_closed_form_contact_passes(impact, tmp_path: Path, kind: str) -> None:
    problem, bounds = impact
    check_record(*_record(tmp_path, kind, _signals(problem)[kind]), bounds)


def test_the_shipped_records_pass(shipped_project) -> None:
    """Every record of every shipped case passes (the configuration's load checks them too)."""
    checked = 0
    for case in shipped_project.cases.values():
        measured = case.get("measured") or {}
        for key in ("force_history", "strain_history", "velocity_history"):
            if measured.get(key):
                spec = measured[key]
                check_record(
                    read_history(Path(spec["path"]), spec, key), spec, impact_bounds(ImpactProblem.from_case(case))
                )
                checked += 1
    assert checked >= 6


def test_the_noise_is_read_from_the_scatter_whatever_the_pulse() -> None:
    """Gaussian noise of sigma is read as sigma (within the estimate's own spread, about
    2.6 % at 5,000 samples), alone and under a pulse 100 times larger sampled over 60 points."""
    rng = np.random.default_rng(11)
    noise = rng.normal(0.0, 0.5, 5000)
    t = np.arange(5000)
    pulse = 50.0 * np.where((t > 1000) & (t < 1060), np.sin(np.pi * (t - 1000) / 60), 0.0)
    assert record_noise(noise) == pytest.approx(0.5, rel=0.08)
    assert record_noise(noise + pulse) == pytest.approx(0.5, rel=0.08)
    assert record_noise(np.zeros(100)) == 0.0


@pytest.mark.parametrize("kind", list(KINDS))
def test_a_record_of_noise_alone_is_refused(impact, tmp_path: Path, kind: str) -> None:
    """A million samples of Gaussian noise reach about 5 sigma at most: far below the 10 a pulse needs."""
    problem, bounds = impact
    rng = np.random.default_rng(3)
    t = np.arange(-20.0, 250.0, 0.5)
    scale = float(np.max(np.abs(_signals(problem)[kind])))
    level = problem.velocity_m_s if kind == "impactor" else 0.0
    history, spec = _record(tmp_path, kind, level + rng.normal(0.0, 0.01 * scale, len(t)), noise=0.0)
    error = _refused(history, spec, bounds)
    assert error.field == "file" and "no pulse above the record's noise" in error.reason, error


def test_a_pulse_ten_times_its_noise_passes(impact, tmp_path: Path) -> None:
    """The line between a pulse and noise: a clean closed-form strain under noise of 1/12 of its
    crest passes (about 12 times its noise), under 1/8 of it is refused."""
    problem, bounds = impact
    strain = _signals(problem)["strain_history"]
    history, spec = _record(tmp_path, "strain_history", strain, noise=1.0 / (1.2 * MIN_SIGNAL_TO_NOISE))
    check_record(history, spec, bounds)
    history, spec = _record(tmp_path, "strain_history", strain, noise=1.0 / (0.8 * MIN_SIGNAL_TO_NOISE))
    assert "no pulse above" in _refused(history, spec, bounds).reason


@pytest.mark.parametrize("kind", ["force_history", "strain_history", "far_end", "impactor"])
def test_a_record_of_the_wrong_sign_names_sign(impact, tmp_path: Path, kind: str) -> None:
    problem, bounds = impact
    signal = _signals(problem)[kind]
    history, spec = _record(tmp_path, kind, -signal)
    error = _refused(history, spec, bounds)
    assert error.field == "sign" and "declare sign: -1" in error.reason, error
    declared, spec = _record(tmp_path, kind, -signal, sign=-1)
    check_record(declared, spec, bounds)  # declared: read as the closed form
    flipped, spec = _record(tmp_path, kind, signal, sign=-1)
    assert "remove sign: -1" in _refused(flipped, spec, bounds).reason


@pytest.mark.parametrize("kind", list(KINDS))
def test_a_record_without_a_pre_trigger_is_refused(impact, tmp_path: Path, kind: str) -> None:
    """Started after the first pulse has risen: no quiet samples to read the noise from."""
    problem, bounds = impact
    signals = _signals(problem)
    arrival_us = {"force_history": 2.0, "strain_history": 52.0, "far_end": 100.0, "impactor": 6.0}[kind]
    keep = SAMPLE_US >= arrival_us
    history, spec = _record(tmp_path, kind, signals[kind][keep], times_us=SAMPLE_US[keep])
    error = _refused(history, spec, bounds)
    assert error.field == "file" and "pre-trigger" in error.reason, error


def test_a_thinning_that_leaves_no_pre_trigger_names_every(impact, tmp_path: Path) -> None:
    problem, bounds = impact
    times = np.arange(30.0, 250.0, 0.5)  # 36 samples before the wave reaches the gauge at 0.25 m
    strain = _signals(problem)["strain_history"][SAMPLE_US >= 30.0]
    history, spec = _record(tmp_path, "strain_history", strain, times_us=times, every=6)
    error = _refused(history, spec, bounds)
    assert error.field == "every" and "thin it less" in error.reason, error


def test_a_force_record_that_ends_inside_its_contact_is_refused(impact, tmp_path: Path) -> None:
    problem, bounds = impact
    keep = SAMPLE_US <= 20.0
    history, spec = _record(
        tmp_path, "force_history", _signals(problem)["force_history"][keep], times_us=SAMPLE_US[keep]
    )
    error = _refused(history, spec, bounds)
    assert error.field == "file" and "ends inside a contact" in error.reason, error


@pytest.mark.parametrize(
    "kind, header, scale, declared, field, words",
    [
        # the header's unit is the header's fault (the file); a declared one, its key
        ("strain_history", "time_us,strain_strain", 1e6, {}, "file", "header's unit 'strain_strain'"),
        ("strain_history", "time_us,strain", 1e6, {"strain_unit": "strain"}, "strain_unit", "strain_unit: strain"),
        ("force_history", "time_us,force_kN", 1.0, {}, "file", "header's unit 'force_kN'"),
        ("far_end", "time_us,velocity_m_s", 1e3, {}, "file", "header's unit 'velocity_m_s'"),
        ("impactor", "time_us,velocity_m_s", 1e3, {}, "file", "header's unit 'velocity_m_s'"),
        # a velocity in m/s headed mm/s starts at a thousandth of the impact velocity
        ("impactor", "time_us,velocity_mm_s", 1.0, {}, "file", "header's unit 'velocity_mm_s'"),
    ],
)
def test_a_size_the_impact_cannot_give_blames_the_unit(
    impact, tmp_path: Path, kind, header, scale, declared, field, words
) -> None:
    problem, bounds = impact
    history, spec = _record(tmp_path, kind, _signals(problem)[kind], header=header, scale=scale, **declared)
    error = _refused(history, spec, bounds)
    assert error.field == field and words in error.reason, error


def test_the_size_bound_is_the_rigid_wall_by_the_stated_factor(impact, tmp_path: Path) -> None:
    """A force just under the factor times the rigid wall's peak passes, just over it is refused."""
    problem, bounds = impact
    t = 1e-6 * SAMPLE_US
    shape = _force(problem, t) / np.max(_force(problem, t))
    for share, passes in ((0.97, True), (1.03, False)):
        history, spec = _record(
            tmp_path, "force_history", share * MAGNITUDE_FACTOR * bounds.rigid_peak_force_N * shape, noise=0.0
        )
        if passes:
            check_record(history, spec, bounds)
        else:
            assert _refused(history, spec, bounds).field == "file"


@pytest.mark.parametrize(
    "kind, header, declared, field, words",
    [
        ("strain_history", "time_ms,strain_microstrain", {}, "file", "header's unit 'time_ms'"),
        ("far_end", "time,velocity_m_s", {"time_unit": "ms"}, "time_unit", "time_unit: ms right?"),
        ("impactor", "time_ms,velocity_m_s", {}, "file", "header's unit 'time_ms'"),
        ("force_history", "time_ms,force_N", {}, "file", "header's unit 'time_ms'"),
    ],
)
def test_a_time_the_rod_does_not_allow_blames_the_unit(impact, tmp_path: Path, kind, header, declared, field, words):
    problem, bounds = impact
    history, spec = _record(tmp_path, kind, _signals(problem)[kind], header=header, **declared)
    error = _refused(history, spec, bounds)
    assert error.field == field and words in error.reason, error


@pytest.mark.parametrize("kind", ["strain_history", "far_end", "impactor"])
@pytest.mark.parametrize("offset_s", [-100e-6, 1e-3])
def test_a_clock_not_started_at_the_impact_names_the_offset(impact, tmp_path: Path, kind: str, offset_s: float):
    """A wave signal or the impactor's velocity is read on the record's clock: its zero must be
    the impact. A force record aligns on itself, so its offset is free."""
    problem, bounds = impact
    history, spec = _record(tmp_path, kind, _signals(problem)[kind], time_offset_s=offset_s)
    error = _refused(history, spec, bounds)
    assert error.field == "time_offset_s" and "time zero must be the impact" in error.reason, error
    force, spec = _record(tmp_path, "force_history", _signals(problem)["force_history"], time_offset_s=offset_s)
    check_record(force, spec, bounds)


def test_the_arrival_window_is_the_waves_speeds_and_the_contact(impact, tmp_path: Path) -> None:
    """At the gauge, the first pulse's half crest may come no earlier than the dilatational wave
    at the gauge's near edge less the rigid wall's rise, and no later than the bar wave at its far
    edge plus twice the contact-time estimate: just inside each end passes, just outside is refused."""
    problem, bounds = impact
    strain = _signals(problem)["strain_history"]
    c = bounds.bar_speed_m_s
    # where the closed form's half crest falls: x/c plus the time to half of a half-sine's crest
    half = STATION_M / c + DURATION_S / 6.0
    early = (STATION_M - GAUGE_M / 2) / bounds.dilatational_speed_m_s - bounds.rigid_rise_s
    late = (STATION_M + GAUGE_M / 2) / c + LATE_FACTOR * bounds.contact_time_bound_s
    for target, passes in ((early + 2e-7, True), (early - 2e-7, False), (late - 2e-7, True), (late + 2e-7, False)):
        moved, spec = _record(tmp_path, "strain_history", strain, noise=0.0, time_offset_s=target - half)
        if passes:
            check_record(moved, spec, bounds)
        else:
            assert _refused(moved, spec, bounds).field == "time_offset_s"
