"""A lab's own records: strain at a gauge and velocities read and checked, their first pulses read
against closed forms, and every bad record or calibration block refused in one line before any
job (config/README.md, "Comparing with your experiment"; docs/calibration.md)."""

from __future__ import annotations

import copy
import math
import shutil
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import yaml

from rodimpact.analysis.measured import HistoryError, read_history
from rodimpact.analysis.wave_compare import compare_signals, first_pulse
from rodimpact.config.load import load_global_config, load_project
from rodimpact.config.project import ConfigError

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = "config/cases/worked_example_gauge.yaml"


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def _half_sine(t: np.ndarray, start: float, duration: float, peak: float) -> np.ndarray:
    inside = (t >= start) & (t <= start + duration)
    return np.where(inside, peak * np.sin(np.pi * np.clip(t - start, 0.0, duration) / duration), 0.0)


def test_strain_and_velocity_units_from_the_header_or_declared(tmp_path: Path) -> None:
    rows = "".join(f"{k},{-3.0 * k}\n" for k in range(20))
    micro = read_history(_write(tmp_path / "a.csv", "time_us,strain_microstrain\n" + rows), {}, "strain_history")
    plain = read_history(
        _write(tmp_path / "b.csv", "time,strain\n" + rows),
        {"time_unit": "us", "strain_unit": "microstrain"},
        "strain_history",
    )
    np.testing.assert_allclose(micro.values, -3e-6 * np.arange(20), rtol=1e-12)
    np.testing.assert_allclose(plain.values, micro.values, rtol=1e-12)
    speed = read_history(_write(tmp_path / "c.csv", "time_ms,velocity_mm_s\n" + rows), {"sign": -1}, "velocity_history")
    np.testing.assert_allclose(speed.values, 3e-3 * np.arange(20), rtol=1e-12)
    np.testing.assert_allclose(speed.time_s, 1e-3 * np.arange(20), rtol=1e-12)


@pytest.mark.parametrize(
    "key, text, spec, field, words",
    [
        ("strain_history", "time_us,strain_microstrain\n", {"strain_unit": "strain"}, "strain_unit", "contradicts"),
        ("strain_history", "time_us,strain_ue\n", {}, "file", "unknown unit 'ue'"),
        ("strain_history", "time_us,force_N\n", {}, "file", "as 'strain' or 'strain_<unit>'"),
        ("velocity_history", "time_us,velocity\n", {}, "velocity_unit", "names no unit of velocity"),
        (
            "strain_history",
            "time_us,strain_strain\n" + "".join(f"{k},0\n" for k in range(9)),
            {},
            "file",
            "zero throughout",
        ),
    ],
)
def test_each_bad_record_is_one_error_naming_its_key(tmp_path: Path, key, text, spec, field, words) -> None:
    with pytest.raises(HistoryError) as caught:
        read_history(_write(tmp_path / "r.csv", text), spec, key)
    assert caught.value.field == field and words in caught.value.reason, str(caught.value)


def test_first_pulse_of_a_half_sine_against_its_closed_form() -> None:
    """A compressive half-sine of 40 µs arriving at 50 µs, then a later reflection: the pulse is
    read between the crossings of 5 % of its crest, its arrival at half of it; its integral is the
    half-sine's over the part above 5 %, (2 A T / pi) cos(pi tau / T) with tau where sin = 0.05."""
    t = np.linspace(0.0, 300e-6, 300_001)
    duration, peak, threshold = 40e-6, -250e-6, 0.05
    signal = _half_sine(t, 50e-6, duration, peak) + _half_sine(t, 180e-6, duration, 0.8 * peak)
    pulse = first_pulse(t, signal, threshold)
    tau = duration * math.asin(threshold) / math.pi
    assert pulse.sign == -1
    # the arrival at half the crest: sin = 1/2 a sixth of the way through (half of the crest's
    # parabola, whose vertex is off by its quartic term, a few 1e-4: 2e-5 of the time)
    assert pulse.arrival_s == pytest.approx(50e-6 + duration / 6.0, rel=1e-4)
    # the bounds at 5 % of the crest's parabola (its vertex a few 1e-4 off): 1e-6 of the time
    assert pulse.end_s == pytest.approx(50e-6 + duration - tau, rel=1e-5)
    # the crest's parabola, on a half-sine: its quartic term alone, a few 1e-4
    assert pulse.peak == pytest.approx(peak, rel=5e-4)
    expected = 2.0 * peak * duration / math.pi * math.cos(math.pi * tau / duration)
    assert pulse.integral == pytest.approx(expected, rel=1e-5)


