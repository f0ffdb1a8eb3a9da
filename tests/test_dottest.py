"""The small configuration in .test/ (run end to end by `make test`): valid, and made of the
shipped cases, so that it tests what users run and does not drift from it."""

from __future__ import annotations

from pathlib import Path

import yaml

from rodimpact.config.load import load_project

ROOT = Path(__file__).resolve().parents[1]
TEST = ROOT / ".test"


def _config(directory: Path) -> dict:
    return yaml.safe_load((directory / "config" / "config.yaml").read_text(encoding="utf-8"))


def test_the_small_configuration_is_valid_and_exercises_every_stage() -> None:
    config = _config(TEST)
    project = load_project(
        config, root=TEST, schema_dir=ROOT / "workflow" / "schemas", config_file=TEST / "config" / "config.yaml"
    )
    assert set(project.sets) >= {"model", "table2", "stress"}
    assert project.sweeps_in("table2")
    methods = {m for case in project.cases.values() for m in case["methods"]}
    assert methods == {"sem", "sem_paper", "fem1d", "fem_axi"}
    assert config["work_precision"]["cases"] and config["stability"]["map"]["methods"]


def test_its_cases_are_the_shipped_cases() -> None:
    shipped = load_project(_config(ROOT), root=ROOT)
    small = load_project(
        _config(TEST), root=TEST, schema_dir=ROOT / "workflow" / "schemas", config_file=TEST / "config" / "config.yaml"
    )
    for case_id, case in small.cases.items():
        assert case_id in shipped.cases, case_id
        for key in ("impactor", "rod", "contact", "measured", "published", "outputs", "stations"):
            assert case.get(key) == shipped.cases[case_id].get(key), (case_id, key)
    assert small.cases["model"]["methods"] == shipped.cases["model"]["methods"]


#: Where .test/config/config.yaml may differ from config/config.yaml (its header says why).
SMALLER = {
    ("materials",),
    ("work_precision", "cases"),
    ("work_precision", "timing"),
    ("work_precision", "methods"),
    ("stability", "map", "mass_kg"),
    ("stability", "map", "impedance_kg_s"),
    ("numerics", "fem_axi", "steps_per_contact"),
    ("numerics", "fem_axi", "elements_across"),
    # .test has no reading calibrated without the sensor (r10_l30_film_cal, r10_l30_cal)
    ("sensor", "film_table", "film_calibrated"),
    ("sensor", "film_table", "no_film_calibrated"),
    # the study's separate cases take minutes (fem_axi on the slowest Table 2 row): none in .test
    ("work_precision", "separate"),
    # a case's own methods and orders, for the cases .test sweeps only (checked below)
    ("work_precision", "per_case"),
    # smaller jobs for the sweeps: .test's forty-point sweep cut into several parts
    ("batch", "target_s"),
}


def _leaves(document: object, path: tuple = ()) -> dict:
    if isinstance(document, dict):
        return {k: v for key, value in document.items() for k, v in _leaves(value, (*path, key)).items()}
    return {path: document}


def test_its_settings_are_the_shipped_settings_but_smaller() -> None:
    shipped, small = _leaves(_config(ROOT)), _leaves(_config(TEST))
    differ = {p for p in shipped.keys() | small.keys() if shipped.get(p) != small.get(p)}
    assert {p for p in differ if not any(p[: len(s)] == s for s in SMALLER)} == set()
    levels = _config(TEST)["work_precision"]["methods"]
    assert all(
        spec["levels"] == _config(ROOT)["work_precision"]["methods"][m]["levels"][:3] for m, spec in levels.items()
    )
    # per_case: the shipped entries of exactly the cases .test sweeps, unchanged
    shipped_study, small_study = _config(ROOT)["work_precision"], _config(TEST)["work_precision"]
    swept = set(small_study["cases"]) & set(shipped_study.get("per_case", {}))
    assert small_study.get("per_case", {}) == {case: shipped_study["per_case"][case] for case in swept}
