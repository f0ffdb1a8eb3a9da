"""Tests of rodimpact.storage.runs: HDF5 run files with provenance, written atomically."""

from __future__ import annotations

import json
import re
from datetime import datetime
from pathlib import Path
from typing import Any

import h5py
import numpy as np
import pytest

from rodimpact.storage import atomic, provenance, runs
from rodimpact.storage.runs import StoreError, read_run, read_summary, write_run

RTOL = 0.0  # float64 is stored losslessly: exact round trip expected
N = 6001  # > 4096 elements: exercises compression


def make_config() -> dict[str, Any]:
    return {
        "id": "steel_ball_on_rod",
        "impactor": {"radius_m": 0.0125, "mass_kg": 0.0641, "velocity_m_s": 1.0},
        "rod": {"length_m": 1.0, "diameter_m": 0.02, "material": "steel", "E_Pa": 2.1e11},
        "numerics": {"dt_s": 1e-7, "n_modes": 200, "stations_m": [0.0, 0.5, 1.0], "tol": None},
        "flags": {"damping": False},
        "label": "Stahl – Kugel",
    }


def make_series() -> dict[str, tuple[np.ndarray, str, str]]:
    t = np.linspace(0.0, 6e-4, N)
    force = 1.5e3 * np.clip(np.sin(np.pi * t / 2e-4), 0.0, None) ** 1.5 * (t < 2e-4)
    stations = np.column_stack([np.sin(k * 1e4 * t) * 1e-6 for k in range(1, 4)])
    return {
        "time": (t, "s", "time since first contact"),
        "contact_force": (force, "N", "contact force between impactor and rod end"),
        "approach": (np.cbrt(force) * 1e-6, "m", "Hertz approach of impactor and rod end"),
        "impactor_velocity": (1.0 - t * 10.0, "m/s", "impactor velocity"),
        "station_displacement": (stations, "m", "axial displacement at config stations"),
        "n_iterations": (np.arange(N), "1", "integer series stored as float64"),
    }


def make_summary(peaks: int = 2) -> dict[str, Any]:
    return {
        "contact_time_s": 2.0e-4,
        "peak_force_N": np.linspace(1.5e3, 1.2e3, peaks),
        "peak_time_s": np.linspace(1.0e-4, 1.6e-4, peaks),
        "rebound_velocity_m_s": -0.8125,
        "energy_error": 3.2e-9,
        "contact_start_s": [0.0],
        "contact_end_s": np.array([2.0e-4]),
        "n_contacts": 1,
        "success": True,
        "status": 0,
        "message": "The solver successfully reached the end of the integration interval. ✓",
        "n_steps": np.int64(6000),
    }


def write_good(path: Path, **overrides: Any) -> Path:
    kwargs: dict[str, Any] = {
        "config": make_config(),
        "method": "sem",
        "series": make_series(),
        "summary": make_summary(),
        "wall_time_s": 1.25,
        "code_version": "0.1.0+gabc1234",
    }
    kwargs.update(overrides)
    return write_run(path, **kwargs)


def leftovers(directory: Path) -> list[Path]:
    return sorted(p for p in directory.iterdir() if ".tmp" in p.name)