def test_the_peak_of_a_noisy_pulse_is_not_biased_by_its_noise() -> None:
    """1 % noise on a pulse of 80 samples: the largest sample overshoots the peak by over 1 % on
    average; the crest's parabola stays within 0.3 % of the clean pulse's own reading."""
    t = np.arange(-20e-6, 120e-6, 0.5e-6)
    clean = _half_sine(t, 40e-6, 40e-6, -80e-6)
    reference = first_pulse(t, clean, 0.05).peak
    rng = np.random.default_rng(7)
    peaks, largest = [], []
    for _ in range(200):
        noisy = clean + rng.normal(0.0, 0.8e-6, len(t))
        peaks.append(first_pulse(t, noisy, 0.05).peak)
        largest.append(noisy.min())
    assert np.mean(largest) / reference - 1.0 > 0.01
    assert abs(np.mean(peaks) / reference - 1.0) < 0.003


def test_a_record_shifted_and_scaled_is_aligned_and_its_error_is_the_scale() -> None:
    t = np.linspace(0.0, 200e-6, 4001)
    model = _half_sine(t, 48e-6, 35e-6, -100e-6)
    record_t = np.linspace(-20e-6, 150e-6, 341)
    record = 1.02 * _half_sine(record_t, 51e-6, 35e-6, -100e-6)
    result = compare_signals(record_t, record, t, model, 0.05)
    assert result.shift_s == pytest.approx(-3e-6, abs=2e-9)
    assert result.measured_pulse.arrival_s - result.model_pulse.arrival_s == pytest.approx(3e-6, abs=2e-9)
    # |1 - s| / s for a scale s, to the ns the record's 0.5 µs samples place its arrival to
    assert result.l2_error == pytest.approx(0.02 / 1.02, rel=1e-2)


# --- the configuration: one line per fault, before any job ------------------------------------


@pytest.fixture
def project_dir(tmp_path: Path) -> Path:
    """A copy of the project's config and schemas to break."""
    shutil.copytree(ROOT / "config", tmp_path / "config")
    shutil.copytree(ROOT / "workflow" / "schemas", tmp_path / "workflow" / "schemas")
    return tmp_path


def _refused(project_dir: Path, change: Callable[[dict], None]) -> str:
    case_file = project_dir / EXAMPLE
    document = yaml.safe_load(case_file.read_text())
    change(document)
    case_file.write_text(yaml.safe_dump(document, sort_keys=False))
    with pytest.raises(ConfigError) as caught:
        load_project(load_global_config(project_dir / "config" / "config.yaml"), root=project_dir)
    message = str(caught.value)
    assert "\n" not in message and message.startswith(f"{EXAMPLE}: "), message
    return message


def _record(document: dict) -> dict:
    return document["cases"][0]["measured"]["strain_history"]


def _parameter(document: dict, index: int = 0) -> dict:
    return document["calibrate"]["parameters"][index]


