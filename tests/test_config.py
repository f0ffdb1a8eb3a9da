"""Tests of the configuration layer (rodimpact.config.load): shipped config, schemas, error messages.

Every test that changes a file works on a copy of config/ and workflow/schemas/ in tmp_path.
"""

from __future__ import annotations

import json
import math
import pickle
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest
import yaml
from jsonschema import Draft202012Validator

from rodimpact.config.load import METHODS, OUTPUTS, Project, load_global_config, load_project, registry_schema
from rodimpact.config.project import ConfigError
from rodimpact.solvers.registry import METHODS as REGISTRY

from helpers.repo import ROOT

SCHEMAS = ROOT / "workflow" / "schemas"
ROWS = ["ball_3.16mm", "ball_4.75mm", "ball_5.56mm", "ball_6.34mm", "ball_9.51mm", "ball_12.73mm"]
VARIANTS = {  # name -> (rod radius, rod length), m
    "r10_l30": (0.010, 0.0301),
    "r1_l301": (0.001, 0.301),
    "r1_l30": (0.001, 0.0301),
    "r10_l301": (0.010, 0.301),
    "r10_l30_film": (0.010, 0.0301),
    "r1_l301_film": (0.001, 0.301),
    "r1_l30_film": (0.001, 0.0301),
    "r10_l301_film": (0.010, 0.301),
    "r10_l30_sensor": (0.010, 0.0301),
    "r1_l30_sensor": (0.001, 0.0301),
    "r10_l30_sensor_cal": (0.010, 0.0301),
    "r1_l30_sensor_cal": (0.001, 0.0301),
    "r10_l30_film_cal": (0.010, 0.0301),
    "r10_l30_cal": (0.010, 0.0301),
}


# --------------------------------------------------------------------------- helpers


@pytest.fixture
def project_dir(tmp_path: Path) -> Path:
    """A copy of the project's config and schemas to break."""
    shutil.copytree(ROOT / "config", tmp_path / "config")
    shutil.copytree(SCHEMAS, tmp_path / "workflow" / "schemas")
    return tmp_path


def load(root: Path) -> Project:
    return load_project(load_global_config(root / "config" / "config.yaml"), root=root)


def edit(path: Path, change: Callable[[dict], None]) -> None:
    """Apply `change` to the YAML document in `path` (comments are lost: copies only)."""
    document = yaml.safe_load(path.read_text())
    change(document)
    path.write_text(yaml.safe_dump(document, sort_keys=False))


def error_of(root: Path) -> str:
    with pytest.raises(ConfigError) as info:
        load(root)
    return str(info.value)


@pytest.fixture(scope="module")
def shipped(shipped_project: Project) -> Project:
    """The shipped project (conftest.py), under the name these tests use."""
    return shipped_project


# --------------------------------------------------------------------------- shipped config


STRESS = [
    "microgram_fast",
    "heavy_slow",
    "thin_wire",
    "long_rod_heavy",
    "short_rod",
    "rubber_on_steel",
    "steel_on_rubber",
    "seconds_contact",
    "thornton_far_below",
    "thornton_far_above",
]


def test_shipped_config_loads_all_cases(shipped: Project) -> None:
    expected = ["model"] + [f"{row}-{variant}" for row in ROWS for variant in VARIANTS]
    # 1 + 6 rows x 14 variants, in file order (files sorted by name: model, plastic, smooth,
    # stress, table2, worked_example, worked_example_gauge)
    others = ("plastic", "smooth", "stress", "example", "gauge_example")
    assert [c for c in shipped.cases if shipped.cases[c]["set"] not in others] == expected
    assert shipped.sets == {
        "gauge_example": ["gauge_8mm", "gauge_12mm", "gauge_16mm", "gauge_20mm"],
        "example": ["ball_10mm", "ball_20mm"],
        "model": ["model"],
        "table2": expected[1:],
        "stress": STRESS,
        "smooth": ["linear_spring"],
        "plastic": ["thornton_past_yield"],
    }
    assert list(shipped.variants["table2"]) == list(VARIANTS)
    assert shipped.variants["model"] == {}


def test_model_case_is_table1_model_column(shipped: Project) -> None:
    case = shipped.cases["model"]
    assert (case["row"], case["variant"], case["set"]) == ("model", None, "model")
    assert case["source_file"] == "config/cases/model.yaml"
    assert case["impactor"] == {
        "mass_kg": 0.5,
        "radius_m": 0.01,
        "velocity_m_s": 1.0,
        "body": "cap",
        "material": {"name": "steel", "youngs_modulus_pa": 2.1e11, "poisson_ratio": 0.3, "density_kg_m3": 7800.0},
    }
    assert case["rod"]["length_m"] == 0.5
    assert case["rod"]["area_m2"] == 5.0e-5
    assert case["rod"]["radius_m"] is None
    assert case["rod"]["far_end"] == "fixed"
    assert case["methods"] == ["sem", "sem_paper", "fem1d", "fem_axi"]
    assert case["stations"] == [0.5]
    # every output but a gauge's strain and the far end's velocity (no gauge; a fixed far end)
    assert case["outputs"] == [o for o in OUTPUTS if o not in ("gauge_strain", "far_end_velocity")]
    assert case["measured"] is None
    assert case["published"]["fem_vs_sem"] == {"contact_time_difference_pct": 11.0, "extrema_difference_pct": 9.0}


def test_table2_variants_set_rod_geometry(shipped: Project) -> None:
    for variant, (radius, length) in VARIANTS.items():
        cases = shipped.cases_in("table2", variant)
        assert [case["row"] for case in cases] == ROWS
        for case in cases:
            assert case["id"] == f"{case['row']}-{variant}"
            assert case["rod"]["radius_m"] == radius
            assert case["rod"]["length_m"] == length
            assert case["rod"]["area_m2"] == pytest.approx(math.pi * radius**2, rel=1e-15)
            assert case["rod"]["material"]["name"] == "aluminium_table1"
            assert case["impactor"]["velocity_m_s"] == 0.3225
            assert case["impactor"]["body"] == "sphere"
            assert case["impactor"]["material"]["name"] == "steel"


def test_defaults_are_filled(shipped: Project) -> None:
    case = shipped.cases["ball_3.16mm-r1_l30"]
    assert case["rod"]["far_end"] == "fixed"
    assert case["methods"] == ["sem", "fem1d", "fem_axi"]
    assert case["outputs"] == ["contact_force"] and "field_grid" not in case
    # on the text's rod the row adds the strain field (its variant_outputs), with its grid's defaults
    waves = shipped.cases["ball_3.16mm-r10_l30"]
    assert waves["outputs"] == ["contact_force", "strain_field"]
    assert waves["field_grid"] == {"sections": 41, "samples_per_transit": 40, "round_trips_after": 1.0}
    assert case["stations"] == []
    assert case["numerics"] == {
        "sem": {
            "dt_s": None,
            "steps_per_contact": None,
            "max_time_factor": 100.0,
            "max_contacts": 50,
            "tolerance": 1e-6,
            "energy_tolerance": 0.01,
            "max_steps": 5_000_000,
        },
        "fem1d": {
            "dt_s": None,
            "steps_per_contact": 2000,
            "max_time_factor": 100.0,
            "max_contacts": 50,
            "element": "P2",
            "elements": None,
            "points_per_wavelength": 200.0,
        },
        "fem_axi": {
            "dt_s": None,
            "steps_per_contact": 300,
            "max_time_factor": 100.0,
            "max_contacts": 50,
            "element": "P2",
            "elements_across": 10,
            "contact_extent": 1.5,
            "continuum_diameters": 5.0,
            "film_layers": 4,
            "cap_height": 1.0,
            "plastic_extent": 2.0,
        },
    }
    assert shipped.cases["model"]["numerics"]["sem_paper"]["steps_per_contact"] == 20000
    assert case["measured"]["source"].startswith("Table 2")
    assert case["published"]["source"].startswith("Table 2")


