"""Reading one YAML document of the configuration: safely, with bounded aliases.

The loader is PyYAML's safe loader (libyaml's parser when available) that refuses duplicate
keys, reads ``2.1e11`` as a float (YAML 1.2) and takes merge keys (``<<: *defaults``). A
document whose aliases would expand it beyond :data:`MAX_EXPANDED_NODES` nodes is refused
before it is built. Nothing here knows about schemas (:mod:`.schema`) or cases; the
workflow reads ``config.yaml`` with it before snakemake does, for one-line errors.
"""

from __future__ import annotations

import re
from collections.abc import Hashable
from pathlib import Path
from typing import Any

import yaml

from rodimpact.inputs.files import InputFileError, read_text

__all__ = ["MAX_EXPANDED_NODES", "MAX_YAML_BYTES", "YamlError", "read_yaml"]


class YamlError(ValueError):
    """A file is not valid YAML (the message names the line and column; `path` the file)."""

    def __init__(self, message: str, path: Path):
        super().__init__(message)
        self.path = path


_MERGE_TAG = "tag:yaml.org,2002:merge"
#: Most nodes a document may expand to, its aliases followed (a case file has a few thousand):
#: a document of a few nested aliases (the "billion laughs") is refused before it is built.
MAX_EXPANDED_NODES = 200_000
#: The largest YAML file read, bytes (a case file of a thousand cases is under 1 MB).
MAX_YAML_BYTES = 16 * 1024 * 1024


class _Loader(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):  # libyaml's parser when available
    """Safe loader that rejects duplicate keys and reads ``2.1e11`` as a float (YAML 1.2)."""

    def construct_mapping(self, node: yaml.MappingNode, deep: bool = False) -> dict:
        seen: set[Any] = set()
        for key_node, _ in node.value:
            if key_node.tag == _MERGE_TAG:
                continue  # `<<: *defaults`: merged (and overridden by the keys here) by the base class
            key = self.construct_object(key_node, deep=True)
            if not isinstance(key, Hashable):
                continue  # the base class reports unhashable keys
            if key in seen:
                raise yaml.constructor.ConstructorError(None, None, f"duplicate key {key!r}", key_node.start_mark)
            seen.add(key)
        return super().construct_mapping(node, deep)


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:[0-9][0-9_]*)(?:\.[0-9_]*)?[eE][-+]?[0-9]+$"),
    list("-+0123456789"),
)


def read_yaml(path: Path) -> Any:
    """Read one YAML document.

    Raises
    ------
    FileNotFoundError
        If `path` does not exist.
    YamlError
        If the text is not valid YAML or a mapping repeats a key.
    """
    try:
        text = read_text(path, limit=MAX_YAML_BYTES)
    except InputFileError as error:
        if error.kind == "missing":
            raise FileNotFoundError(error.reason) from None
        raise YamlError(error.reason, Path(path)) from None
    try:
        loader = _Loader(text)
        try:
            node = loader.get_single_node()
            if node is None:
                return None
            expanded = _expanded_size(node)
            if expanded > MAX_EXPANDED_NODES:
                raise YamlError(
                    f"invalid YAML: its aliases expand it to {expanded:.3g} nodes, more than the "
                    f"{MAX_EXPANDED_NODES} allowed (an alias bomb?)",
                    path,
                )
            return loader.construct_document(node)
        finally:
            loader.dispose()
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        context = f" ({exc.context})" if exc.context else ""
        raise YamlError(f"invalid YAML{where}: {exc.problem}{context}", path) from exc
    except yaml.YAMLError as exc:
        raise YamlError(f"invalid YAML: {exc}", path) from exc


def _expanded_size(root: yaml.Node) -> float:
    """The number of nodes of the document with every alias expanded (each shared node
    counted once per reference), computed once per node."""
    sizes: dict[int, float] = {}
    stack: list[tuple[yaml.Node, bool]] = [(root, False)]
    while stack:
        node, ready = stack.pop()
        if id(node) in sizes:
            continue
        children: list[yaml.Node] = []
        if isinstance(node, yaml.SequenceNode):
            children = list(node.value)
        elif isinstance(node, yaml.MappingNode):
            children = [part for pair in node.value for part in pair]
        if ready or not children:
            sizes[id(node)] = 1.0 + sum(sizes.get(id(child), 0.0) for child in children)
            continue
        stack.append((node, True))
        stack.extend((child, False) for child in children if id(child) not in sizes)
    return sizes[id(root)]