@pytest.mark.parametrize(
    "change, where, words",
    [
        (
            lambda d: _record(d).update(station_m=0.6),
            "case 'gauge_8mm': field 'measured.strain_history.station_m'",
            "0.6 m lies outside the rod [0, 0.5] m",
        ),
        (
            lambda d: _record(d).update(station_m=0.25, gauge_length_m=0.7),
            "field 'measured.strain_history.gauge_length_m'",
            "longer than the rod",
        ),
        (
            lambda d: _record(d).update(station_m=0.499),
            "field 'measured.strain_history.gauge_length_m'",
            "overhangs an end",
        ),
        (
            lambda d: _record(d).update(strain_unit="strain"),
            "field 'measured.strain_history.strain_unit'",
            "contradicts the header",
        ),
        (
            lambda d: _parameter(d).update(path="rod.material.youngs_modulus"),
            "field 'calibrate.parameters[0].path'",
            "names no setting: no key 'youngs_modulus' under 'rod.material'",
        ),
        (
            lambda d: _parameter(d).update(bounds=[-1.0e9, 2.3e11]),
            "field 'calibrate.parameters[0].bounds'",
            "not legal at rod.material.youngs_modulus_pa = -1e+09",
        ),
        (
            lambda d: _parameter(d, 1).update(bounds=[1.2, 0.9]),
            "field 'calibrate.parameters[1].bounds'",
            "the bounds must increase",
        ),
        (
            lambda d: (
                d["calibrate"].update(quantities=["strain_arrival_us"])
                or d["calibrate"]["parameters"].extend(
                    [
                        {"path": "impactor.mass_kg", "bounds": [1e-3, 1e-1], "source": "a guess"},
                        {"path": "rod.material.density_kg_m3", "bounds": [7.7e3, 7.9e3], "source": "steels"},
                        {"path": "rod.material.poisson_ratio", "bounds": [0.27, 0.31], "source": "steels"},
                    ]
                )
            ),
            "field 'calibrate.parameters'",
            "5 constants to fit from 4 measurement(s)",
        ),
        (
            lambda d: d["calibrate"].update(variants=["r10_l30"]),
            "field 'calibrate.variants[0]'",
            "'r10_l30' is no variant of set 'gauge_example'",
        ),
        (
            lambda d: _parameter(d).update(grid=[1.8e11, 2.0e11, 2.3e11]),
            "field 'calibrate.parameters[0].grid'",
            "a grid fits one constant, and 2 are fitted",
        ),
        (
            lambda d: d["calibrate"]["parameters"].pop(1) and _parameter(d).update(grid=[1.8e11, 2.0e11, 2.2e11]),
            "field 'calibrate.parameters[0].grid'",
            "the grid must run from the least bound to the largest",
        ),
        (
            lambda d: (
                d["calibrate"]["parameters"].pop(1) and _parameter(d).update(grid=[1.8e11, 2.1e11, 2.0e11, 2.3e11])
            ),
            "field 'calibrate.parameters[0].grid'",
            "the grid must increase",
        ),
        (
            lambda d: d["calibrate"].update(quantities=["peak_force_n"]),
            "field 'calibrate.quantities[0]'",
            "gives 'peak_force_n'",
        ),
        (
            lambda d: d["cases"][0]["measured"].update(
                velocity_history={"file": "example/gauge_8mm.synthetic.csv", "of": "far_end"}
            ),
            "field 'measured.velocity_history.file'",
            "as 'velocity' or 'velocity_<unit>'",
        ),
    ],
)
def test_a_bad_record_or_calibration_is_one_line_before_any_job(project_dir: Path, change, where, words) -> None:
    message = _refused(project_dir, change)
    assert where in message and words in message, message


def _rows(text: str) -> list[tuple[str, float]]:
    return [(t, float(v)) for t, v in (line.split(",") for line in text.strip().splitlines()[1:])]


def _noise_only(text: str) -> str:
    rng = np.random.default_rng(0)
    return "time_us,strain_microstrain\n" + "".join(f"{t},{rng.normal(0.0, 0.17)!r}\n" for t, _ in _rows(text))


def _negated(text: str) -> str:
    return "time_us,strain_microstrain\n" + "".join(f"{t},{-v!r}\n" for t, v in _rows(text))


def _after(start_us: float) -> Callable[[str], str]:
    return lambda text: (
        "time_us,strain_microstrain\n" + "".join(f"{t},{v!r}\n" for t, v in _rows(text) if float(t) >= start_us)
    )


@pytest.mark.parametrize(
    "rewrite, change, field, words",
    [
        # a record of noise alone, no pulse
        (_noise_only, None, "file", "no pulse above the record's noise"),
        # every strain negated, tension positive, and no sign: declared
        (_negated, None, "sign", "declare sign: -1"),
        # a header in strain over microstrain numbers: a peak of 1.7e7 microstrain
        (lambda t: t.replace("strain_microstrain", "strain_strain", 1), None, "file", "header's unit 'strain_strain'"),
        # a header in ms over microsecond numbers: the wave would reach the gauge after 55 ms
        (lambda t: t.replace("time_us", "time_ms", 1), None, "file", "header's unit 'time_ms'"),
        # the first sample inside the pulse: no pre-trigger
        (_after(56.5), None, "file", "pre-trigger"),
        # a thinning that keeps one row; an offset that swamps the times
        (None, lambda r: r.update(every=1000000), "every", "keeps 1 of the 215 rows"),
        (None, lambda r: r.update(time_offset_s=1.0e300), "time_offset_s", "swamps the times"),
        # a clock not started at the impact
        (None, lambda r: r.update(time_offset_s=1.0), "time_offset_s", "time zero must be the impact"),
    ],
)
def test_a_record_its_impact_cannot_give_is_one_line_naming_its_key(project_dir: Path, rewrite, change, field, words):
    """The faults a lab makes in a strain record by mistake, each refused before any job in one line
    naming the file, the case and the key at fault (rodimpact.analysis.record_checks)."""
    record = project_dir / "config" / "cases" / "example" / "gauge_8mm.synthetic.csv"
    if rewrite is not None:
        record.write_text(rewrite(record.read_text()))
    message = _refused(project_dir, lambda document: change(_record(document)) if change else None)
    assert f"case 'gauge_8mm': field 'measured.strain_history.{field}'" in message and words in message, message