def test_round_trip(tmp_path: Path) -> None:
    path = tmp_path / "runs" / "nested" / "steel.h5"  # parent directories are created
    config, series, summary = make_config(), make_series(), make_summary()
    assert write_good(path, config=config, series=series, summary=summary) == path
    rec = read_run(path)

    assert rec.path == path
    assert rec.case_id == "steel_ball_on_rod"
    assert rec.method == "sem"
    assert rec.config == config
    assert rec.code_version == "0.1.0+gabc1234"
    assert rec.library_versions == provenance.library_versions()
    assert rec.wall_time_s == pytest.approx(1.25, rel=0, abs=0)
    created = datetime.fromisoformat(rec.created_utc)
    assert created.utcoffset() is not None and created.utcoffset().total_seconds() == 0

    assert list(rec.series) == list(series)  # insertion order kept, time first
    for name, (values, units, description) in series.items():
        got = rec.series[name]
        assert got.dtype == np.float64
        assert got.shape == np.shape(values)
        np.testing.assert_allclose(got, values, rtol=RTOL, atol=0.0)
        assert rec.units[name] == units
        assert rec.descriptions[name] == description

    assert set(rec.summary) == set(summary)
    for key in ("contact_time_s", "rebound_velocity_m_s", "energy_error"):
        assert type(rec.summary[key]) is float
        assert rec.summary[key] == pytest.approx(summary[key], rel=1e-15, abs=0.0)
    for key in ("peak_force_N", "peak_time_s", "contact_start_s", "contact_end_s"):
        assert isinstance(rec.summary[key], np.ndarray) and rec.summary[key].ndim == 1
        np.testing.assert_allclose(rec.summary[key], summary[key], rtol=RTOL, atol=0.0)
    assert rec.summary["n_contacts"] == 1 and type(rec.summary["n_contacts"]) is int
    assert rec.summary["n_steps"] == 6000 and type(rec.summary["n_steps"]) is int
    assert rec.summary["success"] is True
    assert rec.summary["status"] == 0
    assert rec.summary["message"] == summary["message"]


def test_schema_on_disk(tmp_path: Path) -> None:
    path = write_good(tmp_path / "run.h5", series={"time": (np.arange(10.0), "s", "t")})
    with h5py.File(path, "r") as h5:
        assert set(h5.attrs) == {
            "case_id", "method", "config_json", "config_sha256", "code_version",
            "library_versions", "wall_time_s", "created_utc", "schema_version", "data_sha256",
        }  # fmt: skip
        assert len(h5.attrs["data_sha256"]) == 64
        assert h5.attrs["schema_version"] == 1
        assert json.loads(h5.attrs["library_versions"]) == provenance.library_versions()
        assert h5.attrs["config_json"] == provenance.canonical_json(make_config())
        assert h5["time"].compression is None  # small datasets stay uncompressed
        assert len(h5["summary"]) == 0  # attributes only
    big = write_good(tmp_path / "big.h5")
    with h5py.File(big, "r") as h5:
        assert h5["contact_force"].compression == "gzip"
        assert h5["contact_force"].compression_opts == 4
        assert h5["contact_force"].shuffle
        assert h5["station_displacement"].shape == (N, 3)


def test_empty_peaks_and_single_sample(tmp_path: Path) -> None:
    path = write_good(
        tmp_path / "nocontact.h5",
        series={"time": (np.array([0.0]), "s", "t"), "contact_force": ([0.0], "N", "F")},
        summary=make_summary(peaks=0) | {"peak_force_N": [], "peak_time_s": []},
    )
    rec = read_run(path)
    for key in ("peak_force_N", "peak_time_s"):
        assert isinstance(rec.summary[key], np.ndarray)
        assert rec.summary[key].shape == (0,) and rec.summary[key].dtype == np.float64
    np.testing.assert_array_equal(rec.series["contact_force"], [0.0])


def test_read_summary_skips_series(tmp_path: Path) -> None:
    path = write_good(tmp_path / "run.h5")
    full, fast = read_run(path), read_summary(path)
    assert fast.series == {} and fast.units == {} and fast.descriptions == {}
    assert fast.config == full.config and fast.config_sha256 == full.config_sha256
    assert fast.summary.keys() == full.summary.keys()
    np.testing.assert_array_equal(fast.summary["peak_force_N"], full.summary["peak_force_N"])