def test_resolved_cases_are_plain_json(shipped: Project) -> None:
    for case in shipped.cases.values():
        assert json.loads(json.dumps(case)) == case  # no tuples, numpy, NaN
    assert isinstance(shipped.cases["model"]["published"]["fem_vs_sem"]["extrema_difference_pct"], float)


def test_cases_in_rejects_unknown_set_and_variant(shipped: Project) -> None:
    assert len(shipped.cases_in("table2")) == 6 * len(VARIANTS)
    with pytest.raises(KeyError, match="unknown case set 'tabel2'"):
        shipped.cases_in("tabel2")
    with pytest.raises(KeyError, match="unknown variant 'r5' of case set 'table2'"):
        shipped.cases_in("table2", "r5")


def test_global_config_defaults_are_filled(tmp_path: Path) -> None:
    (tmp_path / "config.yaml").write_text("targets: {sets: [model]}\n")
    config = load_global_config(tmp_path / "config.yaml", schema_dir=SCHEMAS)
    assert config["cases_dir"] == "config/cases"
    assert config["materials"] == "config/materials.yaml"
    assert config["numerics"]["sem"] == {
        "steps_per_contact": None,
        "tolerance": 1e-6,
        "dt_s": None,
        "max_time_factor": 100.0,
        "max_contacts": 50,
        "energy_tolerance": 0.01,
        "max_steps": 5_000_000,
    }
    assert config["numerics"]["fem_axi"]["elements_across"] == 10
    assert config["numerics"]["sem_paper"]["steps_per_contact"] == 20000


_EXTRA = (
    "cases:\n"
    "  - id: steel_ball\n"
    "    impactor: {mass_kg: 0.01, radius_m: 0.005, velocity_m_s: 2.0, material: steel}\n"
    "    rod: {length_m: 1.0, radius_m: 0.002, material: steel}\n"
)


def test_a_sets_compare_options_are_read_and_checked(project_dir: Path, shipped: Project) -> None:
    assert shipped.compare["table2"] == {
        "x": "mass",
        "title": "Table 2",
        "reference": "Belyaev, Shurpatov and Ma (2018)",
    }
    assert "model" not in shipped.compare  # a set with no compare block: the defaults
    extra = project_dir / "config" / "cases" / "extra.yaml"
    extra.write_text("set: table2\ncompare: {x: velocity}\n" + _EXTRA)
    assert error_of(project_dir) == (
        "config/cases/table2.yaml: field 'compare': set 'table2' is compared differently in another file"
    )
    extra.write_text("compare: {x: speed}\n" + _EXTRA)
    assert "extra.yaml: field 'compare.x'" in error_of(project_dir)


def test_a_variant_name_is_unique_over_all_sets(project_dir: Path) -> None:
    (project_dir / "config" / "cases" / "extra.yaml").write_text(
        "variants: {r10_l30: {description: a long rod, source: none, rod: {length_m: 2.0}}}\n" + _EXTRA
    )
    assert error_of(project_dir) == (
        "config/cases/table2.yaml: field 'variants.r10_l30': variant name already used by "
        "case set 'extra'; a variant's name is unique over all sets"
    )


def test_the_film_table_is_one_sets(project_dir: Path) -> None:
    (project_dir / "config" / "cases" / "extra.yaml").write_text(
        "variants: {long: {description: a long rod, source: none, rod: {length_m: 2.0}}}\n" + _EXTRA
    )
    edit(project_dir / "config/config.yaml", lambda d: d["sensor"]["film_table"].update(no_film="long"))
    assert error_of(project_dir).startswith(
        "config/config.yaml: field 'sensor.film_table': the readings are of several case sets (extra, table2)"
    )
    edit(project_dir / "config/config.yaml", lambda d: d["sensor"]["film_table"].update(no_film="short"))
    assert "field 'sensor.film_table.no_film': unknown reading 'short'" in error_of(project_dir)


def test_new_case_file_is_picked_up(project_dir: Path) -> None:
    (project_dir / "config" / "cases" / "extra.yaml").write_text(
        "cases:\n"
        "  - id: soft_ball\n"
        "    impactor: {mass_kg: 0.01, radius_m: 0.005, velocity_m_s: 2.0, material: steel}\n"
        "    rod: {length_m: 1.0, radius_m: 0.002, far_end: free,\n"
        "          material: {name: rubber, youngs_modulus_pa: 1.0e7, poisson_ratio: 0.49, density_kg_m3: 1100}}\n"
    )
    project = load(project_dir)
    assert project.sets["extra"] == ["soft_ball"]  # set = file stem by default
    case = project.cases["soft_ball"]
    assert list(project.cases)[:2] == ["soft_ball", "model"]  # files in name order
    assert case["rod"]["far_end"] == "free"
    assert case["rod"]["material"] == {
        "name": "rubber",
        "youngs_modulus_pa": 1.0e7,
        "poisson_ratio": 0.49,
        "density_kg_m3": 1100.0,
    }
    assert case["source_file"] == "config/cases/extra.yaml"


def test_case_numerics_override_global(project_dir: Path) -> None:
    edit(
        project_dir / "config/cases/model.yaml",
        lambda d: d["cases"][0].update(numerics={"sem_paper": {"dt_s": 1e-8}, "sem": {"max_contacts": 3}}),
    )
    numerics = load(project_dir).cases["model"]["numerics"]
    assert numerics["sem"] == {
        "dt_s": None,
        "steps_per_contact": None,
        "max_time_factor": 100.0,
        "max_contacts": 3,
        "tolerance": 1e-6,
        "energy_tolerance": 0.01,
        "max_steps": 5_000_000,
    }
    assert numerics["sem_paper"] == {
        "dt_s": 1e-8,
        "steps_per_contact": 20000,
        "max_time_factor": 100.0,
        "max_contacts": 50,
        "energy_tolerance": 0.01,
        "max_steps": 5_000_000,
        "allow_unstable": False,
    }


def test_case_variants_list_selects_variants(project_dir: Path) -> None:
    # (without the row's strain field on r10_l30, a variant it is no longer expanded over)
    edit(
        project_dir / "config/cases/table2.yaml",
        lambda d: d["cases"][0].update(variants=["r1_l301"]) or d["cases"][0].pop("variant_outputs"),
    )
    # the work-precision sweep names ball_3.16mm-r1_l30, which this edit removes
    assert "unknown case 'ball_3.16mm-r1_l30'" in error_of(project_dir)
    edit(project_dir / "config/config.yaml", lambda d: d.pop("work_precision"))
    # ... and the film's force figure names it on r10_l30
    assert "field 'sensor.film_force': no case 'ball_3.16mm' on the reading 'r10_l30'" in error_of(project_dir)
    edit(project_dir / "config/config.yaml", lambda d: d["sensor"].pop("film_force"))
    project = load(project_dir)
    assert [c["id"] for c in project.cases_in("table2")][:2] == ["ball_3.16mm-r1_l301", "ball_4.75mm-r10_l30"]
    assert len(project.cases_in("table2")) == 6 * len(VARIANTS) - (len(VARIANTS) - 1)


# --------------------------------------------------------------------------- schemas


def _schema(name: str) -> dict:
    return yaml.safe_load((SCHEMAS / name).read_text())


