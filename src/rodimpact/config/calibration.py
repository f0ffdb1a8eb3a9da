"""A set's ``calibrate:`` block, checked before any job: what a calibration fits and to what.

The block (``workflow/schemas/cases.schema.yaml``, ``$defs/calibrate``; docs/calibration.md)
names the method that runs the cases, the constants fitted (each by its path in the resolved
case, :mod:`.paths`, with bounds and their source) and the measured quantities fitted
(:data:`rodimpact.analysis.observations.QUANTITY_ORDER`). It is refused, in one line naming
the file, the case where one is at fault, and the field, when:

* a quantity is not one the comparison knows, or no measured case of the set gives it;
* a path names no number in some measured case of the set;
* the bounds are not ordered, or the start lies outside them;
* the path names a setting that takes only whole numbers or a few values (an integer or
  enumerated setting, such as ``numerics.sem.max_contacts``): legal at the bounds, not between
  them, where the fit's trials fall;
* a case is not legal at a bound (its material outside the materials' schema, its contact law
  refusing the value, or the method unable to run it): the bounds leave the setting's declared
  range;
* ``variants`` or ``apply_to`` names no variant of the set, or a variant in both;
* a ``grid`` is not increasing from the least bound to the largest, or is given with more than
  one constant fitted;
* the set gives fewer measurements than there are constants to fit.

The cases predicted at the fitted constants (``apply_to``) are checked at the bounds as the
fitted ones are.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from rodimpact.analysis.measured import measured_cases
from rodimpact.analysis.observations import QUANTITY_ORDER, gives
from rodimpact.config.bodies import check_law
from rodimpact.config.checks import check_run
from rodimpact.config.paths import PathError, format_path, with_setting
from rodimpact.config.project import ConfigError
from rodimpact.contact.laws import bodies_contact, law_of
from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.options import OptionError

if TYPE_CHECKING:  # the schemas are handed in: importing them (jsonschema) is the checker's cost
    from rodimpact.config.schema import Schemas

__all__ = [
    "applied_cases",
    "calibration_cases",
    "check_calibration",
    "expected_evaluations",
    "observation_count",
    "with_method",
]

_MATERIAL_SCHEMA = "materials.schema.yaml"


def calibration_cases(cases: Sequence[Mapping[str, Any]], block: Mapping[str, Any]) -> list[Mapping[str, Any]]:
    """The cases a calibration fits: the set's cases (of the block's ``variants``, when it names
    some) that give at least one of its quantities."""
    return _giving(cases, block, block.get("variants"))


def applied_cases(cases: Sequence[Mapping[str, Any]], block: Mapping[str, Any]) -> list[Mapping[str, Any]]:
    """The cases a calibration predicts at its fitted constants without fitting them: the set's
    cases of the block's ``apply_to`` variants that give at least one of its quantities."""
    return _giving(cases, block, block.get("apply_to") or [])


def _giving(
    cases: Sequence[Mapping[str, Any]], block: Mapping[str, Any], variants: Sequence[str] | None
) -> list[Mapping[str, Any]]:
    return [
        c
        for c in measured_cases(list(cases))
        if (variants is None or c.get("variant") in variants) and any(gives(c, q) for q in block["quantities"])
    ]


def observation_count(cases: Sequence[Mapping[str, Any]], block: Mapping[str, Any]) -> int:
    """The measurements a calibration fits: each case's quantities it gives."""
    return sum(gives(c, q) for c in cases for q in block["quantities"])


def check_calibration(
    set_name: str,
    block: Mapping[str, Any],
    cases: Sequence[Mapping[str, Any]],
    schemas: Schemas,
    numerics: Mapping[str, Any],
    error: Callable[..., ConfigError],
) -> None:
    """Check a set's ``calibrate`` block against its resolved cases (see the module docstring).

    Parameters
    ----------
    set_name : str
        The set.
    block : mapping
        The block, schema-checked.
    cases : sequence of mapping
        The set's resolved cases.
    schemas : Schemas
        The project's schemas (a material changed by a bound is checked against its own).
    numerics : mapping
        The global numerics per method (the calibration's method runs a case with its own
        numerics where the case runs that method, else with these).
    error : callable
        ``error(message, case=..., field=...)`` -> :class:`ConfigError` naming the block's file.

    Raises
    ------
    ConfigError
        The first problem found.
    """
    for index, quantity in enumerate(block["quantities"]):
        if quantity not in QUANTITY_ORDER:
            raise error(
                f"unknown quantity {quantity!r}; known: {', '.join(QUANTITY_ORDER)}",
                field=f"calibrate.quantities[{index}]",
            )
        if not any(gives(c, quantity) for c in cases):
            raise error(
                f"no measured case of set {set_name!r} gives {quantity!r}", field=f"calibrate.quantities[{index}]"
            )
    known = sorted({str(c["variant"]) for c in cases if c.get("variant")})
    for key in ("variants", "apply_to"):
        for index, variant in enumerate(block.get(key) or []):
            if variant not in known:
                raise error(
                    f"{variant!r} is no variant of set {set_name!r}; its variants: {', '.join(known) or 'none'}",
                    field=f"calibrate.{key}[{index}]",
                )
    both = sorted(set(block.get("variants") or []) & set(block.get("apply_to") or []))
    if both:
        raise error(
            f"{', '.join(both)} both fitted and applied: a case is one or the other", field="calibrate.apply_to"
        )
    fitted = calibration_cases(cases, block)
    method = block["method"]
    for index, parameter in enumerate(block["parameters"]):
        where = f"calibrate.parameters[{index}]"
        low, high = (float(b) for b in parameter["bounds"])
        if not low < high:
            raise error(f"the bounds must increase, got [{low:g}, {high:g}]", field=f"{where}.bounds")
        start = parameter.get("start")
        if start is not None and not low <= float(start) <= high:
            raise error(f"{float(start):g} lies outside the bounds [{low:g}, {high:g}]", field=f"{where}.start")
        _check_grid(parameter, low, high, len(block["parameters"]), where, error)
        inside = _fractional_inside(low, high)
        for case in [*fitted, *applied_cases(cases, block)]:
            for bound in (low, high):
                try:
                    changed = with_setting(case, parameter["path"], bound)
                except PathError as problem:
                    raise error(f"names no setting: {problem.reason}", case=case["id"], field=f"{where}.path") from None
                reason = _illegal(changed, method, schemas, numerics)
                if reason:
                    raise error(
                        f"the case is not legal at {parameter['path']} = {bound:g}: {reason}; keep the bounds inside "
                        "the setting's range",
                        case=case["id"],
                        field=f"{where}.bounds",
                    )
            # legal at both bounds: a setting that takes only whole numbers (or a few values) is
            # refused between them, where the fit's trials fall
            reason = (
                None
                if inside is None
                else _illegal(with_setting(case, parameter["path"], inside), method, schemas, numerics)
            )
            if reason:
                raise error(
                    f"{parameter['path']} is not a real-valued constant: the case is legal at its bounds but not at "
                    f"{inside:.6g} between them ({reason}); a calibration varies a constant continuously, so it fits "
                    "no integer or enumerated setting",
                    case=case["id"],
                    field=f"{where}.path",
                )
    names = [p["path"] for p in block["parameters"]]
    if len(set(names)) != len(names):
        raise error("a constant is named twice", field="calibrate.parameters")
    count = observation_count(fitted, block)
    if count < len(names):
        raise error(
            f"{len(names)} constants to fit from {count} measurement(s) of set {set_name!r}: "
            "a fit needs at least as many measurements as constants",
            field="calibrate.parameters",
        )


