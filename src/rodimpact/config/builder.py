"""The project builder: case files resolved into checked cases, one file at a time.

:class:`ProjectBuilder` is what :func:`rodimpact.config.load.load_project` fills: each case file
is checked against ``cases.schema.yaml``, expanded over its variants and sweeps, each case
resolved (materials, contact law, numerics from the method registry) and checked (outputs,
runs, plausibility), and the whole checked once more against the global config's targets and
studies (:meth:`ProjectBuilder.build`). The constants of what a case may name live here too.
"""

from __future__ import annotations

import functools
import logging
import math
from collections.abc import Callable

from rodimpact.analysis.sweeps import SweepError, sweep_point_case, sweep_points
from rodimpact.config.bodies import check_law, resolve_contact, resolve_material
from rodimpact.config.calibration import check_calibration
from rodimpact.config.checks import (
    check_outputs,
    check_run,
    check_sensor,
    check_set_declarations,
    check_stability,
    check_work_precision,
)
from rodimpact.config.measured import (
    check_measured_physics,
    check_records,
    record_outputs,
    resolve_gauges,
    resolve_measured,
)
from rodimpact.config.paths import format_path
from rodimpact.config.plausible import Budget, check_plausible
from rodimpact.config.project import ConfigError, ConfigFile, Project
from rodimpact.config.schema import Schemas, deep_merge, with_floats
from rodimpact.solvers.field import FIELD_OUTPUT, FieldGrid
from rodimpact.solvers.options import OptionError
from rodimpact.solvers.registry import METHODS as METHOD_REGISTRY

__all__ = ["CASES_SCHEMA", "METHODS", "OUTPUTS", "ProjectBuilder"]

logger = logging.getLogger(__name__)

#: Known computation methods, in the registry's order.
METHODS: tuple[str, ...] = tuple(METHOD_REGISTRY)
#: Known outputs (keep equal to ``$defs/output`` in cases.schema.yaml): the time series, and
#: the strain field over the rod (:mod:`rodimpact.solvers.field`).
OUTPUTS: tuple[str, ...] = (
    "contact_force",
    "approach",
    "impactor_displacement",
    "impactor_velocity",
    "rod_end_displacement",
    "station_displacement",
    "station_strain",
    "energy",
    "contact_radius",
    FIELD_OUTPUT,
    "gauge_strain",
    "far_end_velocity",
)

CASES_SCHEMA = "cases.schema.yaml"
COMPLETE_MATERIAL = "materials.schema.yaml#/$defs/complete_material"
_VARIANT_FIELDS = ("impactor", "rod", "contact", "methods", "numerics")  # what a variant may change in a case