def test_config_hash_and_tampering(tmp_path: Path) -> None:
    config = make_config()
    path = write_good(tmp_path / "run.h5", config=config)
    assert read_run(path).config_sha256 == provenance.config_sha256(config)

    with h5py.File(path, "r+") as h5:
        tampered = json.loads(h5.attrs["config_json"])
        tampered["rod"]["length_m"] = 2.0
        h5.attrs["config_json"] = provenance.canonical_json(tampered)
    with pytest.raises(StoreError, match="config_sha256"):
        read_run(path)
    with pytest.raises(StoreError, match="config_sha256"):
        read_summary(path)
    rec = read_run(path, verify=False)
    assert rec.config["rod"]["length_m"] == 2.0


def test_not_a_run_file(tmp_path: Path) -> None:
    text = tmp_path / "notes.h5"
    text.write_text("not hdf5")
    with pytest.raises(StoreError, match="not an HDF5 file"):
        read_run(text)
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as h5:
        h5["time"] = np.arange(3.0)
    with pytest.raises(StoreError, match="missing root attr"):
        read_run(other)
    with pytest.raises(FileNotFoundError):
        read_run(tmp_path / "absent.h5")
    path = write_good(tmp_path / "run.h5")
    with h5py.File(path, "r+") as h5:
        del h5["summary"].attrs["energy_error"]
    with pytest.raises(StoreError, match="energy_error"):
        read_run(path)


@pytest.mark.parametrize("module, where", [(runs, "_write_summary"), (atomic, "_fsync_file")])
def test_failed_write_leaves_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, module: Any, where: str) -> None:
    def boom(*args: Any, **kwargs: Any) -> None:
        raise OSError("disk full (simulated)")

    target = tmp_path / "out" / "run.h5"
    monkeypatch.setattr(module, where, boom)  # runs after all datasets are written
    with pytest.raises(OSError, match="simulated"):
        write_good(target)
    assert not target.exists()
    assert leftovers(target.parent) == []


@pytest.mark.parametrize("module, where", [(runs, "_write_summary"), (atomic, "_fsync_file")])
def test_failed_rewrite_keeps_existing_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, module: Any, where: str
) -> None:
    target = write_good(tmp_path / "run.h5")
    before = target.read_bytes()

    def boom(*args: Any, **kwargs: Any) -> None:
        raise KeyboardInterrupt  # also BaseException subclasses clean up

    monkeypatch.setattr(module, where, boom)
    with pytest.raises(KeyboardInterrupt):
        write_good(target, method="fem", wall_time_s=9.0)
    assert target.read_bytes() == before
    assert leftovers(tmp_path) == []
    monkeypatch.undo()
    assert read_run(target).method == "sem"


