"""Settings, declared once: a dataclass field per setting, with its doc, unit and bounds.

A block of settings is a frozen dataclass deriving from :class:`Settings` whose fields are
declared with :func:`setting`. Everything else is read from those declarations:

- the check of every value (:meth:`Settings.__post_init__`, :class:`OptionError` naming the
  setting, with the path into nested blocks, e.g. ``film.thickness_m``);
- the block's JSON schema (:meth:`Settings.json_schema`), with descriptions, units, bounds,
  defaults and the required settings;
- the conversion from a plain mapping (YAML) into the block (:meth:`Settings.from_settings`)
  and back (:meth:`Settings.as_settings`).

A setting's value is a number, an integer, a boolean or a string (``kind``); a nested block
(``kind`` a :class:`Settings` subclass, e.g. a film inside a contact law's settings); a
:class:`Material` (a material's three constants, resolved by the configuration from a name
or an inline mapping); or a list of any of these (``items=(min, max)`` counts).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar, TypeVar

__all__ = ["REQUIRED", "Material", "MissingSetting", "OptionError", "Setting", "Settings", "setting"]

T = TypeVar("T", bound="Settings")

_KIND_SCHEMA = {float: "number", int: "integer", bool: "boolean", str: "string"}
_KIND_WORD = {float: "a number", int: "an integer", bool: "true or false", str: "a string"}


class _Required:
    """The default of a setting a block cannot do without (:data:`REQUIRED`)."""

    def __repr__(self) -> str:
        return "REQUIRED"


#: ``setting(REQUIRED, ...)``: the setting has no default and must be given.
REQUIRED: Any = _Required()


class OptionError(ValueError):
    """A setting is out of its bounds, missing, or settings contradict each other.

    Attributes
    ----------
    field : str
        The setting at fault (its key; ``outer.inner`` or ``outer[2].inner`` inside nested
        blocks).
    reason : str
        What is wrong, without the setting's name.
    """

    def __init__(self, field: str, reason: str) -> None:
        self.field, self.reason = field, reason
        super().__init__(f"{field} {reason}")

    def __reduce__(self):
        return OptionError, (self.field, self.reason)

    def inside(self, prefix: str) -> OptionError:
        """The same error for the block at ``prefix`` (``prefix.field``)."""
        error = OptionError.__new__(type(self))
        OptionError.__init__(error, f"{prefix}.{self.field}", self.reason)
        return error


class MissingSetting(OptionError):
    """A setting declared :data:`REQUIRED` is not given (``field``: its path)."""

    def __init__(self, field: str) -> None:
        super().__init__(field, "is required")

    def __reduce__(self):
        return MissingSetting, (self.field,)


class Material:
    """The kind of a setting whose value is a material: a mapping with ``name``,
    ``youngs_modulus_pa`` (Pa), ``poisson_ratio`` and ``density_kg_m3`` (kg/m^3); where it
    yields, ``yield_stress_pa`` and ``hardening_modulus_pa`` (Pa); and, where its source gives
    them, ``ranges`` (constant -> [low, high]).

    A case names a material or gives it inline; the configuration resolves it (the
    ``material`` resolver of :meth:`Settings.from_settings`) before the block is built.
    """

    CONSTANTS: ClassVar[tuple[str, ...]] = ("youngs_modulus_pa", "poisson_ratio", "density_kg_m3")
    #: The constants of a material that yields, each optional: without ``yield_stress_pa`` the
    #: material stays elastic, without ``hardening_modulus_pa`` it is perfectly plastic.
    PLASTIC: ClassVar[tuple[str, ...]] = ("yield_stress_pa", "hardening_modulus_pa")

    @classmethod
    def problem(cls, value: Any) -> str | None:
        """What is wrong with a resolved material, or None."""
        if not isinstance(value, Mapping):
            return f"must be a material (its constants), got {value!r}"
        missing = [key for key in cls.CONSTANTS if key not in value]
        if missing:
            return f"must give {', '.join(missing)}"
        modulus, nu, rho = (value[key] for key in cls.CONSTANTS)
        if not all(
            isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in (modulus, nu, rho)
        ):
            return "must have finite numbers as constants"
        if not (modulus > 0 and rho > 0 and -1.0 < nu < 0.5):
            return f"must have E > 0, density > 0 and -1 < nu < 0.5, got {modulus!r}, {rho!r}, {nu!r}"
        plastic = cls.plastic_problem(modulus, value.get("yield_stress_pa"), value.get("hardening_modulus_pa"))
        return None if plastic is None else f"{plastic[0]} {plastic[1]}"

    @staticmethod
    def plastic_problem(
        youngs_modulus_pa: float, yield_stress_pa: float | None, hardening_modulus_pa: float | None
    ) -> tuple[str, str] | None:
        """What is wrong with a material's plastic constants, as (constant, reason), or None.

        The yield stress must be a positive finite number; a hardening modulus needs a yield
        stress and lies in [0, E): the elastic-plastic tangent E H / (E + H) stays below E.
        """
        if yield_stress_pa is not None and not (
            isinstance(yield_stress_pa, (int, float)) and math.isfinite(yield_stress_pa) and yield_stress_pa > 0
        ):
            return "yield_stress_pa", f"must be > 0, got {yield_stress_pa!r}"
        if hardening_modulus_pa is None:
            return None
        if yield_stress_pa is None:
            return "hardening_modulus_pa", "needs a yield_stress_pa: a material without one stays elastic"
        if not (
            isinstance(hardening_modulus_pa, (int, float))
            and math.isfinite(hardening_modulus_pa)
            and 0 <= hardening_modulus_pa < youngs_modulus_pa
        ):
            return (
                "hardening_modulus_pa",
                f"must be >= 0 and below Young's modulus {youngs_modulus_pa:g} Pa, got {hardening_modulus_pa!r}",
            )
        return None


@dataclass(frozen=True)
class Setting:
    """The declaration of one setting: what it means, its unit and the values it takes.

    ``kind`` is float, int, bool or str; a :class:`Settings` subclass (a nested block); or
    :class:`Material`. With ``items=(min, max)`` the value is a list of ``min`` to ``max``
    values of that kind (``max`` None: no upper count), each within the bounds. ``key`` is the
    setting's name in a mapping when it differs from the field's (a Python keyword, ``from``).
    """

    doc: str
    unit: str = "1"
    kind: Any = float
    nullable: bool = False
    minimum: float | None = None
    exclusive_minimum: float | None = None
    maximum: float | None = None
    exclusive_maximum: float | None = None
    choices: tuple[Any, ...] = ()
    items: tuple[int, int | None] | None = None
    key: str | None = None

    @property
    def nested(self) -> bool:
        """The value is a nested block of settings."""
        return isinstance(self.kind, type) and issubclass(self.kind, Settings)

    def bounds_text(self) -> str:
        """The bounds as a short phrase, e.g. ``>= 10`` or ``> 0 and < 1``."""
        parts = [
            f"{op} {value:g}"
            for op, value in (
                (">=", self.minimum),
                (">", self.exclusive_minimum),
                ("<=", self.maximum),
                ("<", self.exclusive_maximum),
            )
            if value is not None
        ]
        return " and ".join(parts)

    def problem(self, value: Any) -> str | None:
        """What is wrong with ``value`` (a reason starting with "must"), or None."""
        if value is None:
            return None if self.nullable else f"must be {self._word()}, got None"
        if self.items is not None:
            low, high = self.items
            if not isinstance(value, (list, tuple)):
                return f"must be a list, got {value!r}"
            if len(value) < low or (high is not None and len(value) > high):
                count = f"{low}" if low == high else f"{low} to {high}" if high is not None else f"at least {low}"
                return f"must have {count} items, got {len(value)}"
            for item in value:
                reason = self._item_problem(item)
                if reason is not None:
                    return reason
            return None
        return self._item_problem(value)

    def _word(self) -> str:
        if self.kind is Material:
            return "a material"
        if self.nested:
            return "a mapping"
        return _KIND_WORD[self.kind]

    def _item_problem(self, value: Any) -> str | None:
        if self.kind is Material:
            return Material.problem(value)
        if self.nested:
            return None if isinstance(value, self.kind) else f"must be a mapping, got {value!r}"
        if self.kind is bool:
            return None if isinstance(value, bool) else f"must be true or false, got {value!r}"
        if self.choices:
            return (
                None
                if value in self.choices
                else (f"must be one of {', '.join(map(repr, self.choices))}; got {value!r}")
            )
        if self.kind is str:
            return None if isinstance(value, str) else f"must be a string, got {value!r}"
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return f"must be {_KIND_WORD[self.kind]}, got {value!r}"
        if self.kind is int and int(value) != value:
            return f"must be an integer, got {value!r}"
        if not math.isfinite(value):
            return f"must be a finite number, got {value!r}"
        ok = (
            (self.minimum is None or value >= self.minimum)
            and (self.exclusive_minimum is None or value > self.exclusive_minimum)
            and (self.maximum is None or value <= self.maximum)
            and (self.exclusive_maximum is None or value < self.exclusive_maximum)
        )
        return None if ok else f"must be {self.bounds_text()}, got {value!r}"

    def json_schema(self, default: Any = REQUIRED, *, material_ref: str = "#/$defs/material") -> dict[str, Any]:
        """This setting's JSON schema (draft 2020-12), with ``default`` unless it is
        :data:`REQUIRED`; a material's schema is a reference to ``material_ref``."""
        unit = "" if self.unit == "1" else f" Unit: {self.unit}."
        schema: dict[str, Any] = {"description": f"{self.doc}{unit}"}
        item = self._item_schema(material_ref)
        if self.items is not None:
            low, high = self.items
            schema["type"] = ["array", "null"] if self.nullable else "array"
            schema["minItems"] = low
            if high is not None:
                schema["maxItems"] = high
            schema["items"] = item
        elif "$ref" in item and self.nullable:
            schema["anyOf"] = [item, {"type": "null"}]
        else:
            if self.nullable:
                item["type"] = [item["type"], "null"]
            schema.update(item)
        if default is not REQUIRED:
            schema["default"] = default
        return schema

    def _item_schema(self, material_ref: str) -> dict[str, Any]:
        if self.kind is Material:
            return {"$ref": material_ref}
        if self.nested:
            nested = self.kind.json_schema(material_ref=material_ref)
            nested.pop("description", None)
            return nested
        schema: dict[str, Any] = {"type": _KIND_SCHEMA[self.kind]}
        if self.choices:
            schema["enum"] = list(self.choices)
        for key, value in (
            ("minimum", self.minimum),
            ("exclusiveMinimum", self.exclusive_minimum),
            ("maximum", self.maximum),
            ("exclusiveMaximum", self.exclusive_maximum),
        ):
            if value is not None:
                schema[key] = value
        return schema