def test_known_lists_match_the_schemas() -> None:
    assert "method" not in _schema("config.schema.yaml")["$defs"]  # generated from the registry
    assert tuple(registry_schema()["config.schema.yaml"]["$defs"]["method"]["enum"]) == METHODS == tuple(REGISTRY)
    assert tuple(_schema("cases.schema.yaml")["$defs"]["output"]["enum"]) == OUTPUTS


def test_numerics_schema_is_the_options_declaration() -> None:
    """Each method's numerics block in the schema is generated from its options class: the
    settings, their defaults and their bounds are declared once."""
    defs = registry_schema()["config.schema.yaml"]["$defs"]
    for name, spec in REGISTRY.items():
        properties = defs[f"numerics_{name}"]["properties"]
        assert tuple(properties) == spec.options.names()
        assert {key: value["default"] for key, value in properties.items()} == spec.options.defaults()
    assert defs["numerics_sem"]["properties"]["tolerance"]["exclusiveMaximum"] == 1


def _nodes(schema: dict):
    """Every (sub)schema of `schema`, through the keywords our schemas use."""
    yield schema
    for keyword in ("properties", "$defs"):
        for sub in schema.get(keyword, {}).values():
            yield from _nodes(sub)
    for keyword in ("items", "additionalProperties", "propertyNames", "not"):
        if isinstance(schema.get(keyword), dict):
            yield from _nodes(schema[keyword])


@pytest.mark.parametrize("name", ["config.schema.yaml", "cases.schema.yaml", "materials.schema.yaml"])
def test_schemas_are_valid_documented_and_closed(name: str) -> None:
    schema = _schema(name)
    Draft202012Validator.check_schema(schema)
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert all("description" in sub for sub in schema["$defs"].values())
    for node in _nodes(schema):
        for prop, sub in node.get("properties", {}).items():
            # a bare {$ref: ...} is documented by the described $defs entry it points to
            assert "description" in sub or set(sub) == {"$ref"}, f"{name}: property {prop!r} undocumented"
        if "properties" in node:
            # closed; or keys limited by propertyNames; or extends (by $ref) a closed schema,
            # only adding constraints or defaults
            closed = node.get("additionalProperties") is False or "propertyNames" in node or "$ref" in node
            assert closed, f"{name}: {node} is open"


def _broken_cases() -> list[tuple[str, dict]]:
    """Each shipped case file's cases (its defaults merged under each), as written and broken."""
    from rodimpact.config.schema import deep_merge

    cases = []
    for path in sorted((ROOT / "config" / "cases").glob("*.yaml")):
        document = yaml.safe_load(path.read_text())
        for entry in document["cases"]:
            case = deep_merge(document.get("defaults", {}), entry)
            cases.append((f"{path.name}:{case['id']}", case))
    breaks = {
        "mass": lambda c: c.setdefault("impactor", {}).update(mass_kg=-1),
        "unknown": lambda c: c.update(colour="red"),
        "method": lambda c: c.update(methods=["sem", "nope"]),
        "stations": lambda c: c.update(stations=[0.5, 2]),
        "outputs": lambda c: c.update(outputs=["contact_force", "contact_force"]),
        "variant_outputs": lambda c: c.update(variant_outputs={"Bad Name": ["contact_force"]}),
        "no_id": lambda c: c.pop("id"),
        "rod": lambda c: c.update(rod="steel"),
        "numerics": lambda c: c.update(numerics={"sem": {"steps_per_contact": "many"}}),
    }
    broken = []
    for name, case in cases[::3]:
        for what, change in breaks.items():
            changed = json.loads(json.dumps(case))
            change(changed)
            broken.append((f"{name}:{what}", changed))
    return cases + broken


def test_the_inlined_schema_finds_what_its_references_find() -> None:
    """A check inlines each ``$ref`` of its schema (``Schemas._inline``): on every shipped case
    (defaults merged) and on each broken in several ways, it reports the same first problem and
    fills in the same defaults as the schema checked through its references."""
    from rodimpact.config import schema as checker
    from rodimpact.config.load import _load_schemas

    schemas = _load_schemas(SCHEMAS, ROOT)
    referencing = checker._FillingValidator(
        {"$ref": f"{schemas._uris['cases.schema.yaml']}#/$defs/resolved_case"}, registry=schemas._registry
    )
    problems = 0
    for name, case in _broken_cases():
        mine, theirs = json.loads(json.dumps(case)), json.loads(json.dumps(case))
        found = schemas.first_problem(mine, "cases.schema.yaml", "/$defs/resolved_case", fill_defaults=True)
        expected = [checker._to_problem(error) for error in referencing.iter_errors(theirs)]
        expected = min(expected, key=lambda p: checker._position(theirs, p.path)) if expected else None
        assert found == expected, name
        assert mine == theirs, name  # the same defaults filled in
        problems += found is not None
    assert problems >= 9 * 5  # the broken cases do break


def test_a_recursive_schema_reference_is_refused(tmp_path: Path) -> None:
    from rodimpact.config.schema import Schemas

    shutil.copytree(SCHEMAS, tmp_path / "schemas")
    path = tmp_path / "schemas" / "materials.schema.yaml"
    schema = yaml.safe_load(path.read_text())
    schema["$defs"]["node"] = {"type": "object", "properties": {"next": {"$ref": "#/$defs/node"}}}
    path.write_text(yaml.safe_dump(schema))
    with pytest.raises(ValueError, match="recursive"):
        Schemas(tmp_path / "schemas").first_problem({}, "materials.schema.yaml", "/$defs/node")


# --------------------------------------------------------------------------- malformed input

MODEL = "config/cases/model.yaml"
TABLE2 = "config/cases/table2.yaml"


def _set(path: str, *keys_and_value):
    """An edit setting document[k1][k2]...= value (a key of None deletes)."""
    *keys, last, value = keys_and_value

    def change(document: dict) -> None:
        node = document
        for key in keys:
            node = node[key]
        if value is None:
            del node[last]
        else:
            node[last] = value

    return path, change


def _both(first, second):
    """Two edits of one file, in turn."""
    (path, apply_first), (other, apply_second) = first, second
    assert path == other

    def change(document: dict) -> None:
        apply_first(document)
        apply_second(document)

    return path, change


def _rename(path: str, keys: tuple, old: str, new: str):
    def change(document: dict) -> None:
        node = document
        for key in keys:
            node = node[key]
        node[new] = node.pop(old)

    return path, change


INLINE_STEEL = {"youngs_modulus_pa": 2.1e11, "poisson_ratio": 0.3, "density_kg_m3": 7800.0}
#: The yielding variants of the materials file, as a message lists them.
YIELDING = "steel_ball_yielding, aluminium_rod_yielding, pvdf_yielding, cyanoacrylate_yielding, silver_ink_yielding"
THORNTON = {"law": "thornton"}