def _fractional_inside(low: float, high: float) -> float | None:
    """A number strictly between ``low`` and ``high`` that is not a whole number (a fit's trial
    of a real constant); None where every double between them is whole (bounds beyond 2^52)."""
    for share in (0.5, 0.381966, 0.618034, 0.1, 0.9):
        value = low + share * (high - low)
        if low < value < high and not value.is_integer():
            return value
    return None


def _check_grid(
    parameter: Mapping[str, Any], low: float, high: float, count: int, where: str, error: Callable[..., ConfigError]
) -> None:
    """A parameter's ``grid``: of the only constant fitted, increasing, from its least bound to its largest."""
    grid = parameter.get("grid")
    if grid is None:
        return
    if count != 1:
        raise error(f"a grid fits one constant, and {count} are fitted", field=f"{where}.grid")
    values = [float(v) for v in grid]
    if any(b <= a for a, b in zip(values, values[1:], strict=False)):
        raise error(f"the grid must increase, got {values}", field=f"{where}.grid")
    if values[0] != low or values[-1] != high:
        raise error(
            f"the grid must run from the least bound to the largest ({low:g} to {high:g}), got {values[0]:g} to "
            f"{values[-1]:g}",
            field=f"{where}.grid",
        )


def _illegal(case: Mapping[str, Any], method: str, schemas: Schemas, numerics: Mapping[str, Any]) -> str | None:
    """Why ``case`` is not legal, or None: its materials against their schema, its law, and the
    method's checks of its options against the case. A law whose curve a rule computes (the
    continuum's indentation, again at every trial of a fit) is checked as the bodies that rule
    indents, under their analytic law."""
    if law_of(case.get("contact")).needs.curve_rule is not None:
        contact = bodies_contact(case.get("contact"))
        case = {**{k: v for k, v in case.items() if k != "contact"}, **({"contact": contact} if contact else {})}
    for body in ("impactor", "rod"):
        problem = schemas.first_problem(
            {k: v for k, v in case[body]["material"].items() if k != "name"},
            _MATERIAL_SCHEMA,
            "/$defs/complete_material",
        )
        if problem:
            return f"{body}.material{('.' + format_path(problem.path)) if problem.path else ''}: {problem.message}"

    def refuse(message: str, field: str | None = None, **_: Any) -> ValueError:
        return ValueError(f"{field}: {message}" if field else message)

    try:
        check_law(case, refuse)
        ImpactProblem.from_case(case)
        check_run(with_method(case, method, numerics), method)
    except OptionError as problem:
        return f"numerics.{method}.{problem.field}: {problem}"
    except (ArithmeticError, ValueError) as problem:
        return str(problem)
    return None


def expected_evaluations(parameters: int, cases: int) -> int:
    """How many times a calibration is expected to run each case, for its job's resources: the
    fit's trust-region steps (about 6) each take p + 1 points of its central-difference stencil
    (2p + 1, shared between steps), some 10 (p + 1) in all; each held-out refit, started from the
    fit, about 10 more per case (measured on the shipped example and the core's tests). Generous
    on purpose: an estimate too low would kill the job, one too high only reserves time."""
    return 10 * (parameters + 1) + 10 * cases


def with_method(case: Mapping[str, Any], method: str, numerics: Mapping[str, Any]) -> dict[str, Any]:
    """The case as the calibration's ``method`` runs it: with the method's numerics (the case's
    own where it runs the method, else the global ones)."""
    own = case["numerics"].get(method)
    return {**case, "methods": [method], "numerics": {**case["numerics"], method: own or dict(numerics[method])}}
