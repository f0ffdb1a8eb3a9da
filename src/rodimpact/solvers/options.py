"""Numerical options, declared once: a dataclass field per setting, with its doc, unit and bounds.

Each method's options class (a frozen dataclass deriving from :class:`Options`) declares its
settings with :func:`setting`. Everything else is read from those declarations:

- the check of every value (:meth:`Options.__post_init__`, :class:`OptionError` naming the
  setting);
- the JSON schema of the method's block in ``config.yaml``'s ``numerics`` and in a case's
  overrides (:meth:`Options.json_schema`; :mod:`rodimpact.config.load` injects it), with the
  defaults the configuration is filled with;
- the list of a method's settings (:meth:`Options.names`) and the conversion of a resolved
  mapping into options (:meth:`Options.from_settings`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, ClassVar, Mapping, TypeVar

__all__ = ["OptionError", "Options", "Setting", "setting"]

T = TypeVar("T", bound="Options")

_KIND_SCHEMA = {float: "number", int: "integer", bool: "boolean", str: "string"}
_KIND_WORD = {float: "a number", int: "an integer", bool: "true or false", str: "a string"}


class OptionError(ValueError):
    """A numerical setting is out of its bounds, or settings contradict each other.

    Attributes
    ----------
    field : str
        The setting at fault (a field of the options class).
    reason : str
        What is wrong, without the setting's name.
    """

    def __init__(self, field: str, reason: str) -> None:
        self.field, self.reason = field, reason
        super().__init__(f"{field} {reason}")

    def __reduce__(self):
        return OptionError, (self.field, self.reason)


@dataclass(frozen=True)
class Setting:
    """The declaration of one setting: what it means, its unit and the values it takes."""

    doc: str
    unit: str = "1"
    kind: type = float
    nullable: bool = False
    minimum: float | None = None
    exclusive_minimum: float | None = None
    maximum: float | None = None
    exclusive_maximum: float | None = None
    choices: tuple[Any, ...] = ()

    def bounds_text(self) -> str:
        """The bounds as a short phrase, e.g. ``>= 10`` or ``> 0 and < 1``."""
        parts = [f"{op} {value:g}" for op, value in ((">=", self.minimum), (">", self.exclusive_minimum),
                                                     ("<=", self.maximum), ("<", self.exclusive_maximum))
                 if value is not None]
        return " and ".join(parts)

    def problem(self, value: Any) -> str | None:
        """What is wrong with ``value`` (a reason starting with "must"), or None."""
        if value is None:
            return None if self.nullable else f"must be {_KIND_WORD[self.kind]}, got None"
        if self.kind is bool:
            return None if isinstance(value, bool) else f"must be true or false, got {value!r}"
        if self.choices:
            return None if value in self.choices else (
                f"must be one of {', '.join(map(repr, self.choices))}; got {value!r}")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return f"must be {_KIND_WORD[self.kind]}, got {value!r}"
        if self.kind is int and int(value) != value:
            return f"must be an integer, got {value!r}"
        if not math.isfinite(value):
            return f"must be a finite number, got {value!r}"
        ok = ((self.minimum is None or value >= self.minimum)
              and (self.exclusive_minimum is None or value > self.exclusive_minimum)
              and (self.maximum is None or value <= self.maximum)
              and (self.exclusive_maximum is None or value < self.exclusive_maximum))
        return None if ok else f"must be {self.bounds_text()}, got {value!r}"

    def json_schema(self, default: Any) -> dict[str, Any]:
        """This setting's JSON schema (draft 2020-12), with ``default``."""
        unit = "" if self.unit == "1" else f" Unit: {self.unit}."
        schema: dict[str, Any] = {"description": f"{self.doc}{unit}"}
        kind = _KIND_SCHEMA[self.kind]
        schema["type"] = [kind, "null"] if self.nullable else kind
        if self.choices:
            schema["enum"] = list(self.choices)
        for key, value in (("minimum", self.minimum), ("exclusiveMinimum", self.exclusive_minimum),
                           ("maximum", self.maximum), ("exclusiveMaximum", self.exclusive_maximum)):
            if value is not None:
                schema[key] = value
        schema["default"] = default
        return schema


def setting(default: Any, doc: str, *, unit: str = "1", kind: type = float, nullable: bool = False,
            minimum: float | None = None, exclusive_minimum: float | None = None,
            maximum: float | None = None, exclusive_maximum: float | None = None,
            choices: tuple[Any, ...] = ()) -> Any:
    """A dataclass field declaring one numerical setting.

    Parameters
    ----------
    default
        The value a configuration that does not set it gets.
    doc : str
        What the setting does (one or two sentences; it becomes the schema's description).
    unit : str
        SI unit, ``"1"`` for a number without unit.
    kind : {float, int, bool, str}
        The value's type.
    nullable : bool
        None (YAML ``null``) is allowed, with the meaning the doc gives it.
    minimum, exclusive_minimum, maximum, exclusive_maximum : float, optional
        Bounds of a number.
    choices : tuple
        The values a string setting may take.
    """
    meta = Setting(doc=doc, unit=unit, kind=kind, nullable=nullable, minimum=minimum,
                   exclusive_minimum=exclusive_minimum, maximum=maximum, exclusive_maximum=exclusive_maximum,
                   choices=tuple(choices))
    return dataclasses.field(default=default, metadata={"setting": meta})


@dataclass(frozen=True)
class Options:
    """Base of every method's options: settings declared with :func:`setting`, checked on creation."""

    #: What the method's block of settings is, for the schema's description.
    DESCRIPTION: ClassVar[str] = ""

    def __post_init__(self) -> None:
        for name, meta in self.settings().items():
            reason = meta.problem(getattr(self, name))
            if reason is not None:
                raise OptionError(name, reason)

    @classmethod
    def settings(cls) -> dict[str, Setting]:
        """Setting name -> its declaration, in declaration order."""
        return {f.name: f.metadata["setting"] for f in dataclasses.fields(cls) if "setting" in f.metadata}

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The setting names, in declaration order."""
        return tuple(cls.settings())

    @classmethod
    def defaults(cls) -> dict[str, Any]:
        """Setting name -> default."""
        return {f.name: f.default for f in dataclasses.fields(cls) if "setting" in f.metadata}

    @classmethod
    def from_settings(cls: type[T], data: Mapping[str, Any]) -> T:
        """Options from a resolved mapping of settings (missing ones: defaults; others ignored).

        Numbers are converted to the setting's kind (a YAML ``5`` for a float setting is 5.0);
        values of the wrong type are left for the check to refuse, by name.
        """
        values = {}
        for name, meta in cls.settings().items():
            if name not in data:
                continue
            value = data[name]
            if value is not None and not isinstance(value, bool):
                if meta.kind is float and isinstance(value, int):
                    value = float(value)
                elif meta.kind is int and isinstance(value, float) and value.is_integer():
                    value = int(value)
            values[name] = value
        return cls(**values)

    @classmethod
    def json_schema(cls) -> dict[str, Any]:
        """The JSON schema of this method's settings, every one optional and defaulted."""
        defaults = cls.defaults()
        return {"description": cls.DESCRIPTION or cls.__doc__.strip().splitlines()[0],
                "type": "object", "additionalProperties": False,
                "properties": {name: meta.json_schema(defaults[name]) for name, meta in cls.settings().items()}}

    def check(self, problem: Any) -> None:
        """Checks that need the case (e.g. a stability limit); raise :class:`OptionError`.

        The base class has none.
        """

    def as_settings(self) -> dict[str, Any]:
        """Setting name -> value (plain Python values)."""
        return {name: getattr(self, name) for name in self.names()}
