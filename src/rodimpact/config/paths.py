"""A setting of a resolved case named by its path: read it, or a copy of the case with it changed.

A path is the keys from the case's top down, joined by dots, with ``[i]`` for an item of a
list: ``impactor.velocity_m_s``, ``rod.material.youngs_modulus_pa``,
``contact.layers[1].thickness_m``. It names a setting when every key exists in the resolved
case (:func:`rodimpact.config.load.load_project` fills every default, so a setting the case
does not write still has its place) and the value there is a number. A calibration changes
cases this way, and a synthetic record is made this way from stated "true" constants.
"""

from __future__ import annotations

import copy
import math
import re
from collections.abc import Mapping, Sequence
from typing import Any

__all__ = ["PathError", "format_path", "parse_path", "setting_at", "with_setting"]

_PART = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[\d+\])*)")


class PathError(ValueError):
    """A path that names no numeric setting of the case; ``path`` is the path as written."""

    def __init__(self, path: str, reason: str) -> None:
        self.path, self.reason = path, reason
        super().__init__(f"{path!r}: {reason}")


def parse_path(path: str) -> list[str | int]:
    """The keys and indices of ``path``, from the top (``a.b[1].c`` -> ``['a', 'b', 1, 'c']``)."""
    steps: list[str | int] = []
    for part in path.split("."):
        match = _PART.fullmatch(part)
        if match is None:
            raise PathError(path, f"{part!r} is not a key (letters, digits, _) with optional [index]")
        steps.append(match.group(1))
        steps += [int(index) for index in re.findall(r"\[(\d+)\]", match.group(2))]
    return steps


def format_path(path: Sequence[str | int]) -> str:
    """The path of keys and list indices ``path`` written as a dotted path, the inverse of
    :func:`parse_path`: ``("methods", 1)`` -> ``"methods[1]"``, ``("a", "b", 0, "c")`` -> ``"a.b[0].c"``."""
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


def _walk(case: Any, path: str) -> tuple[Any, str | int]:
    """The container holding the setting and its key, or PathError naming the first missing key."""
    steps = parse_path(path)
    node, walked = case, ""
    for step in steps[:-1]:
        node = _step(node, step, path, walked)
        walked += f"[{step}]" if isinstance(step, int) else f"{'.' if walked else ''}{step}"
    last = steps[-1]
    _step(node, last, path, walked)
    return node, last


def _step(node: Any, step: str | int, path: str, walked: str) -> Any:
    where = f"under {walked!r}" if walked else "at the case's top"
    if isinstance(step, int):
        if not isinstance(node, list) or step >= len(node):
            size = f"a list of {len(node)}" if isinstance(node, list) else "not a list"
            raise PathError(path, f"no item [{step}] {where} ({size})")
        return node[step]
    if not isinstance(node, Mapping) or step not in node:
        known = ", ".join(sorted(map(str, node))) if isinstance(node, Mapping) else "not a mapping"
        raise PathError(path, f"no key {step!r} {where} (there: {known})")
    return node[step]


def setting_at(case: Mapping[str, Any], path: str) -> float:
    """The numeric setting ``path`` names in ``case``.

    Raises
    ------
    PathError
        A key or an index along the path is missing, or the value there is not a finite number.
    """
    node, key = _walk(case, path)
    value = node[key]
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise PathError(path, f"names {value!r}, not a number")
    return float(value)


def with_setting(case: Mapping[str, Any], path: str, value: float) -> dict[str, Any]:
    """A deep copy of ``case`` with the setting ``path`` set to ``value`` (the case is unchanged).

    Raises
    ------
    PathError
        As :func:`setting_at`.
    """
    setting_at(case, path)
    changed = copy.deepcopy(dict(case))
    node, key = _walk(changed, path)
    node[key] = float(value)
    return changed
