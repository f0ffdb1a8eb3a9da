"""The plumbing around snakemake (rodimpact.plumbing) against snakemake's own internals.

Each mechanism relies on something snakemake does not promise as an interface: the argument
parser of its command line, the place and names of its lock files, and a process that runs
its :mod:`atexit` handlers after a dry run. These tests use snakemake itself, so that a new
snakemake that changes any of them fails here, by name, instead of quietly disabling the check.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from rodimpact.plumbing.locks import LOCK_DIR, RUNS_DIR, OrphanedJobs, live_job_pids, release_stale_lock, runs_snakemake
from rodimpact.plumbing.targets import command_line_targets, untargeted_set_message

REPO = Path(__file__).resolve().parents[1]
DRY_RUN_TIMEOUT_S = 300


@pytest.mark.parametrize(
    "argv, targets",
    [
        (["snakemake", "-j2", "--directory", ".test", "results/a.csv", "all"], ["results/a.csv", "all"]),
        (
            ["/env/lib/python3.11/site-packages/snakemake/__main__.py", "--nocolor", "-n", "results/runs/model/sem.h5"],
            ["results/runs/model/sem.h5"],
        ),
        (["snakemake", "-n", "--quiet", "rules"], []),
        (
            ["snakemake", "-j1", "--forcerun", "bench_sem", "bench_fem", "--", "results/benchmarks/sem.csv"],
            ["results/benchmarks/sem.csv"],
        ),
        (
            ["snakemake", "--config", "targets={sets: [model]}", "--", "results/tables/table2_r1_l30.csv"],
            ["results/tables/table2_r1_l30.csv"],
        ),
        (["pytest", "results/a.csv"], []),
        ([], []),
    ],
    ids=[
        "targets after options",
        "python -m snakemake",
        "a list option's value",
        "after --",
        "after --config",
        "not snakemake",
        "no command line",
    ],
)
def test_snakemakes_parser_reads_the_targets_of_a_command_line(argv: list[str], targets: list[str]) -> None:
    """snakemake.cli.get_argument_parser still exists and names its positionals ``targets``."""
    assert command_line_targets(argv) == targets


def _fake_proc(root: Path, processes: dict[int, tuple[list[str], Path]]) -> Path:
    """A /proc with the given processes: pid -> (command line, working directory)."""
    proc = root / "proc"
    proc.mkdir()
    for pid, (command, cwd) in processes.items():
        (proc / str(pid)).mkdir()
        (proc / str(pid) / "cmdline").write_bytes(b"\0".join(part.encode() for part in command) + b"\0")
        os.symlink(cwd, proc / str(pid) / "cwd")
    return proc


def _snakemakes_locks(project: Path) -> list[Path]:
    """Locks written by snakemake's own (default, file) persistence, as a running build holds them."""
    from snakemake.persistence.file import FilePersistence

    persistence = FilePersistence(path=project / ".snakemake")
    persistence._write_locks("input", ["config/config.yaml"])
    persistence._write_locks("output", ["results/runs/model/sem.h5"])
    return sorted((project / LOCK_DIR).glob("*.lock"))


def test_snakemakes_own_lock_files_are_found_and_released(tmp_path: Path) -> None:
    project = tmp_path / "project"
    project.mkdir()
    locks = _snakemakes_locks(project)
    assert len(locks) == 2
    notice = release_stale_lock(project, proc=_fake_proc(tmp_path, {}))
    assert notice is not None and notice.startswith("rodimpact: released snakemake's lock of ")
    assert not any(lock.exists() for lock in locks)


def test_the_lock_of_a_live_snakemake_is_kept(tmp_path: Path) -> None:
    project = tmp_path / "project"
    project.mkdir()
    locks = _snakemakes_locks(project)
    proc = _fake_proc(tmp_path, {4242: ([sys.executable, "-m", "snakemake", "-j2"], project)})
    assert release_stale_lock(project, proc=proc) is None
    assert all(lock.exists() for lock in locks)


@pytest.mark.parametrize(
    "command, is_snakemake",
    [
        (["/env/bin/python3.11", "/env/bin/snakemake", "-j2"], True),  # the console script, by its #! line
        (["snakemake", "-n"], True),
        (["python", "-m", "snakemake", "-j2"], True),
        (["python3", "-u", "-X", "dev", "-m", "snakemake"], True),
        (["python", "/env/lib/python3.11/site-packages/snakemake/__main__.py", "-n"], True),
        (["timeout", "500", "snakemake", "-j2"], False),
        (["/usr/bin/time", "/env/bin/snakemake", "-j2"], False),
        (["bash", "-c", "snakemake -j2 && echo done"], False),
        (["python", "-c", "import snakemake"], False),
        (["python", "-m", "pytest", "tests/snakemake"], False),
        ([], False),
    ],
    ids=[
        "console script",
        "snakemake",
        "python -m",
        "python options",
        "__main__.py",
        "timeout",
        "time",
        "shell",
        "python -c",
        "another module",
        "no command line",
    ],
)
def test_a_process_is_a_snakemake_run_by_what_it_executes(command: list[str], is_snakemake: bool) -> None:
    assert runs_snakemake(command) is is_snakemake