def setting(
    default: Any,
    doc: str,
    *,
    unit: str = "1",
    kind: Any = float,
    nullable: bool = False,
    minimum: float | None = None,
    exclusive_minimum: float | None = None,
    maximum: float | None = None,
    exclusive_maximum: float | None = None,
    choices: tuple[Any, ...] = (),
    items: tuple[int, int | None] | None = None,
    key: str | None = None,
) -> Any:
    """A dataclass field declaring one setting.

    Parameters
    ----------
    default
        The value a configuration that does not set it gets; :data:`REQUIRED`: none, the
        setting must be given (declare such blocks ``kw_only``).
    doc : str
        What the setting does (one or two sentences; it becomes the schema's description).
    unit : str
        SI unit, ``"1"`` for a number without unit.
    kind : {float, int, bool, str}, Settings subclass or Material
        The value's type: a plain value, a nested block of settings, or a material.
    nullable : bool
        None (YAML ``null``) is allowed, with the meaning the doc gives it.
    minimum, exclusive_minimum, maximum, exclusive_maximum : float, optional
        Bounds of a number (of each item of a list).
    choices : tuple
        The values a string setting may take.
    items : (int, int or None), optional
        The value is a list of this many items (min, max; max None: unbounded).
    key : str, optional
        The setting's name in a mapping, where it cannot be the field's (``from``).
    """
    meta = Setting(
        doc=doc,
        unit=unit,
        kind=kind,
        nullable=nullable,
        minimum=minimum,
        exclusive_minimum=exclusive_minimum,
        maximum=maximum,
        exclusive_maximum=exclusive_maximum,
        choices=tuple(choices),
        items=items,
        key=key,
    )
    if default is REQUIRED:
        return dataclasses.field(metadata={"setting": meta})
    return dataclasses.field(default=default, metadata={"setting": meta})