MALFORMED = {
    "missing mass": (
        _set(TABLE2, "cases", 0, "impactor", "mass_kg", None),
        f"{TABLE2}: case 'ball_3.16mm-r10_l30': field 'impactor.mass_kg': missing required field",
    ),
    "mass is text": (
        _set(TABLE2, "cases", 0, "impactor", "mass_kg", "abc"),
        f"{TABLE2}: case 'ball_3.16mm': field 'impactor.mass_kg': must be a number, got string 'abc'",
    ),
    "negative mass": (
        _set(TABLE2, "cases", 0, "impactor", "mass_kg", -0.13),
        f"{TABLE2}: case 'ball_3.16mm': field 'impactor.mass_kg': must be > 0, got -0.13",
    ),
    "zero rod length": (
        _set(MODEL, "cases", 0, "rod", "length_m", 0),
        f"{MODEL}: case 'model': field 'rod.length_m': must be > 0, got 0",
    ),
    "non-positive Young's modulus inline": (
        _set(MODEL, "cases", 0, "impactor", "material", {**INLINE_STEEL, "youngs_modulus_pa": -2.1e11}),
        f"{MODEL}: case 'model': field 'impactor.material.youngs_modulus_pa': must be > 0, got -210000000000.0",
    ),
    "Poisson 0.5": (
        _set("config/materials.yaml", "materials", "steel", "poisson_ratio", 0.5),
        "config/materials.yaml: field 'materials.steel.poisson_ratio': must be < 0.5, got 0.5",
    ),
    "Poisson -1.2 inline": (
        _set(MODEL, "cases", 0, "rod", "material", {**INLINE_STEEL, "poisson_ratio": -1.2}),
        f"{MODEL}: case 'model': field 'rod.material.poisson_ratio': must be > -1, got -1.2",
    ),
    "inline material incomplete": (
        _set(MODEL, "cases", 0, "rod", "material", {"youngs_modulus_pa": 2.1e11, "poisson_ratio": 0.3}),
        f"{MODEL}: case 'model': field 'rod.material.density_kg_m3': missing required field",
    ),
    "unknown method": (
        _set(MODEL, "cases", 0, "methods", ["sem", "fem2d"]),
        f"{MODEL}: case 'model': field 'methods[1]': unknown method 'fem2d'; known: sem, sem_paper, fem1d, fem_axi",
    ),
    "repeated method": (
        _set(MODEL, "cases", 0, "methods", ["sem", "sem"]),
        f"{MODEL}: case 'model': field 'methods': items must be unique; 'sem' appears more than once",
    ),
    "no method": (
        _set(MODEL, "cases", 0, "methods", []),
        f"{MODEL}: case 'model': field 'methods': must not be empty",
    ),
    "unknown output": (
        _set(MODEL, "cases", 0, "outputs", ["contact_force", "stress"]),
        f"{MODEL}: case 'model': field 'outputs[1]': unknown output 'stress'; known: " + ", ".join(OUTPUTS),
    ),
    "unknown numerics method": (
        _set(MODEL, "cases", 0, "numerics", {"fem": {"dt_s": 1e-9}}),
        f"{MODEL}: case 'model': field 'numerics.fem': unknown method 'fem'; known: sem, sem_paper, fem1d, fem_axi",
    ),
    "numerics too few steps": (
        _set(MODEL, "cases", 0, "numerics", {"sem": {"steps_per_contact": 5}}),
        f"{MODEL}: case 'model': field 'numerics.sem.steps_per_contact': must be >= 10, got 5",
    ),
    "unknown variant": (
        _set(TABLE2, "cases", 0, "variants", ["r10_l30", "r5_l30"]),
        f"{TABLE2}: case 'ball_3.16mm': field 'variants[1]': unknown variant 'r5_l30'; "
        "declared: " + ", ".join(VARIANTS),
    ),
    "variant without description": (
        _set(TABLE2, "variants", "r1_l30", "description", None),
        f"{TABLE2}: field 'variants.r1_l30.description': missing required field",
    ),
    "unknown material name": (
        _set(MODEL, "cases", 0, "rod", "material", "steal"),
        f"{MODEL}: case 'model': field 'rod.material': unknown material 'steal'; known: steel, "
        "aluminium_table1, rubber, pvdf, silver_ink, cyanoacrylate, " + YIELDING,
    ),
    "unknown contact law": (
        _set(TABLE2, "variants", "r10_l30_film", "contact", "law", "hertz_flim"),
        f"{TABLE2}: field 'variants.r10_l30_film.contact.law': unknown contact law 'hertz_flim'; "
        "known: hertz, hertz_film, hertz_stack, tabulated, spring, thornton",
    ),
    "negative film thickness": (
        _set(TABLE2, "variants", "r10_l30_film", "contact", "film", "thickness_m", -2.8e-5),
        f"{TABLE2}: field 'variants.r10_l30_film.contact.film.thickness_m': must be > 0, got -2.8e-05",
    ),
    "unknown film material": (
        _set(TABLE2, "variants", "r10_l30_film", "contact", "film", "material", "pvfd"),
        f"{TABLE2}: case 'ball_3.16mm-r10_l30_film': field 'contact.film.material': unknown material 'pvfd'; "
        "known: steel, aluminium_table1, rubber, pvdf, silver_ink, cyanoacrylate, " + YIELDING,
    ),
    "film on the hertz law": (
        _set(TABLE2, "variants", "r10_l30_film", "contact", "law", "hertz"),
        f"{TABLE2}: case 'ball_3.16mm-r10_l30_film': field 'contact.film': the hertz law takes no 'film'; laws "
        "that take it: hertz_film, tabulated",
    ),
    "tabulated law on fem_axi": (
        _set(TABLE2, "variants", "r10_l30_cal", "methods", ["sem", "fem_axi"]),
        f"{TABLE2}: case 'ball_3.16mm-r10_l30_cal': field 'methods[1]': method 'fem_axi' resolves the contact in "
        "the continuum and cannot take the tabulated law; laws it can take: hertz, hertz_film, hertz_stack",
    ),
    "film range without its nominal": (
        _set(TABLE2, "variants", "r10_l30_film", "contact", "film", "thickness_range_m", [3e-5, 4e-5]),
        f"{TABLE2}: case 'ball_3.16mm-r10_l30_film': field 'contact.film.thickness_range_m': the thickness 2.8e-05 m "
        "must lie inside a non-empty range, got [3e-05, 4e-05]",
    ),
    "yield stress not positive": (
        _set("config/materials.yaml", "materials", "pvdf_yielding", "yield_stress_pa", 0),
        "config/materials.yaml: field 'materials.pvdf_yielding.yield_stress_pa': must be > 0, got 0",
    ),
    "hardening modulus above Young's": (
        _set("config/materials.yaml", "materials", "aluminium_rod_yielding", "hardening_modulus_pa", 8.0e10),
        "config/materials.yaml: field 'materials.aluminium_rod_yielding.hardening_modulus_pa': must be >= 0 and "
        "below Young's modulus 7.342e+10 Pa, got 80000000000.0",
    ),
    "hardening modulus without a yield stress inline": (
        _set(MODEL, "cases", 0, "rod", "material", {**INLINE_STEEL, "hardening_modulus_pa": 1e9}),
        f"{MODEL}: case 'model': field 'rod.material.hardening_modulus_pa': needs a yield_stress_pa: a material "
        "without one stays elastic",
    ),
    "thornton without a limiting pressure": (
        _set(MODEL, "cases", 0, "contact", THORNTON),
        f"{MODEL}: case 'model': field 'contact.limiting_pressure_pa': missing; the thornton law needs it, or a "
        "yield_stress_pa in the impactor's or the rod's material",
    ),
    "thornton limiting pressure below first yield": (
        _both(
            _set(MODEL, "cases", 0, "contact", {**THORNTON, "limiting_pressure_pa": 1.0e9}),
            _set(MODEL, "cases", 0, "rod", "material", "steel_ball_yielding"),
        ),
        f"{MODEL}: case 'model': field 'contact.limiting_pressure_pa': 1e+09 Pa lies below what the contact "
        "reaches elastically: Hertz's peak pressure first yields the softer material at 1.6 x its yield stress "
        "2.03e+09 Pa = 3.248e+09 Pa",
    ),
    "thornton on fem_axi": (
        _set(MODEL, "cases", 0, "contact", {**THORNTON, "limiting_pressure_pa": 4.0e9}),
        f"{MODEL}: case 'model': field 'methods[3]': method 'fem_axi' cannot carry the memory of the thornton law "
        "(its largest approach and the dent it leaves); methods that can: sem, sem_paper, fem1d",
    ),
    "both area and radius": (
        _set(MODEL, "cases", 0, "rod", "radius_m", 0.004),
        f"{MODEL}: case 'model': field 'rod': exactly one of 'area_m2' and 'radius_m' must be given, got both",
    ),
    "neither area nor radius": (
        _set(MODEL, "cases", 0, "rod", "area_m2", None),
        f"{MODEL}: case 'model': field 'rod': exactly one of 'area_m2' and 'radius_m' must be given, got neither",
    ),
    "typo mas_kg": (
        _rename(TABLE2, ("cases", 0, "impactor"), "mass_kg", "mas_kg"),
        f"{TABLE2}: case 'ball_3.16mm': field 'impactor.mas_kg': unknown field (did you mean 'mass_kg'?); "
        "allowed: mass_kg, radius_m, velocity_m_s, material, body",
    ),
    "far end clamped": (
        _set(MODEL, "cases", 0, "rod", "far_end", "clamped"),
        f"{MODEL}: case 'model': field 'rod.far_end': unknown far-end condition 'clamped'; known: fixed, free",
    ),
    "id with a dash": (
        _set(MODEL, "cases", 0, "id", "model-1"),
        f"{MODEL}: field 'cases[0].id': must be a name of letters, digits, '_' and '.' that starts with a letter "
        "or digit, got 'model-1'",
    ),
    "case without id": (
        _set(MODEL, "cases", 0, "id", None),
        f"{MODEL}: field 'cases[0].id': missing required field",
    ),
    "id in defaults": (
        _set(TABLE2, "defaults", "id", "x"),
        f"{TABLE2}: field 'defaults.id': is not allowed here",
    ),
    "no cases": (
        _set(MODEL, "cases", []),
        f"{MODEL}: field 'cases': must not be empty",
    ),
    "measurement without source": (
        _set(TABLE2, "defaults", "measured", "source", None),
        f"{TABLE2}: case 'ball_3.16mm-r10_l30': field 'measured.source': missing required field",
    ),
    "published error negative": (
        _set(TABLE2, "cases", 2, "published", "fem", "error_pct", -49.42),
        f"{TABLE2}: case 'ball_5.56mm': field 'published.fem.error_pct': must be >= 0, got -49.42",
    ),
    "not a number": (
        _set(MODEL, "cases", 0, "impactor", "velocity_m_s", float("inf")),
        f"{MODEL}: case 'model': field 'impactor.velocity_m_s': must be a finite number, got inf",
    ),
    "unknown target set": (
        _set("config/config.yaml", "targets", "sets", ["model", "tabel2"]),
        "config/config.yaml: field 'targets.sets[1]': unknown case set 'tabel2'; known: model, plastic, smooth, "
        "stress, table2, example, gauge_example",
    ),
    "sensor band of a reading without a calibrated stack": (
        _set("config/config.yaml", "sensor", "band", ["r10_l30_sensor_cal", "r10_l30_film_cal"]),
        "config/config.yaml: field 'sensor.band[1]': case 'ball_3.16mm-r10_l30_film_cal' of the reading "
        "'r10_l30_film_cal' needs a law calibrated by the continuum (from: fem_axi_indentation) on a stack "
        "(contact.stack)",
    ),
    "work precision on an unknown case": (
        _set("config/config.yaml", "work_precision", "cases", ["model", "modle"]),
        "config/config.yaml: field 'work_precision.cases[1]': unknown case 'modle'",
    ),
    "work precision level with another method's setting": (
        _set("config/config.yaml", "work_precision", "methods", "sem", "levels", 0, "elements_across", 4),
        "config/config.yaml: field 'work_precision.methods.sem.levels[0].elements_across': not a setting of "
        "method 'sem'; its settings: dt_s, steps_per_contact, max_time_factor, max_contacts, energy_tolerance, "
        "max_steps, tolerance",
    ),
    "work precision levels that do not refine": (
        _set("config/config.yaml", "work_precision", "methods", "sem", "levels", 1, "steps_per_contact", 25),
        "config/config.yaml: field 'work_precision.methods.sem.levels': levels must refine: steps_per_contact = "
        "[25, 25, 100, 200, 400, 800, 1600, 3200, 6400, 12800]",
    ),
    "work precision level beyond the paper scheme's stability limit": (
        _set("config/config.yaml", "work_precision", "methods", "sem_paper", "levels", 0, "steps_per_contact", 10),
        "config/config.yaml: field 'work_precision.methods.sem_paper.levels[0]': case 'ball_12.73mm-r1_l30': "
        "steps_per_contact: dt_s=7.109e-06 s exceeds the paper scheme's stability limit 2 Z / k_c = 3.252e-06 s "
        "(rod impedance Z = 44.2 kg/s, contact stiffness k_c = dP/dalpha = 2.719e+07 N/m at the rigid-rod approach "
        "7.79e-06 m); take dt_s <= 3.252e-06 s (steps_per_contact >= 22), or set allow_unstable: true to run it "
        "anyway",
    ),
    "separate work precision on an unknown case": (
        _set("config/config.yaml", "work_precision", "separate", "cases", ["ball_9.51mm-r1_I301"]),
        "config/config.yaml: field 'work_precision.separate.cases[0]': unknown case 'ball_9.51mm-r1_I301'",
    ),
    "separate work precision on a case of the default build": (
        _set("config/config.yaml", "work_precision", "separate", "cases", ["ball_9.51mm-r1_l301", "model"]),
        "config/config.yaml: field 'work_precision.separate.cases[1]': case 'model' is swept by the default build "
        "already (work_precision.cases)",
    ),
    "separate work precision with a method not swept": (
        _set("config/config.yaml", "work_precision", "separate", "methods", ["fem_ax"]),
        "config/config.yaml: field 'work_precision.separate.methods[0]': method 'fem_ax' is not swept; swept: sem, "
        "sem_paper, fem1d, fem_axi",
    ),
    "separate work precision without a method's reference": (
        _set("config/config.yaml", "work_precision", "separate", "methods", ["fem1d"]),
        "config/config.yaml: field 'work_precision.separate.methods': method 'fem1d' is measured against 'sem', "
        "which is not among them",
    ),
    "work precision per case on a case not swept": (
        _set("config/config.yaml", "work_precision", "per_case", "modle", {"methods": ["sem"]}),
        "config/config.yaml: field 'work_precision.per_case.modle': case 'modle' is not swept "
        "(work_precision.cases, work_precision.separate.cases)",
    ),
    "work precision per case with a method not swept": (
        _set("config/config.yaml", "work_precision", "per_case", "linear_spring", "methods", ["sem", "fem2d"]),
        "config/config.yaml: field 'work_precision.per_case.linear_spring.methods[1]': method 'fem2d' is not swept; "
        "swept: sem, sem_paper, fem1d, fem_axi",
    ),
    "work precision per case with a method that cannot run the case's law": (
        _set("config/config.yaml", "work_precision", "per_case", "linear_spring", "methods", ["sem", "fem_axi"]),
        "config/config.yaml: field 'work_precision.per_case.linear_spring.methods[1]': method 'fem_axi' cannot run "
        "the case's spring law",
    ),
    "work precision per case without a method's reference": (
        _set("config/config.yaml", "work_precision", "per_case", "linear_spring", "methods", ["fem1d"]),
        "config/config.yaml: field 'work_precision.cases[3]': case 'linear_spring': method 'fem1d' is measured "
        "against 'sem', which is not swept on it (swept: fem1d)",
    ),
    "work precision per case with orders of a method not swept on it": (
        _set(
            "config/config.yaml",
            "work_precision",
            "per_case",
            "linear_spring",
            "expected_orders",
            "sem_paper",
            {"max": 1},
        ),
        "config/config.yaml: field 'work_precision.per_case.linear_spring.expected_orders.sem_paper': method "
        "'sem_paper' is not swept on the case; swept: sem, fem1d",
    ),
    "stability on an unknown set": (
        _set("config/config.yaml", "stability", "sets", ["stres"]),
        "config/config.yaml: field 'stability.sets[0]': unknown case set 'stres'; known: model, plastic, smooth, "
        "stress, table2, example, gauge_example",
    ),
    "stability without a method's tolerances": (
        _set("config/config.yaml", "stability", "tolerances", "fem1d", None),
        "config/config.yaml: field 'stability.tolerances': no tolerances for method 'fem1d' (run by case "
        "'microgram_fast')",
    ),
    "unknown sweep parameter": (
        _set(TABLE2, "cases", 6, "sweep", "parameters", "diameter", [1e-3]),
        f"{TABLE2}: case 'ball_sweep': field 'sweep.parameters.diameter': unknown field (did you mean "
        "'ball_diameter_m'?); allowed: ball_diameter_m, mass_kg, radius_m, velocity_m_s, rod_length_m, "
        "film_modulus_pa, film_poisson_ratio, film_thickness_m",
    ),
    "negative sweep start": (
        _set(TABLE2, "cases", 6, "sweep", "parameters", "ball_diameter_m", {"start": -1e-3, "stop": 2e-2, "num": 5}),
        f"{TABLE2}: case 'ball_sweep': field 'sweep.parameters.ball_diameter_m.start': must be > 0, got -0.001",
    ),
    "unknown sweep method": (
        _set(TABLE2, "cases", 6, "sweep", "methods", ["semm"]),
        f"{TABLE2}: case 'ball_sweep': field 'sweep.methods[0]': unknown method 'semm'; known: sem, sem_paper, "
        "fem1d, fem_axi",
    ),
    "sweep values that name the same file": (
        _set(TABLE2, "cases", 6, "sweep", "parameters", "ball_diameter_m", [1e-3, 1.0000001e-3]),
        f"{TABLE2}: case 'ball_sweep-r10_l30': field 'sweep.parameters.ball_diameter_m': values coincide after "
        "rounding to 6 digits: [0.001, 0.001]",
    ),
}