def test_temporary_file_name(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[str] = []
    real_fsync = atomic._fsync_file

    def spy(path: Path) -> None:
        seen.append(Path(path).name)
        real_fsync(path)

    monkeypatch.setattr(atomic, "_fsync_file", spy)
    write_good(tmp_path / "run.h5")
    assert re.fullmatch(r"run\.tmp-[0-9a-f]+\.h5", seen[0])
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize(
    ("overrides", "exc", "pattern"),
    [
        ({"series": {"force": (np.zeros(3), "N", "F")}}, ValueError, r"series.*'time'"),
        (
            {"series": {"time": (np.arange(3.0), "s", "t"), "contact_force": (np.zeros(4), "N", "F")}},
            ValueError,
            r"series\['contact_force'\].*len\(time\) = 3",
        ),
        (
            {"series": {"time": (np.arange(3.0), "s", "t"), "x": (np.zeros((3, 2, 2)), "m", "x")}},
            ValueError,
            r"series\['x'\]",
        ),
        ({"series": {"time": (np.zeros((3, 2)), "s", "t")}}, ValueError, r"series\['time'\]"),
        ({"series": {"time": (np.arange(3.0), "s")}}, TypeError, r"series\['time'\]"),
        ({"series": {"time": (np.arange(3.0), None, "t")}}, TypeError, r"series\['time'\]"),
        ({"series": {"time": (np.arange(3.0), "s", "t"), "a/b": ([1, 2, 3], "m", "x")}}, ValueError, "series name"),
        (
            {"summary": {k: v for k, v in make_summary().items() if k != "energy_error"}},
            ValueError,
            r"summary.*energy_error",
        ),
        ({"summary": make_summary() | {"peak_time_s": [1.0]}}, ValueError, r"summary.*peak_time_s"),
        ({"summary": make_summary() | {"contact_time_s": "long"}}, TypeError, r"summary\['contact_time_s'\]"),
        ({"summary": make_summary() | {"extra": None}}, TypeError, r"summary\['extra'\]"),
        ({"summary": make_summary() | {"grid": np.zeros((2, 2))}}, ValueError, r"summary\['grid'\]"),
        ({"config": {k: v for k, v in make_config().items() if k != "id"}}, ValueError, r"config.*'id'"),
        ({"config": make_config() | {"id": 7}}, ValueError, r"config\['id'\]"),
        ({"config": make_config() | {"dt": np.float64(1e-7)}}, TypeError, r"config.*\$\.dt"),
        ({"method": ""}, ValueError, "method"),
        ({"wall_time_s": float("nan")}, ValueError, "wall_time_s"),
        ({"wall_time_s": -1.0}, ValueError, "wall_time_s"),
        ({"code_version": ""}, ValueError, "code_version"),
        ({"summary": [("contact_time_s", 1.0)]}, TypeError, "summary"),
    ],
)  # fmt: skip
def test_validation_errors(tmp_path: Path, overrides: dict[str, Any], exc: type[Exception], pattern: str) -> None:
    target = tmp_path / "run.h5"
    with pytest.raises(exc, match=pattern):
        write_good(target, **overrides)
    assert list(tmp_path.iterdir()) == []  # nothing written, not even the directory content


def test_default_code_version(tmp_path: Path) -> None:
    path = write_good(tmp_path / "run.h5", code_version=None)
    assert read_summary(path).code_version == provenance.code_version()


def test_series_have_time_as_their_dimension_scale(tmp_path: Path) -> None:
    path = write_good(tmp_path / "run.h5")
    with h5py.File(path, "r") as h5:
        time = h5["time"]
        assert time.is_scale
        for name, dataset in h5.items():
            if not isinstance(dataset, h5py.Dataset) or name == "time":
                continue
            assert dataset.dims[0].label == "time" and dataset.dims[0][0] == time, name
            assert dataset.attrs["long_name"] == dataset.attrs["description"]
            if dataset.ndim == 2:
                assert dataset.dims[1].label == "station"
    assert read_run(path).series.keys() == make_series().keys()  # the scales are not series


# ---------------------------------------------------------------------------- files of runs


def _runs_file(path: Path, names: tuple[str, ...] = ("m~0.001", "m~0.002")) -> list[str]:
    """A file of runs: each name a run of its own case (ids differ), written as write_run takes it."""
    with runs.write_runs(path) as writer:
        return [
            writer.add(
                name,
                config={**make_config(), "id": f"sweep.{name}"},
                method="sem",
                series=make_series(),
                summary=make_summary(),
                wall_time_s=0.01,
                code_version="1.0+gabc1234",
            )
            for name in names
        ]


def test_a_file_of_runs_holds_each_run_whole_under_its_reference(tmp_path: Path) -> None:
    """write_runs: one group per run, each read back through ``file#name`` exactly as a run file
    of its own is (config, hashes, series, summary, dimension scales); run_references lists them
    in the order written, and a run file of its own as itself."""
    path = tmp_path / "part0.h5"
    references = _runs_file(path)
    assert references == runs.run_references(path) == [f"{path}#m~0.001", f"{path}#m~0.002"]
    alone = write_good(tmp_path / "alone.h5")
    assert runs.run_references(alone) == [str(alone)]
    with h5py.File(path, "r") as h5:
        assert h5.attrs["layout"] == runs.RUNS_LAYOUT and int(h5.attrs["runs"]) == 2
        assert h5["m~0.001/contact_force"].dims[0][0] == h5["m~0.001/time"]
    single = read_run(alone)
    for name, reference in zip(("m~0.001", "m~0.002"), references):
        record = read_run(reference)
        assert record.path == Path(reference) and record.case_id == f"sweep.{name}"
        assert record.summary.keys() == single.summary.keys() and record.data_sha256
        for series, values in single.series.items():
            np.testing.assert_allclose(record.series[series], values, rtol=RTOL, atol=0.0)
        assert read_summary(reference).series == {}


def test_a_file_of_runs_is_written_whole_or_not_at_all(tmp_path: Path) -> None:
    path = tmp_path / "part1.h5"
    with pytest.raises(RuntimeError, match="killed"):
        with runs.write_runs(path) as writer:
            writer.add("a", config=make_config(), method="sem", series=make_series(), summary=make_summary(),
                       wall_time_s=0.0)  # fmt: skip
            raise RuntimeError("killed after the first run")
    assert not path.exists() and leftovers(tmp_path) == []


@pytest.mark.parametrize("name", ["", "a/b", "a#b", ".", ".."])
def test_a_run_needs_a_name_that_can_name_it(tmp_path: Path, name: str) -> None:
    with pytest.raises(ValueError, match="cannot name a run"):
        _runs_file(tmp_path / "bad.h5", (name,))
    assert not (tmp_path / "bad.h5").exists()


def test_a_run_named_twice_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="already holds a run 'a'"):
        _runs_file(tmp_path / "twice.h5", ("a", "a"))