def test_a_calibration_of_an_integer_setting_is_refused_naming_its_path(project_dir: Path) -> None:
    """``numerics.sem.max_contacts`` is legal at the bounds 30 and 80, not between them, where a
    fit's trials fall: refused before any job, not at every trial of the fit."""

    def change(document: dict) -> None:
        _parameter(document, 1).update(path="numerics.sem.max_contacts", bounds=[30, 80], unit="1")

    message = _refused(project_dir, change)
    assert "field 'calibrate.parameters[1].path'" in message and "not a real-valued constant" in message, message
    assert "max_contacts must be an integer" in message, message


def test_a_far_end_velocity_needs_a_free_far_end(project_dir: Path) -> None:
    """A velocity record of the far end of a rod whose far end is fixed: refused by name."""
    record = project_dir / "config" / "cases" / "example" / "far.csv"
    record.write_text("time_us,velocity_m_s\n" + "".join(f"{k},{0.01 * k}\n" for k in range(20)))

    def change(document: dict) -> None:
        document["cases"][0]["measured"]["velocity_history"] = {"file": "example/far.csv", "of": "far_end"}

    message = _refused(project_dir, change)
    assert "field 'measured.velocity_history.of'" in message and "rod.far_end: free" in message, message


def test_velocity_records_made_from_a_run_compare_to_it_within_their_noise(shipped_project, tmp_path: Path) -> None:
    """A free far end's velocity and the impactor's, recorded from the SEM's own run (with 1 %
    noise on the far end's): the far end's first pulse arrives, peaks and moves the end as the run
    says, within the record's stated uncertainties, and the impactor's record has no error."""
    from rodimpact.analysis.observations import observed
    from rodimpact.jobs.runner import run_case

    case = copy.deepcopy(shipped_project.cases["gauge_8mm"])
    case["rod"]["far_end"], case["outputs"] = "free", ["contact_force", "impactor_velocity", "far_end_velocity"]
    case.pop("gauges")
    result = run_case(case, "sem")
    series = {name: array for name, (array, _, _) in result.series(case["outputs"]).items()}
    t_us = np.arange(-20.0, 1e6 * series["time"][-1], 0.5)
    far = np.interp(1e-6 * t_us, series["time"], series["far_end_velocity"], left=0.0)
    noisy = far + np.random.default_rng(3).normal(0.0, 0.01 * np.max(np.abs(far)), len(t_us))
    far_file = _write(
        tmp_path / "far.csv",
        "time_us,velocity_m_s\n" + "".join(f"{a},{float(b)!r}\n" for a, b in zip(t_us, noisy, strict=True)),
    )
    spec = {"file": "far.csv", "of": "far_end", "threshold": 0.05}
    case["measured"] = {"velocity_history": spec, "source": "the run itself"}
    rows = {
        r.quantity: r
        for r in observed(
            case, series, result.summary(), {"velocity_history": read_history(far_file, spec, "velocity_history")}
        )
    }
    for quantity in ("far_end_arrival_us", "far_end_peak_velocity_m_s", "far_end_displacement_um"):
        row = rows[quantity]
        assert abs(row.computed - row.measured) < 3.0 * row.measured_sd, (quantity, row)
    assert rows["far_end_velocity_l2_pct"].error_pct < 3.0
    # the far end's pulse arrives after L/c (at half its crest: the force's rise on top)
    assert rows["far_end_arrival_us"].computed > 1e6 * 0.5 / math.sqrt(2.1e11 / 7800.0)
    own = np.interp(1e-6 * t_us, series["time"], series["impactor_velocity"], left=series["impactor_velocity"][0])
    own_file = _write(
        tmp_path / "own.csv",
        "time_us,velocity_m_s\n" + "".join(f"{a},{float(b)!r}\n" for a, b in zip(t_us, own, strict=True)),
    )
    spec = {"file": "own.csv", "of": "impactor"}
    case["measured"] = {"velocity_history": spec, "source": "the run itself"}
    rows = {
        r.quantity: r
        for r in observed(
            case, series, result.summary(), {"velocity_history": read_history(own_file, spec, "velocity_history")}
        )
    }
    assert rows["impactor_velocity_l2_pct"].error_pct < 0.1 and rows["impactor_velocity_max_pct"].error_pct < 0.5
