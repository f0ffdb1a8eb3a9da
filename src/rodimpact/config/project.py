"""The loaded configuration (:class:`Project`), its errors (:class:`ConfigError`) and the file
they are found in (:class:`ConfigFile`).

:mod:`rodimpact.config.load` reads and checks the YAML, and :mod:`rodimpact.config.builder`
resolves the case files; this module holds what they return and raise, and the handle of a file
being read (:class:`ConfigFile`), which locates a problem in that file.
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

__all__ = ["ConfigError", "ConfigFile", "Project"]


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
class ConfigFile:
    """A configuration file being read, with its name as messages show it.

    Attributes
    ----------
    path : pathlib.Path
        Where the file is.
    label : str
        Its name in messages: relative to the project's root when it lies under it.
    """

    path: Path
    label: str

    @classmethod
    def under(cls, path: str | Path, root: Path) -> ConfigFile:
        """The file at ``path``, relative to ``root`` unless absolute, labelled relative to ``root``.

        Parameters
        ----------
        path : str or pathlib.Path
            The file, absolute or relative to ``root``.
        root : pathlib.Path
            The project's root.

        Returns
        -------
        ConfigFile
        """
        path = Path(path) if Path(path).is_absolute() else root / path
        try:
            label = path.resolve().relative_to(root.resolve()).as_posix()
        except ValueError:
            label = str(path)
        return cls(path, label)

    def error(self, message: str, *, case: str | None = None, field: str | None = None) -> ConfigError:
        """A :class:`ConfigError` in this file, optionally naming the case and the field.

        Parameters
        ----------
        message : str
            What is wrong.
        case : str, optional
            The case's id.
        field : str, optional
            The field's dotted path.

        Returns
        -------
        ConfigError
            Not raised: the caller raises it.
        """
        return ConfigError(message, file=self.label, case=case, field=field)

    def read(self) -> Any:
        """The file's YAML content (None when empty).

        Raises
        ------
        ConfigError
            The file is missing, unreadable or not YAML.
        """
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
        """Check ``document``, read from this file, against a schema.

        Parameters
        ----------
        document : Any
            The file's content.
        schemas : Schemas
            The project's schemas.
        schema : str
            The schema's name (and its fragment, if any).
        fill : bool
            Fill in the schema's defaults while checking.

        Raises
        ------
        ConfigError
            The first schema problem or non-finite number in ``document``, naming the case when
            it lies in ``cases[i]`` of a case file.
        """
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
