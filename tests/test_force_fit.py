"""The contact force handed on: the Chebyshev closed form (rodimpact.analysis.force_fit) and
its export (rodimpact.present.forces): errors measured, not assumed."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from rodimpact.analysis.force_fit import MAX_DEGREE, fit_force
from rodimpact.present.forces import export_forces, read_force_json
from rodimpact.storage.runs import read_run, write_run

from helpers.paper import model_problem


def test_a_polynomial_force_is_reproduced_at_its_own_degree() -> None:
    t = np.linspace(0.0, 1e-4, 400)
    x = 2.0 * t / 1e-4 - 1.0
    force = 1e3 * (1.0 - x**2) * (1.0 + 0.3 * x**3)  # degree 5, zero at both ends
    fit = fit_force(t, force, [(0.0, 1e-4)], rel_tol=1e-9)
    (piece,) = fit.pieces
    assert len(piece.coefficients) - 1 == 5
    assert fit.max_abs_error_N == pytest.approx(0.0, abs=1e-9 * fit.peak_force_N)


def test_a_hertz_pulse_meets_the_target_and_the_error_is_the_measured_one() -> None:
    tau = 2e-4
    t = np.linspace(-5e-5, 3e-4, 3001)
    force = np.where((t >= 0) & (t <= tau), 2e3 * np.sin(np.pi * np.clip(t, 0, tau) / tau) ** 1.5, 0.0)
    for rel_tol in (1e-2, 1e-3):
        fit = fit_force(t, force, [(0.0, tau)], rel_tol=rel_tol)
        assert fit.max_rel_error <= rel_tol
        measured = np.max(np.abs(fit.evaluate(t) - force))
        assert fit.max_abs_error_N == pytest.approx(measured, rel=1e-12)
        assert np.all(fit.evaluate(t[(t < 0) | (t > tau)]) == 0.0)  # zero outside the contact


def test_two_contacts_are_two_pieces_with_no_force_between() -> None:
    t = np.linspace(0.0, 1e-3, 5001)

    def bump(a: float, b: float) -> np.ndarray:
        phase = np.clip((t - a) / (b - a), 0.0, 1.0)
        return np.where((t >= a) & (t <= b), np.sin(np.pi * phase) ** 1.5, 0.0)

    force = 1e3 * bump(0.0, 2e-4) + 4e2 * bump(6e-4, 7e-4)
    fit = fit_force(t, force, [(0.0, 2e-4), (6e-4, 7e-4)])
    assert len(fit.pieces) == 2
    between = (t > 2e-4) & (t < 6e-4)
    assert np.all(fit.evaluate(t[between]) == 0.0)
    assert fit.max_rel_error <= 0.01


def test_an_unreachable_target_is_reported_not_hidden() -> None:
    t = np.linspace(0.0, 1.0, 2001)
    force = np.where(t < 0.5, 1.0, 2.0) * (t > 0) * (t < 1)  # a jump: no polynomial fits it to 1e-6
    fit = fit_force(t, force, [(0.0, 1.0)], rel_tol=1e-6)
    assert len(fit.pieces[0].coefficients) - 1 == MAX_DEGREE
    assert fit.max_rel_error > 1e-6
    assert fit.max_abs_error_N == pytest.approx(np.max(np.abs(fit.evaluate(t) - force)), rel=1e-12)


@pytest.fixture
def model_run(tmp_path: Path) -> Path:
    """The model impact solved by the SEM, stored as the workflow stores it."""
    from rodimpact.solvers.sem.solver import solve_sem

    result = solve_sem(model_problem())
    series = {
        "time": (result.time, "s", "time since first contact"),
        "contact_force": (result.contact_force, "N", "contact force"),
    }
    return write_run(
        tmp_path / "runs" / "model" / "sem.h5",
        method="sem",
        config={"id": "model"},
        series=series,
        summary=result.summary(),
        wall_time_s=0.1,
        code_version="0.1.0+gdeadbeef",
    )


def test_the_export_carries_the_force_its_closed_form_and_its_provenance(model_run: Path, tmp_path: Path) -> None:
    csv, json_path, sidecar = tmp_path / "f" / "sem.csv", tmp_path / "f" / "sem.json", tmp_path / "f.provenance.json"
    export_forces([model_run], [csv], [json_path], provenance=sidecar)
    record = read_run(model_run)
    header = [line for line in csv.read_text(encoding="utf-8").splitlines() if line.startswith("#")]
    assert any(f"data_sha256: {record.data_sha256}" in line for line in header)
    assert any(f"source: {model_run}" in line for line in header)
    data = np.loadtxt(csv, delimiter=",", comments="#", skiprows=len(header) + 1)
    np.testing.assert_array_equal(data[:, 0], record.series["time"])
    np.testing.assert_array_equal(data[:, 1], record.series["contact_force"])
    stored = json.loads(json_path.read_text(encoding="utf-8"))
    assert stored["case_id"] == "model" and "T_k" in stored["fit"]["formula"]
    fit = read_force_json(json_path)
    error = np.max(np.abs(fit.evaluate(data[:, 0]) - data[:, 1]))  # from the two files alone
    assert error == pytest.approx(stored["fit"]["max_abs_error_N"], rel=1e-9)
    assert stored["fit"]["max_rel_error"] <= stored["fit"]["rel_tol"] == 0.01
    assert json.loads(sidecar.read_text(encoding="utf-8"))["inputs"][0]["data_sha256"] == record.data_sha256
