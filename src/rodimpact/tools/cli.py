"""The ``rodimpact`` command: what users run by hand, outside snakemake.

``rodimpact run CASE_FILE [--case ID] [--method M]``
    Solve the cases of one case file (anywhere; checked against the project's
    ``config/config.yaml`` and materials, as the workflow checks them) and print each run's
    summary: contact time, force maxima, rebound velocity, status. Nothing is written: a
    quick look before a case joins ``config/cases/``.
``rodimpact audit [--root DIR] [--no-workflow] [--json FILE]``
    The provenance audit of ``results/`` (``make provenance``; :mod:`.audit`).
``rodimpact --version``
    The package's version.

Errors the user causes (a bad case file, an unknown case or method, a solver that fails on
the case) are one line on stderr and exit status 1.
"""

from __future__ import annotations

import argparse
import logging
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TextIO

import rodimpact
from rodimpact.config.load import load_case_file, load_global_config
from rodimpact.config.project import ConfigError
from rodimpact.jobs.runner import SolverFailed, run_case
from rodimpact.tools import audit

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="rodimpact",
        description="Axial impact on an elastic rod: solve a case file, or audit the results' provenance.",
    )
    parser.add_argument("--version", action="version", version=f"rodimpact {rodimpact.__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="solve the cases of one case file and print their summaries")
    run.add_argument("case_file", type=Path, help="a case file (the format of config/cases/*.yaml)")
    run.add_argument("--case", action="append", help="only this case id (repeatable; default: every case)")
    run.add_argument("--method", action="append", help="only this method (repeatable; default: the case's)")
    run.add_argument(
        "--root",
        type=Path,
        default=Path("."),
        help="project directory whose config/config.yaml and materials apply (default: .)",
    )
    audit.add_arguments(commands.add_parser("audit", help="audit results/: every file resolves to its config and code"))
    return parser


def _summary_line(case_id: str, method: str, result) -> str:
    peaks = ", ".join(f"{p / 1e3:.4g}" for p in result.peak_force_N) or "none"
    return (
        f"{case_id:<28} {method:<9} contact {1e6 * result.contact_time_s:10.4g} us  "
        f"maxima [{peaks}] kN  rebound {result.rebound_velocity_m_s:+.4g} m/s  {result.status}: {result.message}"
    )


def run_file(
    case_file: Path, root: Path, cases: Sequence[str] | None, methods: Sequence[str] | None, out: TextIO
) -> int:
    """Solve and print; the exit status (1 after a one-line error on stderr)."""
    try:
        resolved = load_case_file(case_file, load_global_config(root / "config" / "config.yaml"), root)
    except ConfigError as error:
        sys.stderr.write(f"rodimpact: invalid configuration: {error}\n")
        return 1
    wanted = list(resolved) if not cases else cases
    for case_id in wanted:
        if case_id not in resolved:
            sys.stderr.write(f"rodimpact: no case {case_id!r} in {case_file}; its cases: {', '.join(resolved)}\n")
            return 1
        case = resolved[case_id]
        for method in methods or case["methods"]:
            if method not in case["methods"]:
                sys.stderr.write(
                    f"rodimpact: case {case_id!r} does not run {method!r}; its methods: {', '.join(case['methods'])}\n"
                )
                return 1
            try:
                result = run_case(case, method)
            except SolverFailed as error:
                sys.stderr.write(f"rodimpact: {error}\n")
                return 1
            out.write(_summary_line(case_id, method, result) + "\n")
            out.flush()
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """The ``rodimpact`` console command; its exit status."""
    args = _parser().parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s %(name)s: %(message)s")
    if args.command == "audit":
        return audit.run(args)
    return run_file(args.case_file, args.root, args.case, args.method, sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main())
