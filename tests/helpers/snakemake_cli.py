"""snakemake's command line, run in a copy of the project, and what its output says: the jobs a
run plans (its "Job stats" table) and the files it would write (``--summary``)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

#: A dry run or a summary: planning only (s).
DRY_RUN_TIMEOUT_S = 120
#: A build of a copy (s): the shrunk copy's full build takes 3-4 min idle, a loaded machine doubles it.
BUILD_TIMEOUT_S = 1200


class Run:
    """A finished snakemake process; ``output`` is stdout and stderr together."""

    def __init__(self, proc: subprocess.CompletedProcess):
        self.returncode, self.stdout, self.stderr = proc.returncode, proc.stdout, proc.stderr
        self.output = proc.stdout + proc.stderr
        self.args = proc.args

    def describe(self) -> str:
        tail = self.output[-6000:]
        return f"{' '.join(map(str, self.args))} -> exit {self.returncode}\n{tail}"


def snakemake_environment() -> dict[str, str]:
    """This process's environment without snakemake's variables and PYTHONPATH: the workflow
    puts its own checkout's src/ first (workflow/rules/preflight.smk)."""
    env = {key: value for key, value in os.environ.items() if not key.startswith("SNAKEMAKE") and key != "PYTHONPATH"}
    env.update(MPLBACKEND="Agg")
    return env


def snakemake_command(args: tuple[str, ...], workdir: str | None, wrapper: tuple[str, ...] = ()) -> list[str]:
    directory = ["--directory", workdir] if workdir else []
    # under a wrapper, the environment's snakemake program, as a user types it after the wrapper
    program = [str(Path(sys.executable).parent / "snakemake")] if wrapper else [sys.executable, "-m", "snakemake"]
    return [*wrapper, *program, "--nocolor", *directory, *args]


def snakemake(
    project: Path,
    *args: str,
    timeout: float = DRY_RUN_TIMEOUT_S,
    workdir: str | None = None,
    wrapper: tuple[str, ...] = (),
) -> Run:
    """Run the snakemake CLI of this interpreter's environment in ``project`` (the directory of
    the Snakefile); ``workdir``: a working directory of its own inside it (``--directory``,
    such as ``.test``); ``wrapper``: a command that runs it (``("timeout", "500")``)."""
    proc = subprocess.run(
        snakemake_command(args, workdir, wrapper),
        cwd=project,
        env=snakemake_environment(),
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )
    return Run(proc)


def start(project: Path, *args: str) -> subprocess.Popen:
    """snakemake in the background, in its own process group (to kill it with its jobs)."""
    return subprocess.Popen(
        snakemake_command(args, None),
        cwd=project,
        env=snakemake_environment(),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )


def job_stats(output: str) -> dict[str, int]:
    """Jobs per rule from snakemake's "Job stats" table (empty when nothing is planned).

    Why this table: it is what snakemake itself counts from the DAG it would execute, for
    dry runs and real runs alike, and its layout (``job count`` header, dashes, one
    ``<rule> <n>`` line per rule, ``total <n>``) has been stable since snakemake 7. The
    per-job blocks are not used because snakemake 9 prints them twice in a dry run. The table
    may also be printed more than once; every copy must agree and sum to its total.
    """
    tables = []
    for match in re.finditer(r"^Job stats:\n(.*?)^total\s+(\d+)\s*$", output, re.M | re.S):
        rows = {}
        for line in match.group(1).splitlines():
            row = re.fullmatch(r"(\S+)\s+(\d+)", line.strip())
            if row and row.group(1) != "job":
                rows[row.group(1)] = int(row.group(2))
        assert sum(rows.values()) == int(match.group(2)), f"inconsistent job stats:\n{match.group(0)}"
        tables.append(rows)
    assert all(table == tables[0] for table in tables), f"job stats tables differ: {tables}"
    return tables[0] if tables else {}


def summary(project: Path, *targets: str, workdir: str | None = None) -> list[dict[str, str]]:
    """``snakemake --summary``: one row per output file of the DAG of ``targets``.

    Tab-separated, with columns output_file, date, rule, log-file(s), status and plan;
    ``plan`` is "update pending" for files that would be (re)built. This names the exact
    files a run would write, which the job counts alone cannot.
    """
    run = snakemake(project, "--summary", *targets, workdir=workdir)
    assert run.returncode == 0, run.describe()
    lines = [line.split("\t") for line in run.stdout.splitlines() if line.count("\t") == 5]
    assert lines and lines[0][0] == "output_file", run.describe()
    header = lines[0]
    return [dict(zip(header, line)) for line in lines[1:]]


def pending(rows: list[dict[str, str]], rule: str | None = None) -> set[str]:
    """Output files a run would (re)build, optionally of one rule only."""
    return {
        row["output_file"] for row in rows if row["plan"] == "update pending" and (rule is None or row["rule"] == rule)
    }


def pending_runs(rows: list[dict[str, str]], workdir: Path) -> set[str]:
    """The HDF5 files a run would (re)write: pending outputs ending in ``.h5``, and the ``.h5`` files
    in a pending batch's output directory (as they are in ``workdir`` now)."""
    files = set()
    for output in pending(rows):
        if output.endswith(".h5"):
            files.add(output)
        elif (workdir / output).is_dir():
            files.update((Path(output) / f.name).as_posix() for f in (workdir / output).glob("*.h5"))
    return files
