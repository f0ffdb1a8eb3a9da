"""Checks of a run before any job: its method's options can be built and fit the case.

The configuration layer (:mod:`.config`) calls these for every run of every case, sweep
point and study level; the errors carry the setting at fault as data
(:class:`~rodimpact.solvers.options.OptionError`), never in the message alone.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from rodimpact.analysis.studies import level_case
from rodimpact.config.bodies import runs_law
from rodimpact.contact.laws import law_of
from rodimpact.solvers.field import FIELD_OUTPUT
from rodimpact.solvers.options import OptionError
from rodimpact.solvers.registry import METHODS

__all__ = [
    "check_outputs",
    "check_run",
    "check_sensor",
    "check_set_declarations",
    "check_stability",
    "check_work_precision",
    "swept_methods",
]


def check_run(case: Mapping[str, Any], method: str) -> None:
    """Check, without solving, that ``method`` can run ``case`` with its numerics.

    Builds the method's options and runs its checks that need the case (the paper scheme's
    stability limit).

    Raises
    ------
    OptionError
        The setting at fault is ``error.field``.
    """
    spec = METHODS[method]
    options = spec.options_of(case["numerics"][method])
    options.check(spec.estimate_problem(case))


def check_outputs(case: Mapping[str, Any], variant: str | None, error: Callable[..., Exception]) -> list[str]:
    """The outputs of a case (checked by the schema, defaults filled) for its ``variant``: its
    ``outputs`` and those ``variant_outputs`` adds for the variant, checked against the case.

    A station output needs stations; ``strain_field`` needs a method that records it (the
    registry's ``records_field``); ``field_grid`` is given only with ``strain_field``.
    ``error(message, field=)`` builds the exception raised.
    """
    outputs = list(case["outputs"])
    outputs += [name for name in case.get("variant_outputs", {}).get(variant, []) if name not in outputs]
    for index, output in enumerate(outputs):
        where = f"outputs[{index}]" if index < len(case["outputs"]) else f"variant_outputs.{variant}"
        if output.startswith("station_") and not case["stations"]:
            raise error(f"output {output!r} needs stations (fractions of the rod length)", field=where)
        if output == FIELD_OUTPUT and not any(METHODS[m].records_field for m in case["methods"]):
            recording = [name for name, spec in METHODS.items() if spec.records_field]
            raise error(
                f"output {output!r} is recorded by {', '.join(recording)} only; the case runs none of "
                f"them (methods: {', '.join(case['methods'])})",
                field=where,
            )
    if "field_grid" in case and FIELD_OUTPUT not in outputs:
        raise error(f"is the grid of the output {FIELD_OUTPUT!r}, which the case does not list", field="field_grid")
    return outputs


def swept_methods(study: Mapping[str, Any], case_id: str, case: Mapping[str, Any]) -> list[str]:
    """The methods config.yaml's ``work_precision`` sweeps on one of its cases.

    The case's ``per_case`` ``methods`` when it names them; else every method of the study's
    ``methods`` that can run the case's contact law (:func:`~rodimpact.config.bodies.runs_law`),
    in the study's order. A case of ``separate`` takes only ``separate.methods`` of them.
    """
    named = (study.get("per_case") or {}).get(case_id, {}).get("methods")
    methods = [m for m in study["methods"] if (m in named if named is not None else runs_law(case, m))]
    separate = study.get("separate") or {}
    if case_id in separate.get("cases", []):
        methods = [m for m in methods if m in separate["methods"]]
    return methods


def _check_per_case(study: Mapping[str, Any], cases: Mapping[str, dict], error: Callable[..., Exception]) -> None:
    """``per_case``: known cases of the study, and methods it sweeps that can run the case."""
    separate = (study.get("separate") or {}).get("cases", [])
    for case_id, spec in (study.get("per_case") or {}).items():
        where = f"work_precision.per_case.{case_id}"
        if case_id not in [*study["cases"], *separate]:
            raise error(
                f"case {case_id!r} is not swept (work_precision.cases, work_precision.separate.cases)", field=where
            )
        for index, method in enumerate(spec.get("methods", [])):
            if method not in study["methods"]:
                raise error(
                    f"method {method!r} is not swept; swept: {', '.join(study['methods'])}",
                    field=f"{where}.methods[{index}]",
                )
            if not runs_law(cases[case_id], method):
                raise error(
                    f"method {method!r} cannot run the case's {law_of(cases[case_id].get('contact')).name} law",
                    field=f"{where}.methods[{index}]",
                )


def check_work_precision(
    study: Mapping[str, Any] | None,
    cases: Mapping[str, dict],
    numerics: Mapping[str, Any],
    error: Callable[..., Exception],
) -> None:
    """Check config.yaml's ``work_precision`` against the cases; ``error(message, field=)``
    builds the exception raised (a :class:`~rodimpact.config.project.ConfigError` of config.yaml)."""
    if not study:
        return
    for index, case_id in enumerate(study["cases"]):
        if case_id not in cases:
            raise error(f"unknown case {case_id!r}", field=f"work_precision.cases[{index}]")
    separate = study.get("separate") or {"cases": [], "methods": []}
    for index, case_id in enumerate(separate["cases"]):
        if case_id not in cases:
            raise error(f"unknown case {case_id!r}", field=f"work_precision.separate.cases[{index}]")
        if case_id in study["cases"]:
            raise error(
                f"case {case_id!r} is swept by the default build already (work_precision.cases)",
                field=f"work_precision.separate.cases[{index}]",
            )
    for index, method in enumerate(separate["methods"]):
        if method not in study["methods"]:
            raise error(
                f"method {method!r} is not swept; swept: {', '.join(study['methods'])}",
                field=f"work_precision.separate.methods[{index}]",
            )
        reference = study["methods"][method]["reference"]
        if reference not in separate["methods"]:
            raise error(
                f"method {method!r} is measured against {reference!r}, which is not among them",
                field="work_precision.separate.methods",
            )
    _check_per_case(study, cases, error)
    listed = [(f"work_precision.cases[{i}]", c) for i, c in enumerate(study["cases"])]
    listed += [(f"work_precision.separate.cases[{i}]", c) for i, c in enumerate(separate["cases"])]
    for field, case_id in listed:
        swept = swept_methods(study, case_id, cases[case_id])
        if not swept:
            raise error(
                f"case {case_id!r}: no swept method can run its {law_of(cases[case_id].get('contact')).name} law",
                field=field,
            )
        for method in swept:
            reference = study["methods"][method]["reference"]
            if reference not in swept:
                raise error(
                    f"case {case_id!r}: method {method!r} is measured against {reference!r}, which is not "
                    f"swept on it (swept: {', '.join(swept)})",
                    field=field,
                )
        for method in (study.get("per_case") or {}).get(case_id, {}).get("expected_orders", {}):
            if method not in swept:
                raise error(
                    f"method {method!r} is not swept on the case; swept: {', '.join(swept)}",
                    field=f"work_precision.per_case.{case_id}.expected_orders.{method}",
                )
    for method, sweep in study["methods"].items():
        where = f"work_precision.methods.{method}"
        if sweep["reference"] not in study["methods"]:
            raise error(f"reference method {sweep['reference']!r} is not swept", field=f"{where}.reference")
        for index, level in enumerate(sweep["levels"]):
            names = METHODS[method].options.names()
            for name in level:
                if name not in names:
                    raise error(
                        f"not a setting of method {method!r}; its settings: {', '.join(names)}",
                        field=f"{where}.levels[{index}].{name}",
                    )
            if sweep["resolution"] not in level:
                raise error(
                    f"every level must set the resolution {sweep['resolution']!r}", field=f"{where}.levels[{index}]"
                )
            swept = [c for c in (*study["cases"], *separate["cases"]) if method in swept_methods(study, c, cases[c])]
            for case_id in swept:
                case = level_case(cases[case_id], method, numerics, level)
                try:
                    check_run(case, method)
                except OptionError as problem:
                    raise error(
                        f"case {case_id!r}: {problem.field}: {problem.reason}", field=f"{where}.levels[{index}]"
                    ) from None
        resolutions = [level[sweep["resolution"]] for level in sweep["levels"]]
        if any(b <= a for a, b in zip(resolutions, resolutions[1:])):
            raise error(f"levels must refine: {sweep['resolution']} = {resolutions}", field=f"{where}.levels")


def check_stability(
    study: Mapping[str, Any] | None,
    cases: Mapping[str, dict],
    sets: Mapping[str, list],
    error: Callable[..., Exception],
) -> None:
    """Check config.yaml's ``stability`` against the cases and sets (``error`` as above)."""
    if not study:
        return
    for index, name in enumerate(study["sets"]):
        if name not in sets:
            raise error(f"unknown case set {name!r}; known: {', '.join(sets)}", field=f"stability.sets[{index}]")
        for case_id in sets[name]:
            for method in cases[case_id]["methods"]:
                if method not in study["tolerances"]:
                    raise error(
                        f"no tolerances for method {method!r} (run by case {case_id!r})", field="stability.tolerances"
                    )
    spec = study.get("map")
    if spec and spec["base_case"] not in cases:
        raise error(f"unknown case {spec['base_case']!r}", field="stability.map.base_case")


def check_sensor(study: Mapping[str, Any] | None, cases: Mapping[str, dict], error: Callable[..., Exception]) -> None:
    """Check config.yaml's ``sensor`` against the cases (``error`` as above): each reading its
    ``band`` names has cases, every one calibrated by the continuum (a law that needs a curve) on
    a ``stack``."""
    if not study:
        return
    named = [(f"sensor.band[{i}]", v) for i, v in enumerate(study.get("band", []))]
    readings = sorted({c["variant"] for c in cases.values() if c.get("variant")})
    for field, variant in named:
        members = [c for c in cases.values() if c.get("variant") == variant]
        if not members:
            raise error(f"unknown reading {variant!r}; readings: {', '.join(readings)}", field=field)
        for case in members:
            contact = case.get("contact") or {}
            if law_of(contact).needs.curve_rule is None or not contact.get("stack"):
                raise error(
                    f"case {case['id']!r} of the reading {variant!r} needs a law calibrated by the continuum "
                    "(from: fem_axi_indentation) on a stack (contact.stack)",
                    field=field,
                )
    _check_film_readings(study, cases, readings, error)


def _check_film_readings(
    study: Mapping[str, Any], cases: Mapping[str, dict], readings: list[str], error: Callable[..., Exception]
) -> None:
    """``sensor.film_table``: readings of one set; ``sensor.film_force``: rows on readings, as cases."""
    table = study.get("film_table") or {}
    sets = {}
    for role, variant in table.items():
        members = [c for c in cases.values() if c.get("variant") == variant]
        if not members:
            raise error(
                f"unknown reading {variant!r}; readings: {', '.join(readings)}", field=f"sensor.film_table.{role}"
            )
        sets.setdefault(members[0]["set"], role)
    if len(sets) > 1:
        raise error(
            f"the readings are of several case sets ({', '.join(sorted(sets))}); one table is one set's",
            field="sensor.film_table",
        )
    force = study.get("film_force")
    for row in force["rows"] if force else []:
        for variant in force["variants"]:
            if f"{row}-{variant}" not in cases:
                raise error(
                    f"no case {row!r} on the reading {variant!r} (no case {row}-{variant})", field="sensor.film_force"
                )


def check_set_declarations(
    set_name: str,
    variants: Mapping[str, Any],
    compare: Mapping[str, Any] | None,
    known_variants: Mapping[str, Mapping],
    known_compare: Mapping[str, Mapping],
    error: Callable[..., Exception],
) -> None:
    """Check one case file's set-level declarations against the files read before it (``error``
    as above, the file's): a variant's name is unique over all sets (it names a reading: its band
    file, the sensor block's readings), and a set's ``compare`` is the same in all its files."""
    for name in variants:
        other = next((s for s, named in known_variants.items() if s != set_name and name in named), None)
        if other is not None:
            raise error(
                f"variant name already used by case set {other!r}; a variant's name is unique over all sets",
                field=f"variants.{name}",
            )
    if compare is not None and known_compare.get(set_name, compare) != compare:
        raise error(f"set {set_name!r} is compared differently in another file", field="compare")