def test_unstable_sweep_point_is_refused_naming_the_point(project_dir: Path) -> None:
    def change(document: dict) -> None:
        document["cases"][6]["sweep"]["methods"] = ["sem_paper"]
        document["cases"][6]["numerics"] = {"sem_paper": {"steps_per_contact": 10}}

    edit(project_dir / TABLE2, change)
    message = error_of(project_dir)
    assert message.startswith(
        f"{TABLE2}: case 'ball_sweep-r1_l301': field 'numerics.sem_paper.steps_per_contact': at ball_diameter_m = "
    ), message
    assert "stability limit" in message


@pytest.mark.parametrize("change, expected", MALFORMED.values(), ids=MALFORMED.keys())
def test_malformed_input_is_reported(project_dir: Path, change, expected: str) -> None:
    path, apply = change
    edit(project_dir / path, apply)
    assert error_of(project_dir) == expected


def test_first_problem_in_file_order_is_reported(project_dir: Path) -> None:
    def change(document: dict) -> None:
        document["cases"][3]["impactor"]["radius_m"] = 0
        document["cases"][1]["impactor"]["mass_kg"] = -1
        document["cases"][1]["measured"]["contact_time_us"] = "x"

    edit(project_dir / TABLE2, change)
    assert error_of(project_dir) == f"{TABLE2}: case 'ball_4.75mm': field 'impactor.mass_kg': must be > 0, got -1"


