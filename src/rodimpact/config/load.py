"""Configuration: read, check and resolve the global config, materials and case files.

The project is described by YAML only:

* ``config/config.yaml`` (global; ``workflow/schemas/config.schema.yaml``),
* ``config/materials.yaml`` (named materials; ``materials.schema.yaml``),
* ``config/cases/*.yaml`` (case files; ``cases.schema.yaml``), each file one case set,
  optionally expanded over named variants.

:func:`load_project` turns them into fully resolved cases (plain JSON types) or raises
:class:`ConfigError` for the first problem, naming the file, the case and the field (each
kept as data on the error). The methods, their settings and the settings' bounds and
defaults come from the method registry (:mod:`rodimpact.solvers.registry`); the schema
files name no method (:func:`registry_schema` is merged into them when they are read).
"""

from __future__ import annotations

import copy
import logging
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from rodimpact.config.bodies import check_material_ranges
from rodimpact.config.builder import CASES_SCHEMA, COMPLETE_MATERIAL, METHODS, OUTPUTS, ProjectBuilder
from rodimpact.config.project import ConfigError, ConfigFile, Project
from rodimpact.config.schema import Schemas
from rodimpact.config.yamlfile import YamlError
from rodimpact.contact.laws import contact_schema
from rodimpact.solvers.field import FieldGrid
from rodimpact.solvers.registry import METHODS as METHOD_REGISTRY

__all__ = [
    "ConfigError",
    "METHODS",
    "OUTPUTS",
    "Project",
    "load_case_file",
    "load_global_config",
    "load_project",
    "registry_schema",
]

logger = logging.getLogger(__name__)

DEFAULT_SCHEMA_DIR = Path("workflow") / "schemas"
DEFAULT_CONFIG_FILE = "config/config.yaml"
CONFIG_SCHEMA = "config.schema.yaml"
MATERIALS_SCHEMA = "materials.schema.yaml"
#: What a resolved case's materials refer to: a name or a complete inline material.


def registry_schema() -> dict[str, Any]:
    """What the method registry adds to ``config.schema.yaml``: the method names
    (``$defs/method``), each method's settings with their bounds and defaults
    (``$defs/numerics_<method>``, and ``numerics.<method>``), and the union of all settings
    (``$defs/method_numerics_fields``, a case's overrides: checked per method by the loader);
    and to ``cases.schema.yaml`` the settings of the strain field's grid (``$defs/field_grid``,
    :class:`~rodimpact.solvers.field.FieldGrid`) and the ``contact`` block from the contact
    laws' declarations (``$defs/contact``; ``$defs/resolved_contact``, with complete materials:
    :func:`~rodimpact.contact.laws.contact_schema`).
    """
    defs: dict[str, Any] = {
        "method": {
            "title": "method",
            "type": "string",
            "enum": list(METHOD_REGISTRY),
            "description": "A computation method of the registry (rodimpact.solvers.registry.METHODS).",
        }
    }
    union: dict[str, Any] = {}
    for name, spec in METHOD_REGISTRY.items():
        schema = spec.options.json_schema()
        defs[f"numerics_{name}"] = schema
        for field, sub in schema["properties"].items():
            loose = {key: value for key, value in sub.items() if key in ("type", "enum", "description")}
            union[field] = loose if field not in union else {**union[field], **loose}
    defs["method_numerics_fields"] = {
        "description": "Numerical settings of any method, all optional (each method's own are checked by the loader).",
        "type": "object",
        "additionalProperties": False,
        "properties": union,
    }
    numerics = {name: {"$ref": f"#/$defs/numerics_{name}", "default": {}} for name in METHOD_REGISTRY}
    return {
        CONFIG_SCHEMA: {"$defs": defs, "properties": {"numerics": {"properties": numerics}}},
        CASES_SCHEMA: {
            "$defs": {
                "field_grid": FieldGrid.json_schema(),
                "contact": contact_schema(),
                "resolved_contact": contact_schema(COMPLETE_MATERIAL),
            }
        },
    }


def _load_schemas(schema_dir: Path, root: Path) -> Schemas:
    try:
        return Schemas(schema_dir, extra=registry_schema())
    except FileNotFoundError as exc:
        raise ConfigFile.under(exc.filename or schema_dir, root).error("schema file not found") from None
    except YamlError as exc:
        raise ConfigFile.under(exc.path, root).error(f"bad schema: {exc}") from None


def _find_root(path: Path) -> Path:
    """The nearest directory above `path` that holds the schemas (else the working directory)."""
    for directory in path.resolve().parents:
        if (directory / DEFAULT_SCHEMA_DIR / CONFIG_SCHEMA).is_file():
            return directory
    return Path.cwd()


def _checked_config(config: Any, source: ConfigFile, schemas: Schemas) -> dict:
    """A checked deep copy of the global config, its defaults filled in."""
    config = {} if config is None else copy.deepcopy(config)
    config = dict(config) if isinstance(config, Mapping) else config
    source.check(config, schemas, CONFIG_SCHEMA, fill=True)
    for method, block in config.get("numerics", {}).items():  # each method's settings in declaration order
        config["numerics"][method] = {name: block[name] for name in METHOD_REGISTRY[method].options.names()}
    return config


