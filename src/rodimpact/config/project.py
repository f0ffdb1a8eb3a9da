"""The loaded configuration (:class:`Project`) and its errors (:class:`ConfigError`).

:mod:`rodimpact.config.load` reads and checks the YAML; this module holds what it returns and
raises, and the file handle (:class:`_File`) that locates a problem in a file.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from dataclasses import field as dataclass_field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rodimpact.config.paths import format_path

if TYPE_CHECKING:
    from rodimpact.config.schema import Problem, Schemas

__all__ = ["ConfigError", "Project"]


class ConfigError(ValueError):
    """One clear message naming the file, the case and the field.

    ``str(err)`` is ``"<file>: case '<id>': field '<dotted.path[0]>': <message>"``, the case
    and field parts left out when they do not apply. The parts are kept as the attributes
    `file`, `case`, `field` and `reason` (the message alone).
    """

    def __init__(self, message: str, *, file: str, case: str | None = None, field: str | None = None):
        self.reason, self.file, self.case, self.field = message, str(file), case, field
        parts = [self.file]
        if case is not None:
            parts.append(f"case '{case}'")
        if field:
            parts.append(f"field '{field}'")
        super().__init__(": ".join([*parts, message]))

    def __reduce__(self):
        rebuild = functools.partial(ConfigError, file=self.file, case=self.case, field=self.field)
        return rebuild, (self.reason,)


@dataclass(frozen=True)
class _File:
    """A file being read, with its name as shown in messages (relative to the root)."""

    path: Path
    label: str

    @classmethod
    def under(cls, path: str | Path, root: Path) -> _File:
        path = Path(path) if Path(path).is_absolute() else root / path
        try:
            label = path.resolve().relative_to(root.resolve()).as_posix()
        except ValueError:
            label = str(path)
        return cls(path, label)

    def error(self, message: str, *, case: str | None = None, field: str | None = None):
        return ConfigError(message, file=self.label, case=case, field=field)

    def read(self) -> Any:
        """The file's YAML content (None when empty); ConfigError if missing or not YAML."""
        from rodimpact.config.yamlfile import YamlError, read_yaml  # the checker's; a checked Project needs none

        try:
            return read_yaml(self.path)
        except FileNotFoundError:
            raise self.error("file not found") from None
        except (IsADirectoryError, UnicodeDecodeError) as exc:
            raise self.error(f"cannot read file: {exc}") from None
        except YamlError as exc:
            raise self.error(str(exc)) from None

    def check(self, document: Any, schemas: Schemas, schema: str, *, fill: bool = False) -> None:
        """Raise ConfigError for the first schema problem or non-finite number in `document`."""
        from rodimpact.config.schema import first_non_finite

        problem = schemas.first_problem(document, schema, fill_defaults=fill)
        problem = problem or first_non_finite(document)
        if problem:
            raise self._located(problem, document)

    def _located(self, problem: Problem, document: Any) -> ConfigError:
        """The error, naming the case when the problem lies in ``cases[i]`` of a case file."""
        path = problem.path
        if len(path) >= 2 and path[0] == "cases" and isinstance(path[1], int):
            entry = document["cases"][path[1]]
            case_id = entry.get("id") if isinstance(entry, dict) else None
            if isinstance(case_id, str) and case_id and path[2:] != ("id",):  # not an id at fault
                field = format_path(path[2:]) or None
                return self.error(problem.message, case=case_id, field=field)
        return self.error(problem.message, field=format_path(path) or None)


@dataclass(frozen=True)
class Project:
    """All resolved cases of the project.

    Attributes
    ----------
    cases
        Resolved case dicts keyed by id, in file order (files sorted by name).
    sets
        Case set name -> case ids, in file order.
    variants
        Case set name -> {variant name -> variant mapping as written}.
    compare
        Case set name -> its ``compare`` options as written (``x``, ``title``, ``reference``;
        empty when its files give none).
    calibrate
        Case set name -> its ``calibrate`` block as checked (:mod:`.calibration`); sets
        without one are absent.
    sweeps
        Resolved sweep cases keyed by id (not in ``cases`` nor ``sets``): a case with its
        ``sweep`` (``description``, ``methods``, ``parameters``: name -> sorted values).
    config
        The global configuration as checked, every default filled in.
    """

    cases: dict[str, dict]
    sets: dict[str, list[str]]
    variants: dict[str, dict]
    compare: dict[str, dict] = dataclass_field(default_factory=dict)
    calibrate: dict[str, dict] = dataclass_field(default_factory=dict)
    sweeps: dict[str, dict] = dataclass_field(default_factory=dict)
    config: dict[str, Any] = dataclass_field(default_factory=dict)

    def sweeps_in(self, set_name: str, variant: str | None = None) -> list[dict]:
        """The sweep cases of a set (none if it has none), optionally of one variant."""
        return [
            case
            for case in self.sweeps.values()
            if case["set"] == set_name and (variant is None or case["variant"] == variant)
        ]

    def cases_in(self, set_name: str, variant: str | None = None) -> list[dict]:
        """The resolved cases of a set, optionally only those of one variant.

        Raises
        ------
        KeyError
            If the set, or the variant of that set, does not exist.
        """
        if set_name not in self.sets:
            raise KeyError(f"unknown case set {set_name!r}; known: {', '.join(self.sets)}")
        known = self.variants.get(set_name, {})
        if variant is not None and variant not in known:
            listed = ", ".join(known) or "none"
            raise KeyError(f"unknown variant {variant!r} of case set {set_name!r}; known: {listed}")
        return [
            self.cases[case_id]
            for case_id in self.sets[set_name]
            if variant is None or self.cases[case_id]["variant"] == variant
        ]