def test_duplicate_case_id_names_both_files(project_dir: Path) -> None:
    model = project_dir / MODEL
    shutil.copy(model, project_dir / "config/cases/a_copy.yaml")
    assert error_of(project_dir) == (
        f"{MODEL}: case 'model': field 'id': duplicate case id; already defined in config/cases/a_copy.yaml"
    )


def test_yaml_syntax_error_names_file_and_line(project_dir: Path) -> None:
    (project_dir / "config/cases/broken.yaml").write_text("cases:\n  - id: a\n    rod: {length_m: 1\n  - id: b\n")
    message = error_of(project_dir)
    assert message.startswith("config/cases/broken.yaml: invalid YAML at line 4, column 7: ")


def test_duplicate_yaml_key_is_an_error(project_dir: Path) -> None:
    text = (project_dir / MODEL).read_text().replace("      mass_kg: 0.5\n", "      mass_kg: 0.5\n      mass_kg: 5\n")
    (project_dir / MODEL).write_text(text)
    assert error_of(project_dir).startswith(f"{MODEL}: invalid YAML at line 12, column 7: duplicate key 'mass_kg'")


def test_empty_case_file(project_dir: Path) -> None:
    (project_dir / "config/cases/empty.yaml").write_text("# nothing yet\n")
    assert error_of(project_dir) == (
        "config/cases/empty.yaml: file is empty; expected a mapping with a non-empty 'cases' list"
    )


def test_case_file_that_is_not_a_mapping(project_dir: Path) -> None:
    (project_dir / "config/cases/list.yaml").write_text("- id: a\n")
    assert error_of(project_dir) == "config/cases/list.yaml: must be a mapping, got a list"


def test_missing_materials_file(project_dir: Path) -> None:
    (project_dir / "config/materials.yaml").unlink()
    assert error_of(project_dir) == "config/materials.yaml: file not found"


def test_global_config_typo(project_dir: Path) -> None:
    path = project_dir / "config/config.yaml"
    edit(path, lambda d: d.update(numerics={"sem": {"step_per_contact": 100}}))
    with pytest.raises(ConfigError) as info:
        load_global_config(path)
    assert str(info.value) == (
        "config/config.yaml: field 'numerics.sem.step_per_contact': unknown field "
        "(did you mean 'steps_per_contact'?); allowed: dt_s, steps_per_contact, max_time_factor, max_contacts, "
        "energy_tolerance, max_steps, tolerance"
    )


def test_exponent_without_sign_is_a_number(project_dir: Path) -> None:
    text = (project_dir / "config/materials.yaml").read_text().replace("2.1e+11", "2.1e11")
    (project_dir / "config/materials.yaml").write_text(text)
    assert load(project_dir).cases["model"]["rod"]["material"]["youngs_modulus_pa"] == 2.1e11


def test_config_error_parts_and_pickling() -> None:
    err = ConfigError(
        "must be > 0, got -0.13", file="config/cases/table2.yaml", case="ball_3.16mm", field="impactor.mass_kg"
    )
    assert str(err) == "config/cases/table2.yaml: case 'ball_3.16mm': field 'impactor.mass_kg': must be > 0, got -0.13"
    assert (err.file, err.case, err.field, err.reason) == (
        "config/cases/table2.yaml",
        "ball_3.16mm",
        "impactor.mass_kg",
        "must be > 0, got -0.13",
    )
    assert isinstance(err, ValueError)
    assert str(pickle.loads(pickle.dumps(err))) == str(err)
    assert str(ConfigError("file not found", file="x.yaml")) == "x.yaml: file not found"


def test_setting_of_another_method_is_refused(project_dir: Path) -> None:
    edit(project_dir / MODEL, lambda d: d["cases"][0].update(numerics={"sem": {"elements": 10}}))
    assert error_of(project_dir) == (
        f"{MODEL}: case 'model': field 'numerics.sem.elements': not a setting of "
        "method 'sem'; its settings: dt_s, steps_per_contact, max_time_factor, max_contacts, energy_tolerance, "
        "max_steps, tolerance"
    )


