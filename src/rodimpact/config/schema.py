"""YAML documents behind :mod:`rodimpact.config.load`: checking and merging (reading is
:mod:`.yamlfile`'s, re-exported here).

Nothing here knows about files, cases or the project layout: problems are returned as
:class:`Problem` (a path inside the checked document and a message) and turned into
:class:`rodimpact.config.project.ConfigError` by the caller.
"""

from __future__ import annotations

import copy
import difflib
import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from jsonschema import Draft202012Validator, validators
from jsonschema.exceptions import ValidationError
from referencing import Registry
from referencing.jsonschema import DRAFT202012

from rodimpact.config.yamlfile import YamlError, read_yaml
from rodimpact.inputs.files import quoted

__all__ = [
    "Problem",
    "Schemas",
    "YamlError",
    "deep_merge",
    "first_non_finite",
    "read_yaml",
    "with_floats",
]

SCHEMA_FILES = ("config.schema.yaml", "cases.schema.yaml", "materials.schema.yaml")

PathParts = tuple[str | int, ...]


@dataclass(frozen=True)
class Problem:
    """One problem found in a document: where (`path` of keys and list indices) and what."""

    path: PathParts
    message: str


# --------------------------------------------------------------------------- schemas


def _extend_with_default(cls: type) -> type:
    """Validator class that inserts each missing property's `default` (a deep copy)."""
    validate_properties = cls.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, schema):
        if validator.is_type(instance, "object"):
            for name, subschema in properties.items():
                if isinstance(subschema, dict) and "default" in subschema and name not in instance:
                    instance[name] = copy.deepcopy(subschema["default"])
        yield from validate_properties(validator, properties, instance, schema)

    return validators.extend(cls, {"properties": set_defaults})


_FillingValidator = _extend_with_default(Draft202012Validator)


class Schemas:
    """The project's JSON schemas (YAML files), cross-referenced through one registry.

    Parameters
    ----------
    schema_dir
        Directory holding the files of :data:`SCHEMA_FILES`. Each schema gets its file URI as
        ``$id`` (as snakemake does), so relative ``$ref`` such as
        ``config.schema.yaml#/$defs/method`` resolve between the files.
    extra
        File name -> a mapping merged (:func:`deep_merge`) into that schema as it is read:
        the parts of a schema that are generated rather than written.
    """

    def __init__(self, schema_dir: Path, extra: Mapping[str, Mapping[str, Any]] | None = None):
        self.dir = Path(schema_dir)
        self._uris: dict[str, str] = {}
        resources = []
        for name in SCHEMA_FILES:
            path = self.dir / name
            uri = path.resolve().as_uri()
            # Without "$schema", jsonschema keeps our default-filling class across $ref
            # (it would switch to the plain class named there); the dialect is fixed here.
            document = {key: v for key, v in read_yaml(path).items() if key != "$schema"}
            document = deep_merge(document, (extra or {}).get(name, {}))
            document["$id"] = uri
            self._uris[name] = uri
            resources.append((uri, DRAFT202012.create_resource(document)))
        self._registry = Registry().with_resources(resources)
        self._inlined: dict[tuple[str, str], dict] = {}

    def first_problem(
        self, instance: Any, schema: str, pointer: str = "", *, fill_defaults: bool = False
    ) -> Problem | None:
        """Check `instance` against ``schema#pointer``; return the first problem in document order.

        With `fill_defaults`, missing properties that have a ``default`` are inserted into
        `instance` (in place) while it is checked.
        """
        cls = _FillingValidator if fill_defaults else Draft202012Validator
        validator = cls(self._inline(schema, pointer))
        problems = [_to_problem(error) for error in validator.iter_errors(instance)]
        if not problems:
            return None
        return min(problems, key=lambda p: _position(instance, p.path))

    def _inline(self, schema: str, pointer: str) -> dict:
        """``schema#pointer`` with each ``$ref`` replaced, in its place, by ``allOf`` of the schema it
        names (cached per schema and pointer).

        A check then looks no reference up: the look-ups took a third of the time of checking a
        resolved case. ``allOf`` of one schema gives the errors ``$ref`` gives, in the same order,
        and, like ``$ref``, hides that schema's ``default`` from the property it stands for.
        """
        key = (schema, pointer)
        if key not in self._inlined:
            root = self._registry.resolver().lookup(f"{self._uris[schema]}#{pointer}")
            self._inlined[key] = _inline_refs(root.contents, root.resolver, ())
        return self._inlined[key]


#: Keywords whose value is a schema, a list of schemas, or a mapping of names to schemas: where
#: :func:`_inline_refs` looks for ``$ref`` (every other keyword's value is data: enum, default...).
_SUBSCHEMA = frozenset(
    ("items", "additionalProperties", "propertyNames", "contains", "not", "if", "then", "else")
    + ("unevaluatedItems", "unevaluatedProperties", "additionalItems")
)
_SUBSCHEMA_LISTS = frozenset(("prefixItems", "allOf", "anyOf", "oneOf"))
_SUBSCHEMA_MAPS = frozenset(("properties", "patternProperties", "dependentSchemas"))


