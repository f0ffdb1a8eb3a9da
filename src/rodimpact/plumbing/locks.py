"""Snakemake's lock of the project directory after a killed run: released when no run holds it.

What snakemake does on its own
    With its default (file) persistence, a run writes the files it reads and writes into
    ``.snakemake/locks/<n>.input.lock`` and ``<n>.output.lock``
    (``snakemake.persistence.file.FilePersistence._write_locks``) and removes that folder when it
    ends, also on an error (``PersistenceBase.lock``). A second run whose files overlap a lock
    stops with ``LockException`` (a dry run only warns). A run killed by SIGKILL, an
    out-of-memory kill or a power cut removes nothing, and every later run stops on the lock
    until someone runs ``snakemake --unlock``, which deletes it without looking whether a run
    still holds it.

Why that is not enough here
    A build killed on this 2-core machine (or by the cluster's scheduler) should be redone by
    the same command, as the docs promise, and ``--unlock`` run by hand (or by make) would also
    release the lock of a live run. The workflow calls :func:`release_stale_lock` when it is
    parsed: the lock is released, with a one-line notice, only when

    * no snakemake process other than the caller runs in this directory on this machine (read
      from ``/proc``: the program a process runs and its working directory; without ``/proc``
      nothing is released). A process is a snakemake run by what it executes: the
      ``snakemake`` program, or a Python interpreter running the ``snakemake`` script or
      ``-m snakemake`` (:func:`runs_snakemake`). A wrapper whose arguments name snakemake
      (``timeout 500 snakemake ...``, ``/usr/bin/time snakemake ...``, a shell) is not one: its
      snakemake child is, and is found on its own; and
    * no job of a killed run still runs here (a process of this directory running a script
      snakemake wrote for a job, ``.snakemake/scripts/``: :func:`live_job_pids`): killing
      snakemake alone leaves its jobs running and writing. Then the lock is kept and the run
      stops before it plans anything, in one line naming the processes (:class:`OrphanedJobs`);
    * no run on another machine registered itself here (:func:`register_run`, called when a run
      starts: ``.snakemake/rodimpact/runs/<host>-<pid>``, removed when it ends; a shared file
      system may hold a live run of another node, which this machine cannot see).

    A cluster job (snakemake's ``--mode remote`` on a compute node) never calls it
    (``workflow/rules/preflight.smk``): the lock belongs to the run that submitted the job.

    Snakemake's database persistence (``--persistence-backend db``) keeps its locks in the
    database: none is found here and nothing is released.

If snakemake's internals change
    Should the locks move or be renamed, no lock is found and a killed run's lock stays until
    ``snakemake --unlock`` (snakemake's own behaviour: nothing is released wrongly).
    ``tests/test_plumbing.py::test_snakemakes_own_lock_files_are_found_and_released`` writes
    the locks with snakemake's own persistence class and releases them;
    ``tests/test_faults.py::test_a_killed_build_leaves_a_lock_that_the_next_run_releases`` and
    ``test_a_second_build_under_a_live_one_is_refused_and_the_lock_kept`` check it end to end.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import socket
from pathlib import Path

__all__ = [
    "OrphanedJobs",
    "live_job_pids",
    "live_snakemake_pids",
    "register_run",
    "release_stale_lock",
    "runs_snakemake",
]

LOCK_DIR = Path(".snakemake") / "locks"
RUNS_DIR = Path(".snakemake") / "rodimpact" / "runs"
_PROC = Path("/proc")


#: Options of the Python interpreter that take a value as the next argument.
_PYTHON_OPTIONS_WITH_VALUE = {"-W", "-X", "--check-hash-based-pycs"}


def runs_snakemake(command: list[str]) -> bool:
    """Whether a process with this command line (``/proc/<pid>/cmdline``, split at NULs) is
    snakemake itself, not a program that was given snakemake as an argument.

    The program is the command's first word, or for a Python interpreter (``python``,
    ``python3.11``) the script it runs or the module after ``-m``. A script started by its
    ``#!`` line shows as ``python /path/bin/snakemake ...``.
    """
    if not command:
        return False
    program = os.path.basename(command[0])
    if program == "snakemake":
        return True
    if not program.startswith("python"):
        return False
    arguments = iter(command[1:])
    for argument in arguments:
        if argument == "-m":
            return next(arguments, "") == "snakemake"
        if argument == "-c":  # a program given as a string: not snakemake's entry point
            return False
        if argument in _PYTHON_OPTIONS_WITH_VALUE:
            next(arguments, None)
        elif not argument.startswith("-"):  # the script
            return os.path.basename(argument) == "snakemake" or argument.endswith(
                os.path.join("snakemake", "__main__.py")
            )
    return False


def live_snakemake_pids(root: str | Path, proc: Path = _PROC) -> list[int] | None:
    """Other processes running snakemake in ``root`` on this machine; None without ``/proc``."""
    if not proc.is_dir():
        return None
    here, me = Path(root).resolve(), os.getpid()
    found = []
    for entry in proc.iterdir():
        if not entry.name.isdigit() or int(entry.name) == me:
            continue
        try:
            command = (entry / "cmdline").read_bytes().decode(errors="replace").split("\0")
            if not runs_snakemake([part for part in command if part]):
                continue
            if Path(os.readlink(entry / "cwd")).resolve() == here:
                found.append(int(entry.name))
        except OSError:  # gone, or not ours to read
            continue
    return found


#: Where snakemake writes the script a ``script:`` job runs (relative to the working directory).
SCRIPTS_DIR = os.path.join(".snakemake", "scripts")


class OrphanedJobs(RuntimeError):
    """A killed run's lock is held by its jobs, which still run: ``pids`` -> what each runs.

    The message is one line: the processes, and what to do (wait, or stop them).
    """

    def __init__(self, root: Path, jobs: dict[int, str]) -> None:
        self.root, self.jobs = Path(root), dict(jobs)
        listed = ", ".join(f"{pid} ({what})" for pid, what in sorted(self.jobs.items()))
        pids = " ".join(str(pid) for pid in sorted(self.jobs))
        super().__init__(
            f"rodimpact: a killed run's jobs still run in {self.root.resolve()}: pid {listed}; its lock is kept "
            f"and nothing is started: wait for them to end (or stop them: kill {pids}), then run again"
        )


def _job_script(command: list[str]) -> str | None:
    """The script a snakemake ``script:`` job runs (``solve_part.py``), None for another process."""
    for argument in command[1:]:
        normal = os.path.normpath(argument)
        if normal.startswith(SCRIPTS_DIR + os.sep) or f"{os.sep}{SCRIPTS_DIR}{os.sep}" in normal:
            return os.path.basename(normal).split(".", 1)[-1]  # tmpXXXX.solve_part.py -> solve_part.py
    return None


def live_job_pids(root: str | Path, proc: Path = _PROC) -> dict[int, str] | None:
    """Processes running a snakemake job's script in ``root`` on this machine, pid -> the script;
    None without ``/proc``. Jobs whose snakemake was killed keep running (and writing) until
    they end: their outputs are not to be started again meanwhile."""
    if not proc.is_dir():
        return None
    here, me = Path(root).resolve(), os.getpid()
    found = {}
    for entry in proc.iterdir():
        if not entry.name.isdigit() or int(entry.name) == me:
            continue
        try:
            command = [part for part in (entry / "cmdline").read_bytes().decode(errors="replace").split("\0") if part]
            script = _job_script(command)
            if script is not None and Path(os.readlink(entry / "cwd")).resolve() == here:
                found[int(entry.name)] = script
        except OSError:  # gone, or not ours to read
            continue
    return found


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def register_run(root: str | Path) -> Path:
    """Record this run (host and pid) until it ends; the record's path."""
    runs = Path(root) / RUNS_DIR
    runs.mkdir(parents=True, exist_ok=True)
    record = runs / f"{socket.gethostname()}-{os.getpid()}"
    record.write_text(f"{socket.gethostname()} {os.getpid()}\n", encoding="utf-8")

    def remove() -> None:
        with contextlib.suppress(OSError):
            record.unlink()

    atexit.register(remove)
    return record


