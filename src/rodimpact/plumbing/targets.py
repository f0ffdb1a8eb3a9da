"""Command-line targets that no rule makes, and what to ask for instead.

The workflow checks each target given on the command line before it plans any job
(``workflow/rules/targets.smk``): a rule name or a file some rule's output pattern makes
passes (what that rule's inputs then ask of the configuration is checked by them), anything
else is refused in one line that lists the patterns of the nearest folder that has any.
"""

from __future__ import annotations

from typing import Iterable, Sequence

__all__ = ["MAX_LISTED", "plain_pattern", "unknown_target_message"]

#: Most patterns a message lists (then "and N more").
MAX_LISTED = 12


def plain_pattern(pattern: str) -> str:
    """An output pattern with its wildcards' constraints left out: ``{case,[a-z]+}`` -> ``{case}``."""
    out, depth, skipping = [], 0, False
    for char in pattern:
        if char == "{":
            depth += 1
            if depth == 1:
                skipping = False
                out.append(char)
                continue
        elif char == "}":
            depth -= 1
            if depth == 0:
                out.append(char)
                skipping = False
                continue
        if depth == 1 and char == "," and not skipping:
            skipping = True
            continue
        if not skipping:
            out.append(char)
    return "".join(out)


def _literal_prefix(pattern: str) -> str:
    """The part of an output pattern before its first wildcard."""
    return pattern.split("{", 1)[0]


def unknown_target_message(target: str, patterns: Iterable[str], rule_names: Sequence[str]) -> str:
    """One line saying that no rule makes ``target``, with what the nearest folder offers.

    Parameters
    ----------
    target : str
        The requested file or rule name.
    patterns : iterable of str
        The output patterns of every rule (``{wildcard}`` as written in the rules).
    rule_names : sequence of str
        The rules that may be asked for by name.

    Returns
    -------
    str
        ``no rule makes '<target>'; <folder> holds: <patterns>`` (or the rule names when no
        folder of the target holds any output).
    """
    patterns = sorted({plain_pattern(p) for p in patterns})
    parts = target.split("/")[:-1]
    for depth in range(len(parts), 0, -1):
        folder = "/".join(parts[:depth]) + "/"
        near = [p for p in patterns if p.startswith(folder) or _literal_prefix(p).startswith(folder)]
        if near:
            shown = ", ".join(near[:MAX_LISTED])
            more = f" and {len(near) - MAX_LISTED} more" if len(near) > MAX_LISTED else ""
            return f"no rule makes {target!r}; {folder} holds: {shown}{more}"
    names = ", ".join(sorted(rule_names)[:MAX_LISTED])
    more = f" and {len(rule_names) - MAX_LISTED} more" if len(rule_names) > MAX_LISTED else ""
    return f"no rule makes {target!r} and no rule has that name; rules: {names}{more} (files under results/)"
