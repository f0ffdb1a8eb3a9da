"""Command-line targets that no rule makes, and what to ask for instead.

The workflow checks each target given on the command line before it plans any job
(``workflow/rules/targets.smk``): a rule name or a file some rule's output pattern makes
passes (what that rule's inputs then ask of the configuration is checked by them), anything
else is refused in one line that lists the patterns of the nearest folder that has any.

What snakemake does on its own
    It parses the Snakefile first and is told its targets afterwards: the command-line
    interface (``snakemake.cli.args_to_api``) builds the workflow, whose first use parses the
    Snakefile (``snakemake.api.WorkflowApi._workflow``), and only then hands the targets over
    (``DAGApi.__post_init__`` sets ``workflow.dag_settings``, ``None`` while the Snakefile is
    parsed). A target no rule makes stops the DAG's construction with a ``MissingRuleException``
    (``No rule to produce <target> (if you use input functions ...)``), which names neither
    the rules nor the files a folder holds.

Why that is not enough here
    The targets are checked while the Snakefile is parsed, to refuse a missing file in one line
    that lists what the nearest folder holds. :func:`command_line_targets` reads them from the
    command line with snakemake's own argument parser (``snakemake.cli.get_argument_parser``),
    as the ``snakemake`` command reads them; a snakemake started otherwise (its API, a job's
    own snakemake) is not checked.

If snakemake's internals change
    Should the parser move, or its positional ``targets`` be renamed, :func:`command_line_targets`
    finds no target and nothing is checked before planning (snakemake's own error remains).
    ``tests/test_plumbing.py::test_snakemakes_parser_reads_the_targets_of_a_command_line``
    calls the parser with known command lines and checks the targets read;
    ``tests/test_faults.py::test_a_target_the_configuration_does_not_define_is_one_line`` checks
    the refusal end to end.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

__all__ = ["MAX_LISTED", "command_line_targets", "plain_pattern", "unknown_target_message", "untargeted_set_message"]

#: Most patterns a message lists (then "and N more").
MAX_LISTED = 12


def command_line_targets(argv: Sequence[str]) -> list[str]:
    """The targets of the ``snakemake`` command line ``argv`` (``sys.argv``), [] when unknown.

    Parameters
    ----------
    argv : sequence of str
        The program (``snakemake``, or ``.../snakemake/__main__.py`` for ``python -m
        snakemake``) and its arguments. Another program (snakemake's API, a test runner)
        gives [].

    Returns
    -------
    list of str
        The positional targets as snakemake's own argument parser reads them; [] when the
        command line does not parse.
    """
    if not argv:
        return []
    program = Path(argv[0])
    if program.name != "snakemake" and program.parts[-2:] != ("snakemake", "__main__.py"):
        return []
    from snakemake.cli import get_argument_parser  # only when snakemake itself runs

    try:
        known, _ = get_argument_parser().parse_known_args(list(argv[1:]))
    except (Exception, SystemExit):
        return []
    return list(known.targets or [])


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


def unknown_target_message(
    target: str, patterns: Iterable[str], rule_names: Sequence[str], batch: tuple[str, str] | None = None
) -> str:
    """One line saying that no rule makes ``target``, with what the nearest folder offers.

    Parameters
    ----------
    target : str
        The requested file or rule name.
    patterns : iterable of str
        The output patterns of every rule (``{wildcard}`` as written in the rules).
    rule_names : sequence of str
        The rules that may be asked for by name.
    batch : (str, str), optional
        The directory holding ``target`` that a rule writes as a whole (a batch of runs), and
        that rule's name: the message asks for the directory instead.

    Returns
    -------
    str
        ``no rule makes '<target>'; <folder> holds: <patterns>`` (or the rule names when no
        folder of the target holds any output).
    """
    if batch is not None:
        return (
            f"no rule makes {target!r} alone: it would be a file of {batch[0]}, which rule {batch[1]} writes "
            f"as a whole (one job for all its runs); ask for {batch[0]}"
        )
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


def untargeted_set_message(target: str, untargeted: Mapping[str, str], config_file: str) -> str | None:
    """One line for a target that names a case set the configuration does not build.

    Parameters
    ----------
    target : str
        The requested file (``results/tables/compare_mylab.csv``).
    untargeted : mapping
        Each case set that is not in ``targets.sets`` -> the case file that declares it.
    config_file : str
        The global configuration, where ``targets.sets`` is.

    Returns
    -------
    str or None
        ``'<target>' is of case set '<set>' (<case file>), which is not in targets.sets of
        <config file>: add it there to build its tables and figures``; None when the target
        names no such set (a name as a path part, or after an underscore, before a dot, an
        underscore or a slash: ``compare_mylab.csv``, ``forces/mylab/``).
    """
    for name, source in sorted(untargeted.items(), key=lambda item: -len(item[0])):
        if re.search(rf"(^|[/_]){re.escape(name)}([./_]|$)", target):
            return (
                f"{target!r} is of case set {name!r} ({source}), which is not in targets.sets of {config_file}: "
                "add it there to build its tables and figures"
            )
    return None