def load_global_config(path: str | Path, schema_dir: str | Path | None = None) -> dict:
    """Read and check the global config file and fill in its defaults.

    Parameters
    ----------
    path
        The global config file (e.g. ``config/config.yaml``).
    schema_dir
        Directory of the JSON schemas; default ``workflow/schemas`` under the project root,
        the nearest directory above `path` that holds it.

    Returns
    -------
    dict
        The config with every default of ``config.schema.yaml`` filled in.

    Raises
    ------
    ConfigError
        If the file is missing, not YAML, or breaks the schema.
    """
    path = Path(path)
    root = _find_root(path)
    schemas = _load_schemas(Path(schema_dir) if schema_dir else root / DEFAULT_SCHEMA_DIR, root)
    source = ConfigFile.under(path, root)
    return _checked_config(source.read(), source, schemas)


def load_project(
    config: Mapping,
    root: str | Path = ".",
    schema_dir: str | Path | None = None,
    *,
    config_file: str | Path = DEFAULT_CONFIG_FILE,
) -> Project:
    """Read the materials and every case file named by `config`; check and resolve the cases.

    Parameters
    ----------
    config
        The global config (as read by snakemake or :func:`load_global_config`); it is checked
        again, on a copy, with its defaults filled in.
    root
        Project root: ``cases_dir`` and ``materials`` are relative to it, and so are the file
        names in messages.
    schema_dir
        Directory of the JSON schemas (default ``<root>/workflow/schemas``).
    config_file
        Name of the global config file, used only in error messages.

    Returns
    -------
    Project
        All cases, resolved: files in name order, cases in file order, each case expanded
        over its variants.

    Raises
    ------
    ConfigError
        For the first problem found (files in name order, each from top to bottom).
    """
    root = Path(root)
    schemas = _load_schemas(Path(schema_dir) if schema_dir else root / DEFAULT_SCHEMA_DIR, root)
    config_source = ConfigFile.under(config_file, root)
    checked = _checked_config(config, config_source, schemas)
    builder = ProjectBuilder(checked, config_source, _load_materials(checked, root, schemas))
    for source in _case_files(checked, root, config_source):
        builder.add_file(source, schemas)
    project = builder.build()
    logger.info("loaded %d cases in %d sets", len(project.cases), len(project.sets))
    return project


def load_case_file(path: str | Path, config: Mapping, root: str | Path = ".") -> dict[str, dict]:
    """The resolved cases of one case file (not its sweeps), checked as :func:`load_project`
    checks them, against the global ``config`` and the materials it names; a file anywhere
    (``rodimpact run``). Raises :class:`ConfigError` like :func:`load_project`."""
    root = Path(root)
    schemas = _load_schemas(root / DEFAULT_SCHEMA_DIR, root)
    config_source = ConfigFile.under(DEFAULT_CONFIG_FILE, root)
    checked = _checked_config(config, config_source, schemas)
    builder = ProjectBuilder(checked, config_source, _load_materials(checked, root, schemas))
    builder.add_file(ConfigFile.under(path, root), schemas)
    return builder.cases


def _load_materials(config: dict, root: Path, schemas: Schemas) -> dict[str, dict]:
    source = ConfigFile.under(config["materials"], root)
    document = source.read()
    if document is None:
        raise source.error("file is empty; expected a 'materials' mapping")
    source.check(document, schemas, MATERIALS_SCHEMA)
    check_material_ranges(document["materials"], source.error)
    return document["materials"]


def _case_files(config: dict, root: Path, config_source: ConfigFile) -> list[ConfigFile]:
    directory = ConfigFile.under(config["cases_dir"], root)
    if not directory.path.is_dir():
        raise config_source.error(f"directory not found: {directory.label}", field="cases_dir")
    for other in sorted(directory.path.glob("*.yml")):
        if not other.name.startswith("."):
            raise ConfigFile.under(other, root).error(
                f"a case file ends in .yaml; rename it {other.stem}.yaml (only *.yaml files are read)"
            )
    # a case file below the directory is not read: refused by name, never ignored (a directory
    # beside the case files holds what they point to, such as force histories)
    for nested in sorted(directory.path.rglob("*.y*ml")):
        inner = nested.relative_to(directory.path)
        if len(inner.parts) > 1 and not any(part.startswith(".") for part in inner.parts):
            raise ConfigFile.under(nested, root).error(
                f"a case file in a subdirectory is not read; move it to {directory.label}/ (only "
                f"{directory.label}/*.yaml are case files)"
            )
    paths = sorted(p for p in directory.path.glob("*.yaml") if not p.name.startswith("."))
    if not paths:
        raise config_source.error(f"no *.yaml case files in {directory.label}", field="cases_dir")
    return [ConfigFile.under(p, root) for p in paths]