def _inline_refs(node: Any, resolver: Any, chain: tuple[int, ...]) -> Any:
    """A copy of the schema ``node`` without ``$ref`` (see :meth:`Schemas._inline`); ``$defs``
    are dropped (only references use them). ``chain``: the schemas being inlined around this one.

    Raises
    ------
    ValueError
        A reference leads back to a schema it is inside of (recursive schemas cannot be inlined).
    """
    if not isinstance(node, dict):
        return node
    inlined: dict[str, Any] = {}
    for keyword, value in node.items():
        if keyword == "$ref":
            target = resolver.lookup(value)
            if id(target.contents) in chain:
                raise ValueError(f"schema reference {value!r} is recursive; the checker inlines references")
            referred = _inline_refs(target.contents, target.resolver, (*chain, id(target.contents)))
            inlined.setdefault("allOf", []).append(referred)
        elif keyword in _SUBSCHEMA:
            inlined[keyword] = _inline_refs(value, resolver, chain)
        elif keyword in _SUBSCHEMA_LISTS:
            inlined.setdefault(keyword, []).extend(_inline_refs(item, resolver, chain) for item in value)
        elif keyword in _SUBSCHEMA_MAPS:
            inlined[keyword] = {name: _inline_refs(item, resolver, chain) for name, item in value.items()}
        elif keyword not in ("$defs", "$id"):
            inlined[keyword] = value
    return inlined


# --------------------------------------------------------------------------- messages

_TYPE_WORDS = {
    "number": "a number",
    "integer": "an integer",
    "string": "a string",
    "object": "a mapping",
    "array": "a list",
    "boolean": "true or false",
    "null": "null",
}
_PY_WORDS = {bool: "boolean", int: "integer", float: "number", str: "string"}
_BOUNDS = {"exclusiveMinimum": ">", "minimum": ">=", "exclusiveMaximum": "<", "maximum": "<="}


def _describe(value: Any) -> str:
    """``string 'abc'``, ``integer 5``, ``a mapping``, ``a list``, ``null``."""
    if value is None:
        return "null"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    return f"{_PY_WORDS.get(type(value), type(value).__name__)} {quoted(value)}"


def _to_problem(error: ValidationError) -> Problem:
    """Translate one jsonschema error into a path and a short, specific message."""
    path: PathParts = tuple(error.absolute_path)
    keyword, expected, value = error.validator, error.validator_value, error.instance
    if "propertyNames" in error.absolute_schema_path:
        path += (value,)  # the offending key itself
    if keyword == "required":
        missing = next(name for name in expected if name not in value)
        return Problem(path + (missing,), "missing required field")
    if keyword == "additionalProperties":
        allowed = list(error.schema.get("properties", {}))
        extra = next(key for key in value if key not in allowed)
        close = difflib.get_close_matches(str(extra), allowed, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        return Problem(path + (extra,), f"unknown field{hint}; allowed: {', '.join(allowed)}")
    return Problem(path, _message(error, keyword, expected, value))


def _message(error: ValidationError, keyword: str | None, expected: Any, value: Any) -> str:
    if keyword == "type":
        kinds = [expected] if isinstance(expected, str) else list(expected)
        return f"must be {' or '.join(_TYPE_WORDS[k] for k in kinds)}, got {_describe(value)}"
    if keyword in _BOUNDS:
        return f"must be {_BOUNDS[keyword]} {expected!r}, got {quoted(value)}"
    if keyword == "enum":
        title = error.schema.get("title")
        if title:
            return f"unknown {title} {quoted(value)}; known: {', '.join(map(str, expected))}"
        return f"must be one of {', '.join(map(repr, expected))}; got {quoted(value)}"
    if keyword in ("minItems", "minProperties", "minLength") and expected == 1:
        return "must not be empty"
    if keyword == "uniqueItems":
        return f"items must be unique; {_first_duplicate(value)!r} appears more than once"
    if keyword == "pattern":
        rule = error.schema.get("title")
        return (
            f"must be {rule}, got {quoted(value)}"
            if rule
            else f"must match the pattern {expected!r}, got {quoted(value)}"
        )
    if keyword == "maxLength":
        return f"must be at most {expected} characters long, got {len(value)}"
    if keyword in (None, "not"):  # a `false` schema or `not: {}`: the key is forbidden here
        return "is not allowed here"
    return error.message


def _first_duplicate(items: Sequence[Any]) -> Any:
    for index, item in enumerate(items):
        if item in items[:index]:
            return item
    return None


def _position(document: Any, path: PathParts) -> tuple[int, ...]:
    """Where `path` is in `document`, as sortable indices (keys in file order; absent keys last)."""
    position = []
    node = document
    for part in path:
        if isinstance(node, dict):
            keys = list(node)
            position.append(keys.index(part) if part in node else len(keys))
            node = node.get(part)
        elif isinstance(node, list) and isinstance(part, int) and part < len(node):
            position.append(part)
            node = node[part]
        else:
            break
    return tuple(position)


def first_non_finite(document: Any, path: PathParts = ()) -> Problem | None:
    """The first NaN or infinite number in `document` (JSON-schema bounds let them through)."""
    if isinstance(document, float) and not math.isfinite(document):
        return Problem(path, f"must be a finite number, got {document!r}")
    children: Iterator[tuple[str | int, Any]]
    if isinstance(document, dict):
        children = iter(document.items())
    elif isinstance(document, list):
        children = enumerate(document)
    else:
        return None
    for key, child in children:
        problem = first_non_finite(child, path + (key,))
        if problem:
            return problem
    return None


# --------------------------------------------------------------------------- merging


def deep_merge(base: Mapping, override: Mapping) -> dict:
    """`override` merged over `base`: mappings recursively, anything else replaced (copies)."""
    merged = copy.deepcopy(dict(base))
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(merged.get(key), Mapping):
            merged[key] = deep_merge(merged[key], value)
        else:
            merged[key] = copy.deepcopy(value)
    return merged


def with_floats(value: Any) -> Any:
    """`value` with every int (not bool) turned into a float, recursively."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        return float(value)
    if isinstance(value, dict):
        return {key: with_floats(item) for key, item in value.items()}
    if isinstance(value, list):
        return [with_floats(item) for item in value]
    return value