class ProjectBuilder:
    """Collects resolved cases file by file, checking each as it goes."""

    def __init__(self, config: dict, config_source: ConfigFile, materials: dict[str, dict]):
        self.config, self.config_source, self.materials = config, config_source, materials
        self.cases: dict[str, dict] = {}
        self.sets: dict[str, list[str]] = {}
        self.variants: dict[str, dict[str, dict]] = {}
        self.compare: dict[str, dict] = {}
        self.calibrate: dict[str, tuple[dict, ConfigFile]] = {}  # set -> its calibrate block and the file declaring it
        self.schemas: Schemas | None = None
        self.sweeps: dict[str, dict] = {}
        self.histories: dict[tuple, tuple] = {}  # measured records read (config.measured)

    def add_file(self, source: ConfigFile, schemas: Schemas) -> None:
        document = source.read()
        if document is None:
            raise source.error("file is empty; expected a mapping with a non-empty 'cases' list")
        if isinstance(document, dict):
            document.setdefault("set", source.path.stem)  # checked by the schema like the rest
        source.check(document, schemas, CASES_SCHEMA)
        set_name, variants = document["set"], document.get("variants", {})
        check_set_declarations(set_name, variants, document.get("compare"), self.variants, self.compare, source.error)
        self._add_variants(source, set_name, variants)
        if document.get("compare") is not None:
            self.compare[set_name] = document["compare"]
        if document.get("calibrate") is not None:
            if set_name in self.calibrate:
                other = self.calibrate[set_name][1].label
                raise source.error(
                    f"set {set_name!r} is calibrated in {other} already; declare it once", field="calibrate"
                )
            self.calibrate[set_name] = (document["calibrate"], source)
        self.schemas = schemas
        self.sets.setdefault(set_name, [])
        for entry in document["cases"]:
            base = deep_merge(document.get("defaults", {}), entry)
            names = self._variant_names(source, base, variants)
            for name in sorted(set(base.get("variant_outputs", {})) - set(names)):
                raise source.error(
                    f"not a variant the case is expanded over (its variants: {names})",
                    case=base["id"],
                    field=f"variant_outputs.{name}",
                )
            for variant in names:
                given = variants.get(variant, {})
                changes = {key: given[key] for key in _VARIANT_FIELDS if key in given}
                self._add_case(source, schemas, set_name, variant, deep_merge(base, changes))
        logger.debug("%s: set %r has %d cases", source.label, set_name, len(self.sets[set_name]))

    def _add_variants(self, source: ConfigFile, set_name: str, variants: dict) -> None:
        known = self.variants.setdefault(set_name, {})
        for name, variant in variants.items():
            if known.get(name, variant) != variant:
                message = f"variant of set {set_name!r} is defined differently in another file"
                raise source.error(message, field=f"variants.{name}")
            known[name] = variant

    @staticmethod
    def _variant_names(source: ConfigFile, case: dict, variants: dict) -> list[str | None]:
        """The variants a case is expanded over ([None]: no expansion)."""
        if "variants" not in case:
            return list(variants) or [None]
        for index, name in enumerate(case["variants"]):
            if name not in variants:
                declared = f"declared: {', '.join(variants)}" if variants else "none declared"
                message = f"unknown variant {name!r}; {declared}"
                raise source.error(message, case=case["id"], field=f"variants[{index}]")
        return list(case["variants"])

    def _add_case(self, source: ConfigFile, schemas: Schemas, set_name: str, variant: str | None, case: dict) -> None:
        case.pop("variants", None)  # already expanded
        row = case["id"]
        case_id = f"{row}-{variant}" if variant else row
        error = functools.partial(source.error, case=case_id)
        problem = schemas.first_problem(case, CASES_SCHEMA, "/$defs/resolved_case", fill_defaults=True)
        if problem:
            if problem.path[:1] == ("id",):  # the id itself is wrong: no case to name
                raise source.error(problem.message, field="id")
            raise error(problem.message, field=format_path(problem.path) or None)
        if case_id in self.cases or case_id in self.sweeps:
            other = {**self.cases, **self.sweeps}[case_id]["source_file"]
            where = "earlier in this file" if other == source.label else f"in {other}"
            raise error(f"duplicate case id; already defined {where}", field="id")
        sweep = case.get("sweep")
        if sweep is not None:
            case["methods"] = sweep.setdefault("methods", case["methods"])
        case["outputs"] = check_outputs(case, variant, error)
        measured, records = resolve_measured(
            with_floats(case["measured"]), source.path, source.label, error, self.histories
        )
        resolved = {
            "id": case_id,
            "row": row,
            "variant": variant,
            "set": set_name,
            "source_file": source.label,
            "description": case["description"],
            "impactor": self._impactor(case["impactor"], error),
            "rod": self._rod(case["rod"], error),
            **self._contact(case.get("contact"), error),
            "methods": list(case["methods"]),
            "outputs": list(case["outputs"]),
            "stations": [float(x) for x in case["stations"]],
            **(
                {"field_grid": FieldGrid.from_settings(case.get("field_grid", {})).as_settings()}
                if FIELD_OUTPUT in case["outputs"]
                else {}
            ),
            "numerics": self._numerics(case, case_id, source),
            "measured": measured,
            "published": with_floats(case["published"]),
        }
        check_measured_physics(resolved, error)
        gauges = resolve_gauges(resolved, case["gauges"], error)
        if gauges:  # only where there are any: a case without keeps its resolved form
            resolved["gauges"] = gauges
        resolved["outputs"] += [name for name in record_outputs(resolved) if name not in resolved["outputs"]]
        if "gauge_strain" in resolved["outputs"] and not gauges:
            where = case["outputs"].index("gauge_strain") if "gauge_strain" in case["outputs"] else None
            raise error(
                "output 'gauge_strain' needs gauges (gauges, or a measured strain_history)",
                field=f"outputs[{where}]" if where is not None else "variant_outputs",
            )
        check_law(resolved if sweep is None else {**resolved, "sweep": sweep}, error)
        if sweep is not None:
            self.sweeps[case_id] = self._sweep(resolved, sweep, source)
            check_records(resolved, records, error)  # once the case's runs are known to be sound
            return
        self._check_runs(resolved, source)
        check_records(resolved, records, error)
        self.cases[case_id] = resolved
        self.sets[set_name].append(case_id)

    def _sweep(self, case: dict, sweep: dict, source: ConfigFile) -> dict:
        """The sweep case with its grid's values; every point's runs checked like a case's."""
        try:
            points = sweep_points(sweep)
        except SweepError as error:
            raise source.error(error.reason, case=case["id"], field=f"sweep.{error.field}") from None
        parameters = {name: sorted({point[name] for point in points}) for name in points[0]}
        case = {
            **case,
            "sweep": {"description": sweep["description"], "methods": list(sweep["methods"]), "parameters": parameters},
        }
        for row in points:
            where = ", ".join(f"{name} = {value:g}" for name, value in row.items())
            try:
                point = sweep_point_case(case, row, "check")
            except ValueError as error:
                raise source.error(f"at {where}: {error}", case=case["id"], field="sweep.parameters") from None
            try:
                self._check_runs(point, source)
            except ConfigError as error:
                raise source.error(f"at {where}: {error.reason}", case=case["id"], field=error.field) from None
        return case

    def _material(self, value: str | dict, error: Callable[..., ConfigError], field: str) -> dict:
        return resolve_material(value, self.materials, error, field)

    def _contact(self, contact: dict | None, error: Callable[..., ConfigError]) -> dict:
        return resolve_contact(contact, self.materials, error)

    def _impactor(self, impactor: dict, error: Callable[..., ConfigError]) -> dict:
        resolved = {key: float(impactor[key]) for key in ("mass_kg", "radius_m", "velocity_m_s")}
        material = self._material(impactor["material"], error, "impactor.material")
        return {**resolved, "body": impactor["body"], "material": material}

    def _rod(self, rod: dict, error: Callable[..., ConfigError]) -> dict:
        given = [key for key in ("area_m2", "radius_m") if key in rod]
        if len(given) != 1:
            got = "both" if given else "neither"
            message = f"exactly one of 'area_m2' and 'radius_m' must be given, got {got}"
            raise error(message, field="rod")
        radius = float(rod["radius_m"]) if "radius_m" in rod else None
        return {
            "length_m": float(rod["length_m"]),
            "area_m2": math.pi * radius**2 if radius is not None else float(rod["area_m2"]),
            "radius_m": radius,
            "far_end": rod["far_end"],
            "material": self._material(rod["material"], error, "rod.material"),
        }

    def _numerics(self, case: dict, case_id: str, source: ConfigFile) -> dict:
        """The global numerics of each of the case's methods, the case's overrides on top."""
        resolved = {}
        for method in case["methods"]:
            if method not in self.config["numerics"]:
                message = f"no numerics for method {method!r} (case {case_id!r}, {source.label})"
                raise self.config_source.error(message, field=f"numerics.{method}")
            overrides = case.get("numerics", {}).get(method, {})
            spec = METHOD_REGISTRY[method]
            allowed = spec.options.names()
            for name in overrides:
                if name not in allowed:
                    message = f"not a setting of method {method!r}; its settings: {', '.join(allowed)}"
                    raise source.error(message, case=case_id, field=f"numerics.{method}.{name}")
            fields = {**self.config["numerics"][method], **overrides}
            try:
                options = spec.options_of({name: fields[name] for name in allowed if name in fields})
            except OptionError as error:
                where = source if error.field in overrides else self.config_source
                raise where.error(
                    error.reason, case=case_id if where is source else None, field=f"numerics.{method}.{error.field}"
                ) from None
            resolved[method] = options.as_settings()
        return resolved

    def _check_runs(self, case: dict, source: ConfigFile) -> None:
        """The case's runs are plausible (:mod:`.plausible`) and each method's options fit
        the case (e.g. sem_paper's step is stable)."""
        finding = check_plausible(case, Budget.of(self.config["limits"]))
        if finding is not None:
            own = not finding.budget
            if finding.setting:  # a setting the case does not change is config.yaml's
                _, method, name = finding.field.split(".")
                own = case["numerics"][method][name] != self.config["numerics"][method].get(name)
            where = source if own else self.config_source
            raise where.error(finding.reason, case=case["id"], field=finding.field)
        for method in case["methods"]:
            try:
                check_run(case, method)
            except OptionError as error:
                raise source.error(str(error), case=case["id"], field=f"numerics.{method}.{error.field}") from None

    def build(self) -> Project:
        for index, name in enumerate(self.config["targets"]["sets"]):
            if name not in self.sets:
                message = f"unknown case set {name!r}; known: {', '.join(self.sets)}"
                raise self.config_source.error(message, field=f"targets.sets[{index}]")
        check_work_precision(
            self.config.get("work_precision"), self.cases, self.config["numerics"], self.config_source.error
        )
        check_stability(self.config.get("stability"), self.cases, self.sets, self.config_source.error)
        check_sensor(self.config.get("sensor"), self.cases, self.config_source.error)
        for set_name, (block, source) in self.calibrate.items():
            cases = [self.cases[case_id] for case_id in self.sets[set_name]]
            check_calibration(set_name, block, cases, self.schemas, self.config["numerics"], source.error)
        return Project(
            cases=self.cases,
            sets=self.sets,
            variants=self.variants,
            compare=self.compare,
            calibrate={name: block for name, (block, _) in self.calibrate.items()},
            sweeps=self.sweeps,
            config=self.config,
        )