def _other_hosts(root: Path) -> list[str]:
    """Registered runs on other machines, and on this one whose process still lives."""
    runs, host, held = root / RUNS_DIR, socket.gethostname(), []
    for record in sorted(runs.glob("*")) if runs.is_dir() else []:
        name, _, pid = record.name.rpartition("-")
        if name != host:
            held.append(f"{name} (pid {pid})")
        elif pid.isdigit() and int(pid) != os.getpid() and _alive(int(pid)):
            held.append(f"{name} (pid {pid})")
        elif pid.isdigit() and int(pid) != os.getpid():
            with contextlib.suppress(OSError):
                record.unlink()  # a dead run's record
    return held


def release_stale_lock(root: str | Path, proc: Path = _PROC) -> str | None:
    """Release a lock no live run holds; the notice to show (None when nothing was done).

    Raises
    ------
    OrphanedJobs
        No snakemake holds the lock, but jobs of the killed run still run here: the lock is
        kept, and the caller stops before anything is planned or started.
    """
    root = Path(root)
    locks = sorted((root / LOCK_DIR).glob("*.lock")) if (root / LOCK_DIR).is_dir() else []
    if not locks:
        return None
    live = live_snakemake_pids(root, proc)
    if live is None or live:
        return None
    if _other_hosts(root):
        return None
    jobs = live_job_pids(root, proc)
    if jobs:
        raise OrphanedJobs(root, jobs)
    for lock in locks:
        with contextlib.suppress(FileNotFoundError):
            lock.unlink()
    return (
        f"rodimpact: released snakemake's lock of {root.resolve()}: no run holds it (one was killed); "
        "its unfinished outputs are remade"
    )