def test_station_output_needs_stations(project_dir: Path) -> None:
    edit(project_dir / MODEL, lambda d: d["cases"][0].update(stations=[]))
    message = error_of(project_dir)
    assert message.startswith(f"{MODEL}: case 'model': field 'outputs[")
    assert "'station_displacement' needs stations" in message


def test_station_outside_the_rod_is_refused(project_dir: Path) -> None:
    edit(project_dir / MODEL, lambda d: d["cases"][0].update(stations=[0.5, 1.5]))
    assert f"{MODEL}: case 'model': field 'stations[1]'" in error_of(project_dir)


# --------------------------------------------------------------------------- plausibility

_CASE0 = ("cases", 0)
IMPLAUSIBLE = {
    # (file, edit), expected start of the message
    "rod length 1e-300": (
        _set(MODEL, *_CASE0, "rod", "length_m", 1e-300),
        f"{MODEL}: case 'model': field 'rod.length_m': 1e-300 m: its wave round trip 2T = ",
    ),
    "nose radius 1e-300": (
        _set(MODEL, *_CASE0, "impactor", "radius_m", 1e-300),
        f"{MODEL}: case 'model': field 'impactor.radius_m': 1e-300 m: its nose radius R = 1e-300 m "
        "lies outside [1e-150, 1e+150] m",
    ),
    "mass 1e30": (
        _set(MODEL, *_CASE0, "impactor", "mass_kg", 1e30),
        f"{MODEL}: case 'model': field 'impactor.mass_kg': 1e+30 kg: its largest approach on a rigid rod, "
        "alpha_H = 9.2e+07 m, reaches the nose radius R = 0.01 m",
    ),
    "mass 1e-300": (
        _set(MODEL, *_CASE0, "impactor", "mass_kg", 1e-300),
        f"{MODEL}: case 'model': field 'impactor.mass_kg': 1e-300 kg: its impactor mass m = 1e-300 kg",
    ),
    "velocity 1e30": (
        _set(MODEL, *_CASE0, "impactor", "velocity_m_s", 1e30),
        f"{MODEL}: case 'model': field 'impactor.velocity_m_s': 1e+30 m/s: its largest approach",
    ),
    "velocity 1e-300": (
        _set(MODEL, *_CASE0, "impactor", "velocity_m_s", 1e-300),
        f"{MODEL}: case 'model': field 'impactor.velocity_m_s': 1e-300 m/s: its rigid-rod contact time t_H",
    ),
    "inline modulus 1e-300": (
        _set(MODEL, *_CASE0, "rod", "material", {**INLINE_STEEL, "youngs_modulus_pa": 1e-300}),
        f"{MODEL}: case 'model': field 'rod.material.youngs_modulus_pa': youngs_modulus_pa = "
        "1e-300 Pa: its rod's Young's modulus = 1e-300 Pa lies outside",
    ),
    "named material's modulus 1e-300": (
        _set("config/materials.yaml", "materials", "steel", "youngs_modulus_pa", 1e-300),
        f"{MODEL}: case 'model': field 'impactor.material': material 'steel': "
        "youngs_modulus_pa = 1e-300 Pa: its impactor's Young's modulus = 1e-300 Pa",
    ),
    "paper scheme's steps 1e12": (
        _set(MODEL, *_CASE0, "numerics", {"sem_paper": {"steps_per_contact": 10**12}}),
        f"{MODEL}: case 'model': field 'numerics.sem_paper.steps_per_contact': 1e+12: "
        "sem_paper would need about 4.3e+12 steps of 2.05e-16 s for the estimated contact, "
        "beyond its step budget max_steps = 5000000",
    ),
    "tolerance 1e-300 in config.yaml": (
        _set("config/config.yaml", "numerics", "sem", "tolerance", 1e-300),
        "config/config.yaml: case 'model': field 'numerics.sem.tolerance': 1e-300: "
        "sem would need about 2.32e+151 steps",
    ),
    "fem1d elements 1e9": (
        _set(MODEL, *_CASE0, "numerics", {"fem1d": {"elements": 10**9}}),
        f"{MODEL}: case 'model': field 'numerics.fem1d.elements': 1e+09: fem1d would take about "
        "1.24e+07 s (1.24e+04 steps of 1.03e-07 s), beyond the budget limits.run_time_s = 3600 s",
    ),
    "a budget no case meets": (
        _set("config/config.yaml", "limits", {"run_time_s": 1e-3}),
        "config/config.yaml: case 'model': field 'limits.run_time_s': sem would take about ",
    ),
}


@pytest.mark.parametrize("change, expected", IMPLAUSIBLE.values(), ids=IMPLAUSIBLE.keys())
def test_implausible_case_is_refused_naming_its_cause(project_dir: Path, change, expected: str) -> None:
    path, apply = change
    edit(project_dir / path, apply)
    message = error_of(project_dir)
    assert message.startswith(expected), message
    assert "\n" not in message


def test_plausibility_fallbacks_and_budget_of_machine() -> None:
    from rodimpact.config.plausible import Budget, machine_memory_mib

    budget = Budget.of({"run_time_s": 10, "memory_mib": None})
    assert budget.memory_mib == machine_memory_mib() > 100.0
    assert Budget.of({"run_time_s": 10, "memory_mib": 64}).memory_mib == 64.0


# --------------------------------------------------------------------------- hostile YAML and names


_NAME_RULE = "must be a name of letters, digits, '_' and '.' that starts with a letter or digit"


@pytest.mark.parametrize(
    "bad_id, expected",
    [
        ("model\n", f"{MODEL}: field 'cases[0].id': {_NAME_RULE}, got 'model\\n'"),
        ("m" * 65, f"{MODEL}: field 'cases[0].id': must be at most 64 characters long, got 65"),
        ("a/b", f"{MODEL}: field 'cases[0].id': {_NAME_RULE}, got 'a/b'"),
    ],
)
def test_case_id_is_a_whole_safe_name(project_dir: Path, bad_id: str, expected: str) -> None:
    edit(project_dir / MODEL, lambda document: document["cases"][0].__setitem__("id", bad_id))
    assert error_of(project_dir) == expected


def test_yml_case_file_is_refused_by_name(project_dir: Path) -> None:
    shutil.copy(project_dir / MODEL, project_dir / "config/cases/extra.yml")
    assert error_of(project_dir) == (
        "config/cases/extra.yml: a case file ends in .yaml; rename it extra.yaml (only *.yaml files are read)"
    )


def test_a_case_file_in_a_subdirectory_is_refused_by_name(project_dir: Path) -> None:
    """config/cases/sub/x.yaml (with a negative mass, say) was ignored without a word."""
    (project_dir / "config/cases/sub").mkdir()
    shutil.copy(project_dir / MODEL, project_dir / "config/cases/sub/x.yaml")
    assert error_of(project_dir) == (
        "config/cases/sub/x.yaml: a case file in a subdirectory is not read; move it to config/cases/ "
        "(only config/cases/*.yaml are case files)"
    )


def test_a_case_file_that_is_a_fifo_is_refused_without_a_read(project_dir: Path) -> None:
    import os

    os.mkfifo(project_dir / "config/cases/pipe.yaml")
    assert error_of(project_dir) == "config/cases/pipe.yaml: is a FIFO (named pipe), not a regular file"


