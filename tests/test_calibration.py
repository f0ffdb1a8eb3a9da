"""The contact law calibrated by the continuum: fem_axi's static indentation as a curve, the
curve file, and the runner handing it to the tabulated law.

- without a film the calibrated law is Hertz's within the static check's 2 %
  (tests/test_fem_axi.py: k within 2 % of (4/3) E* sqrt(R));
- with the text's film the thin-layer law's approach lies above the continuum's at every
  load of the impact (the series sum counts the substrate's Hertz compliance under a point
  load that the film in fact spreads), by 15 % to 35 % on row 1 (measured 19-31 %): the
  thin-layer law is outside its range there (a/h from 0.7 to 4);
- a run through the curve file agrees with the run through the law built from its data, and
  a curve that is another case's, missing, or edited is refused.
"""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest

from rodimpact.contact.hertz import HertzLaw, hertz_constant
from rodimpact.jobs.indentation import indentation_curve
from rodimpact.jobs.runner import run_case, run_to_file
from rodimpact.model.materials import Material
from rodimpact.storage.curves import read_contact_curve, write_contact_curve
from rodimpact.storage.faults import StoredFileError
from rodimpact.storage.runs import read_summary


@pytest.fixture(scope="module")
def cases(shipped_project):
    return shipped_project.cases


@pytest.fixture(scope="module")
def curves(shipped_project, shipped_config):
    settings = shipped_config["numerics"]["fem_axi"]
    return {
        case_id: indentation_curve(shipped_project.cases[case_id], settings)
        for case_id in ("ball_3.16mm-r10_l30_cal", "ball_3.16mm-r10_l30_film_cal")
    }


def test_calibrated_hertz_is_hertz_within_the_static_check(cases, curves):
    case = cases["ball_3.16mm-r10_l30_cal"]
    curve = curves[case["id"]].data
    imp = case["impactor"]
    law = HertzLaw(
        hertz_constant(
            imp["radius_m"], Material.from_mapping(imp["material"]), Material.from_mapping(case["rod"]["material"])
        )
    )
    hertz = np.array([law.approach(p) for p in curve["force_N"]])
    assert np.max(np.abs(curve["approach_m"] / hertz - 1.0)) < 0.02
    np.testing.assert_allclose(curve["law_approach_m"], hertz, rtol=1e-12)


def test_thin_layer_law_against_the_continuum(cases, curves):
    curve = curves["ball_3.16mm-r10_l30_film_cal"].data
    excess = curve["law_approach_m"] / curve["approach_m"] - 1.0
    assert np.all(excess > 0.15) and np.all(excess < 0.35)
    assert curves["ball_3.16mm-r10_l30_film_cal"].summary["analytic_law"] == "hertz_film"


def test_curve_file_round_trip_and_tamper(tmp_path, curves):
    curve = curves["ball_3.16mm-r10_l30_cal"]
    path = write_contact_curve(tmp_path / "curve.h5", curve)
    back = read_contact_curve(path)
    assert back.case_id == curve.case_id and back.summary == curve.summary
    for name, array in curve.data.items():
        np.testing.assert_array_equal(back.data[name], array)
    with h5py.File(path, "r+") as h5:
        h5["force_N"][3] *= 1.01
    with pytest.raises(StoredFileError, match="do not match their data_sha256"):
        read_contact_curve(path)


def test_runner_gives_the_tabulated_law_its_curve(tmp_path, cases, curves):
    case = cases["ball_3.16mm-r10_l30_film_cal"]
    path = write_contact_curve(tmp_path / "curve.h5", curves[case["id"]])
    run = run_to_file(case, "sem", tmp_path / "sem.h5", contact_curve=path)
    summary = read_summary(run).summary
    direct = run_case({**case, "contact": {**case["contact"], "curve": curves[case["id"]].law_curve()}}, "sem")
    assert summary["contact_time_s"] == pytest.approx(direct.contact_time_s, rel=1e-12)
    assert summary["contact_law"] == "tabulated" and 0.0 < summary["table_reach"] <= 1.0
    # the film lengthens the contact against the calibrated bare rod (measured 17.7 -> 28 us)
    bare = run_case(
        {
            **cases["ball_3.16mm-r10_l30_cal"],
            "contact": {
                **cases["ball_3.16mm-r10_l30_cal"]["contact"],
                "curve": curves["ball_3.16mm-r10_l30_cal"].law_curve(),
            },
        },
        "sem",
    )
    assert summary["contact_time_s"] > 1.3 * bare.contact_time_s
    with pytest.raises(ValueError, match="needs its curve file"):
        run_to_file(case, "sem", tmp_path / "none.h5")
    with pytest.raises(ValueError, match="is the curve of case"):
        run_to_file(cases["ball_4.75mm-r10_l30_film_cal"], "sem", tmp_path / "other.h5", contact_curve=path)
    with pytest.raises(ValueError, match="takes no curve"):
        run_to_file(cases["ball_3.16mm-r10_l30"], "sem", tmp_path / "hertz.h5", contact_curve=path)
    assert not (tmp_path / "none.h5").exists() and not math.isnan(summary["contact_time_s"])