#: Resolves a material given by name or inline, at a field path, into its constants.
MaterialResolver = Callable[[Any, str], Mapping[str, Any]]


@dataclass(frozen=True)
class Settings:
    """Base of every block of settings: fields declared with :func:`setting`, checked on creation."""

    #: What the block is, for the schema's description (default: the first line of the docstring).
    DESCRIPTION: ClassVar[str] = ""

    def __post_init__(self) -> None:
        for name, meta in self._fields().items():
            reason = meta.problem(getattr(self, name))
            if reason is not None:
                raise OptionError(meta.key or name, reason)

    @classmethod
    def _fields(cls) -> dict[str, Setting]:
        return {f.name: f.metadata["setting"] for f in dataclasses.fields(cls) if "setting" in f.metadata}

    @classmethod
    def settings(cls) -> dict[str, Setting]:
        """Setting key -> its declaration, in declaration order."""
        return {meta.key or name: meta for name, meta in cls._fields().items()}

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The setting keys, in declaration order."""
        return tuple(cls.settings())

    @classmethod
    def required(cls) -> tuple[str, ...]:
        """The keys of the settings that have no default."""
        return tuple(
            f.metadata["setting"].key or f.name
            for f in dataclasses.fields(cls)
            if "setting" in f.metadata and f.default is dataclasses.MISSING
        )

    @classmethod
    def defaults(cls) -> dict[str, Any]:
        """Setting key -> default (the settings that have one)."""
        return {
            f.metadata["setting"].key or f.name: f.default
            for f in dataclasses.fields(cls)
            if "setting" in f.metadata and f.default is not dataclasses.MISSING
        }

    @classmethod
    def from_settings(cls: type[T], data: Mapping[str, Any], *, material: MaterialResolver | None = None) -> T:
        """The block from a mapping of settings (missing ones: defaults; others ignored).

        Numbers are converted to the setting's kind (a YAML ``5`` for a float setting is 5.0),
        nested mappings to their blocks, and materials through ``material(value, path)`` (by
        default a material must already be resolved); values of the wrong type are left for
        the check to refuse, by name.

        Raises
        ------
        OptionError
            A required setting is missing, or a value is wrong (``field``: its path).
        """
        values = {}
        for name, meta in cls._fields().items():
            key = meta.key or name
            if key not in data:
                continue
            value = data[key]
            if value is not None and meta.items is not None and isinstance(value, (list, tuple)):
                value = [_convert(meta, item, f"{key}[{index}]", material) for index, item in enumerate(value)]
            elif value is not None:
                value = _convert(meta, value, key, material)
            values[name] = value
        missing = [key for key in cls.required() if key not in data]
        if missing:
            raise MissingSetting(missing[0])
        return cls(**values)

    @classmethod
    def json_schema(cls, *, material_ref: str = "#/$defs/material") -> dict[str, Any]:
        """The JSON schema of this block: its settings (defaulted where they have a default),
        the required ones, and no other key."""
        defaults = cls.defaults()
        schema: dict[str, Any] = {
            "description": cls.DESCRIPTION or (cls.__doc__ or "").strip().splitlines()[0],
            "type": "object",
            "additionalProperties": False,
            "properties": {
                key: meta.json_schema(defaults.get(key, REQUIRED), material_ref=material_ref)
                for key, meta in cls.settings().items()
            },
        }
        if cls.required():
            schema["required"] = list(cls.required())
        return schema

    def as_settings(self) -> dict[str, Any]:
        """Setting key -> value, as plain values (nested blocks as mappings, lists as lists)."""
        return {meta.key or name: _plain(getattr(self, name)) for name, meta in self._fields().items()}


def _convert(meta: Setting, value: Any, path: str, material: MaterialResolver | None) -> Any:
    """One value of a mapping as the setting's kind (see :meth:`Settings.from_settings`)."""
    if meta.kind is Material:
        return dict(material(value, path)) if material is not None else value
    if meta.nested:
        if not isinstance(value, Mapping):
            return value  # refused by the check, by name
        inner = None if material is None else (lambda given, where: material(given, f"{path}.{where}"))
        try:
            return meta.kind.from_settings(value, material=inner)
        except OptionError as error:
            raise error.inside(path) from None
    if isinstance(value, bool):
        return value
    if meta.kind is float and isinstance(value, int):
        return float(value)
    if meta.kind is int and isinstance(value, float) and value.is_integer():
        return int(value)
    return value


def _plain(value: Any) -> Any:
    if isinstance(value, Settings):
        return value.as_settings()
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    if isinstance(value, Mapping):
        return {key: _plain(item) for key, item in value.items()}
    return value