@pytest.mark.parametrize("wrapper", [["timeout", "500"], ["/usr/bin/time"]], ids=["timeout", "time"])
def test_a_wrapper_whose_arguments_name_snakemake_holds_no_lock(tmp_path: Path, wrapper: list[str]) -> None:
    """``timeout 500 snakemake ...`` rerunning a killed build: the wrapper (in the project, its
    arguments naming snakemake) is not a live run; the rerun itself is the caller."""
    project = tmp_path / "project"
    project.mkdir()
    locks = _snakemakes_locks(project)
    proc = _fake_proc(tmp_path, {4242: ([*wrapper, "/env/bin/snakemake", "-j2"], project)})
    assert release_stale_lock(project, proc=proc) is not None
    assert not any(lock.exists() for lock in locks)


def test_the_lock_of_a_killed_run_whose_jobs_still_run_is_kept_and_the_run_stops(tmp_path: Path) -> None:
    """snakemake killed alone leaves its jobs running: the lock is kept, and the rerun stops in
    one line naming them; a job of another directory does not count."""
    project = tmp_path / "project"
    project.mkdir()
    locks = _snakemakes_locks(project)
    elsewhere = tmp_path / "other"
    elsewhere.mkdir()
    job = [sys.executable, ".snakemake/scripts/tmpab12cd.solve_part.py"]
    proc = _fake_proc(tmp_path, {4242: (job, project), 4343: (job, elsewhere)})
    with pytest.raises(OrphanedJobs) as caught:
        release_stale_lock(project, proc=proc)
    assert caught.value.jobs == {4242: "solve_part.py"}
    message = str(caught.value)
    assert "pid 4242 (solve_part.py)" in message and "kill 4242" in message and "\n" not in message
    assert all(lock.exists() for lock in locks)
    alone = tmp_path / "alone"
    alone.mkdir()
    assert live_job_pids(project, proc=_fake_proc(alone, {4343: (job, elsewhere)})) == {}


def test_a_run_registered_by_another_host_keeps_its_lock(tmp_path: Path) -> None:
    """A compute node sees none of the login node's processes: the run registry alone keeps the
    live run's lock (tests/test_faults.py runs it with a real build and a separate host)."""
    project = tmp_path / "project"
    project.mkdir()
    locks = _snakemakes_locks(project)
    (project / RUNS_DIR).mkdir(parents=True)
    (project / RUNS_DIR / "login7-4242").write_text("login7 4242\n", encoding="utf-8")
    assert release_stale_lock(project, proc=_fake_proc(tmp_path, {})) is None
    assert all(lock.exists() for lock in locks)


@pytest.mark.workflow
def _snakemake_on_dottest(tmp_path: Path, program: list[str], *args: str) -> tuple[Path, subprocess.CompletedProcess]:
    """``program`` (snakemake's command line, or a script that runs it) with ``args`` on a copy of
    ``.test/config`` (beside a copy of config/: its materials are ../config's), the checkout's
    Snakefile, in an environment without snakemake's variables and PYTHONPATH."""
    project = tmp_path / "project"
    shutil.copytree(REPO / ".test" / "config", project / "config")
    shutil.copytree(REPO / "config", tmp_path / "config")
    env = {key: value for key, value in os.environ.items() if not key.startswith("SNAKEMAKE") and key != "PYTHONPATH"}
    run = subprocess.run(
        [*program, "--nocolor", *args, "--snakefile", str(REPO / "Snakefile"), "--directory", str(project)],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=DRY_RUN_TIMEOUT_S,
        check=False,
    )
    return project, run


def test_a_target_of_a_set_not_built_names_the_set_and_where_to_add_it():
    """compare_mylab.csv of a declared set left out of targets.sets: one line naming the set, its
    case file and targets.sets; a set name inside another word does not match."""
    untargeted = {"mylab": "config/cases/mylab.yaml", "lab": "config/cases/lab.yaml"}
    message = untargeted_set_message("results/tables/compare_mylab.csv", untargeted, "config/config.yaml")
    assert message == (
        "'results/tables/compare_mylab.csv' is of case set 'mylab' (config/cases/mylab.yaml), which is not in "
        "targets.sets of config/config.yaml: add it there to build its tables and figures"
    )
    assert "case set 'lab'" in untargeted_set_message("results/forces/lab/b1/sem.csv", untargeted, "c.yaml")
    assert untargeted_set_message("results/tables/compare_table2.csv", untargeted, "c.yaml") is None
    assert untargeted_set_message("results/tables/compare_mylabel.csv", {"mylab": "x.yaml"}, "c.yaml") is None


#: Runs snakemake's command line in this process, then prints how many threading.Timer threads
#: are still alive once it has returned (before the interpreter joins them at its exit).
_TIMERS_AFTER_RUN = """
import runpy, sys, threading
sys.argv = ["snakemake", *sys.argv[1:]]
try:
    runpy.run_module("snakemake", run_name="__main__")
except SystemExit as stop:
    print("EXIT", stop.code)
print("TIMERS", sum(isinstance(t, threading.Timer) for t in threading.enumerate()))
"""


def test_no_timer_outlives_a_local_run(tmp_path: Path) -> None:
    """A local run drops snakemake's job rate limiter when its jobs start (workflow/rules/
    common.smk, "RATE"): no timer of it is left to hold the process after the run ends (each would
    for up to the limit's timespan, 1 s by default)."""
    project, run = _snakemake_on_dottest(
        tmp_path,
        [sys.executable, "-c", _TIMERS_AFTER_RUN],
        "-j1",
        "--max-jobs-per-timespan",
        "100/1s",
        "results/cases/model.yaml",
    )
    assert "EXIT 0" in run.stdout and (project / "results" / "cases" / "model.yaml").exists(), run.stdout + run.stderr
    assert "TIMERS 0" in run.stdout, run.stdout