def test_a_changed_run_in_a_file_of_runs_is_named_and_its_file_marked(tmp_path: Path) -> None:
    """A run edited after it was written, or asked for by a name the file does not hold, is
    refused as the run (file#name); the file (the job's output) is marked out of date."""
    path = tmp_path / "part2.h5"
    references = _runs_file(path)
    with h5py.File(path, "r+") as h5:
        h5["m~0.002/contact_force"][0] += 1.0
    read_run(references[0])  # the other run is untouched
    with pytest.raises(runs.CorruptRun, match=re.escape(f"{path}#m~0.002: its content differs")) as raised:
        read_run(references[1])
    assert raised.value.marked and path.stat().st_mtime == 0
    with pytest.raises(runs.CorruptRun, match="no run 'm~0.003' in the file of runs"):
        read_run(f"{path}#m~0.003")


def test_many_runs_are_read_by_several_processes_in_order_as_one_reads_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """load_records with workers: the same records, in the same order, as one process reads; a
    damaged run among them still refuses the whole read, naming the run (a reader's share made
    small, so that a few runs take two readers)."""
    from rodimpact.present import inputs
    from rodimpact.present.inputs import load_records

    monkeypatch.setattr(inputs, "RUNS_PER_READER", 10)
    names = tuple(f"m~{i}" for i in range(27))
    series = {"time": (np.linspace(0.0, 1e-4, 5), "s", "time")}
    with runs.write_runs(tmp_path / "part0.h5") as writer:
        references = [
            writer.add(
                name,
                config={"id": f"s.{name}"},
                method="sem",
                series=series,
                summary=make_summary(),
                wall_time_s=0.01,
                code_version="1.0+gabc1234",
            )  # fmt: skip
            for name in names
        ]
    alone = load_records(references)
    shared = load_records(references, workers=2)
    assert [r.path for r in shared] == [r.path for r in alone] == [Path(r) for r in references]
    assert [r.case_id for r in shared] == [f"s.{name}" for name in names]
    assert [r.data_sha256 for r in shared] == [r.data_sha256 for r in alone]
    with h5py.File(tmp_path / "part0.h5", "r+") as h5:
        h5["m~20/time"][1] = 1.0
    with pytest.raises(runs.CorruptRun, match="m~20: its content differs"):
        load_records(references, workers=2)