def test_sweep_that_runs_backwards_is_refused(project_dir: Path) -> None:
    path, change = _set(
        TABLE2, "cases", 6, "sweep", "parameters", "ball_diameter_m", {"start": 2e-2, "stop": 1e-3, "num": 5}
    )
    edit(project_dir / path, change)
    assert error_of(project_dir) == (
        f"{TABLE2}: case 'ball_sweep-r10_l30': field "
        "'sweep.parameters.ball_diameter_m.stop': must be > start (0.02), got 0.001"
    )


def test_merge_key_is_read(project_dir: Path) -> None:
    text = (project_dir / MODEL).read_text()
    text = text.replace(
        "cases:\n  - id: model\n",
        "bodies: &steel_rod\n  length_m: 0.5\n  area_m2: 5.0e-5\n"
        "  material: steel\n  far_end: fixed\ncases:\n  - id: model\n",
    )
    text = text.replace(
        "    rod:\n      length_m: 0.5\n      area_m2: 5.0e-5\n      material: steel\n      far_end: fixed\n",
        "    rod:\n      <<: *steel_rod\n      length_m: 0.25\n",
    )
    assert "<<: *steel_rod" in text
    (project_dir / MODEL).write_text(text)
    # the top-level anchor holder is not a case-file field: the schema names it, after the merge worked
    assert error_of(project_dir).startswith(f"{MODEL}: field 'bodies': unknown field")


def test_alias_bomb_is_refused_before_it_is_built(project_dir: Path) -> None:
    lines = ['a: &a ["x", "x", "x", "x", "x", "x", "x", "x", "x"]']
    lines += [f"{b}: &{b} [{', '.join([f'*{a}'] * 9)}]" for a, b in zip("abcdefgh", "bcdefghi")]
    (project_dir / "config/cases/bomb.yaml").write_text("\n".join(lines) + "\n")
    assert error_of(project_dir) == (
        "config/cases/bomb.yaml: invalid YAML: its aliases expand it to 4.9e+08 "
        "nodes, more than the 200000 allowed (an alias bomb?)"
    )


@pytest.mark.parametrize(
    "change, field, words",
    [
        (
            lambda h, f: f.write_text("time,force_N\n" + "".join(f"{k},1\n" for k in range(10))),
            "time_unit",
            "names no unit of time",
        ),
        (
            lambda h, f: f.write_text("time_us,force_N\n" + "".join(f"{k % 5},1\n" for k in range(10))),
            "file",
            "line 7: the time must increase",
        ),
        (lambda h, f: h.update(file="../../outside.csv"), "file", "outside the directory of its case file"),
        (lambda h, f: f.unlink(), "file", "no such file"),
        # every force negated: refused, with how to declare it
        (
            lambda h, f: f.write_text(
                "\n".join(
                    line if i == 0 else f"{line.split(',')[0]},{-float(line.split(',')[1])!r}"
                    for i, line in enumerate(f.read_text().strip().splitlines())
                )
                + "\n"
            ),
            "sign",
            "the first pulse of the force has the wrong sign",
        ),
        (lambda h, f: h.update(time_unit="s") or f.write_text("time_min,force_N\n" + "0,1\n" * 9), "file", "column 1"),
    ],
)
def test_a_bad_force_history_is_one_line_before_any_job(project_dir: Path, change, field, words) -> None:
    """Each fault of a measured force history stops the load with one line naming the case
    file, the case and the field of the history block."""
    case_file = project_dir / "config" / "cases" / "worked_example.yaml"
    document = yaml.safe_load(case_file.read_text())
    history = document["cases"][0]["measured"]["force_history"]
    change(history, case_file.parent / history["file"])
    case_file.write_text(yaml.safe_dump(document, sort_keys=False))
    with pytest.raises(ConfigError) as caught:
        load(project_dir)
    message = str(caught.value)
    assert message.startswith(
        f"config/cases/worked_example.yaml: case 'ball_10mm': field 'measured.force_history.{field}': "
    ), message
    assert words in message and "\n" not in message, message


def test_a_negated_history_is_read_with_sign_minus_one(project_dir: Path) -> None:
    """The history of the worked example negated, declared ``sign: -1``: read as before."""
    case_file = project_dir / "config" / "cases" / "worked_example.yaml"
    document = yaml.safe_load(case_file.read_text())
    history = document["cases"][0]["measured"]["force_history"]
    path = case_file.parent / history["file"]
    lines = path.read_text().strip().splitlines()
    path.write_text(
        "\n".join([lines[0], *(f"{a},{-float(b)!r}" for a, b in (line.split(",") for line in lines[1:]))]) + "\n"
    )
    history["sign"] = -1
    case_file.write_text(yaml.safe_dump(document, sort_keys=False))
    assert load(project_dir).cases["ball_10mm"]["measured"]["force_history"]["sign"] == -1


@pytest.mark.parametrize(
    "rebound, words",
    [
        (5.0, "a rebound of 5 m/s is faster than the impact at 1 m/s"),
        (-0.816, "must be >= 0"),
    ],
)
def test_a_rebound_faster_than_the_impact_or_negative_is_refused(project_dir: Path, rebound, words) -> None:
    case_file = project_dir / "config" / "cases" / "worked_example.yaml"
    document = yaml.safe_load(case_file.read_text())
    document["cases"][0]["measured"]["rebound_velocity_m_s"] = rebound
    case_file.write_text(yaml.safe_dump(document, sort_keys=False))
    message = error_of(project_dir)
    assert message.startswith(
        "config/cases/worked_example.yaml: case 'ball_10mm': field 'measured.rebound_velocity_m_s': "
    ), message
    assert words in message, message


def test_a_long_bad_value_is_quoted_in_part_with_its_length(project_dir: Path) -> None:
    """A case file that is one long string (a link to /etc/passwd, say): one line, at most about
    100 characters of the value, and its length."""
    text = "root:x:0:0:root:/root:/bin/bash " * 45
    (project_dir / "config/cases/long.yaml").write_text(text + "\n")
    message = error_of(project_dir)
    assert message.startswith("config/cases/long.yaml: must be a mapping, got string 'root:x:0:0"), message
    assert f"... ({len(repr(text.strip()))} characters)" in message and len(message) < 200, message


@pytest.mark.parametrize("stiffness", [1e300, 1e-300])
def test_an_absurd_law_setting_is_blamed_on_that_setting(project_dir: Path, stiffness: float) -> None:
    """A spring of 1e300 (or 1e-300) N/m makes the impact's scales absurd: the spring's stiffness
    is at fault, not the impactor's mass."""
    edit(
        project_dir / "config/cases/smooth.yaml",
        lambda document: document["cases"][0]["contact"].__setitem__("stiffness_n_per_m", stiffness),
    )
    message = error_of(project_dir)
    assert message.startswith("config/cases/smooth.yaml: case 'linear_spring': field 'contact.stiffness_n_per_m': "), (
        message
    )


def test_a_methods_options_are_built_once_per_settings_and_true_is_not_1(shipped_config) -> None:
    """The same resolved settings give the same (frozen) options object, built once: a planned
    sweep estimates every point with them; settings that differ only by a value's type (1 and
    true, equal in Python) are not taken for each other, so a bad type is still refused."""
    from rodimpact.solvers.options import OptionError

    settings = dict(shipped_config["numerics"]["sem"])
    first, again = REGISTRY["sem"].options_of(settings), REGISTRY["sem"].options_of(dict(settings))
    assert first is again and first == REGISTRY["sem"].options.from_settings(settings)
    assert REGISTRY["sem"].options_of({**settings, "max_contacts": 1}).max_contacts == 1
    with pytest.raises(OptionError):  # True == 1 and hash(True) == hash(1): cached apart
        REGISTRY["sem"].options_of({**settings, "max_contacts": True})
