"""``make test-cluster``: the small configuration ``.test/`` built through ``profiles/slurm`` by a
real SLURM scheduler, a one-node cluster on this machine (:mod:`local_slurm`).

What it does, in order:

1. installs Debian's ``slurm-wlm`` and ``munge`` when a program of theirs is missing;
2. copies the project once (``copy_dottest``, with ``profiles/``): every run below works on a
   copy of that copy, so all see the same code and configuration;
3. finds the local build of ``.test/`` to compare with: the checkout's own ``.test/results``
   when ``snakemake -n --directory .test`` has nothing to do (``make test`` builds it), else a
   build (``snakemake -j2 --directory .test``) in a copy;
4. starts the cluster (``slurm.conf``, ``munged``, ``slurmctld``, ``slurmd``: all under a
   temporary directory; ``SLURM_CONF`` for every SLURM command and for snakemake), and runs two
   copies through it, one after the other (the build has the scheduler to itself: it is timed),
   each with what docs/cluster.md tells a user (the partition exported as a user would), under
   ``timeout -s INT`` (on SIGTERM snakemake would wait for the jobs it believes run):

   - the build: ``snakemake --workflow-profile profiles/slurm --directory .test``;
   - a failing job: the same command for one batch, ``results/runs/model/sem/part0.h5``, in a copy
     whose batch script (``workflow/scripts/solve_part.py``) raises;

5. checks the build: exit status 0, the sbatch submissions (the scheduler's own list, which
   keeps every job of the run: ``MinJobAge`` is long), the batches the small configuration cuts
   into parts submitted one part each, side by side, the same files as the local build,
   every HDF5 dataset and attribute and every table equal but for the timings (:mod:`compare`),
   and the provenance audit (``python -m rodimpact.tools.audit --root .test``); writes its jobs,
   submissions and wall time against the local build's to ``results/benchmarks/cluster.csv``
   (:mod:`timing`);
6. checks the failing job: the run ends with a non-zero status before its timeout, its output
   names the failed job's SLURM log (``.snakemake/slurm_logs/...``, which holds the error) and
   the rule's own log, after one submission per attempt (``retries``), each asking for more
   memory and time;
7. checks that one target is planned with the same jobs through the profile as locally
   (grouping adds no job).

The daemons are stopped by their process ids at the end, also when a check fails or the script
is interrupted (Ctrl-C, SIGTERM, SIGHUP). Exit status 0 when every check passes, 1 otherwise.

    .venv/bin/python tests/cluster/check_cluster.py [--keep] [--scratch DIR] [--reference DIR]
"""

from __future__ import annotations

import argparse
import contextlib
import itertools
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path
from types import FrameType

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent)]  # this folder's modules, and tests/helpers

import yte  # noqa: E402 (after the path set-up above)
from compare import TIMING_COLUMNS, VOLATILE_ATTRIBUTES, VOLATILE_CONFIG_ENTRIES, compare_builds  # noqa: E402
from local_slurm import NODE_CONF_LINK, LocalSlurm, SlurmError, install  # noqa: E402
from timing import CLUSTER_CSV, BuildTiming, job_count, recorded_build, write_cluster_csv  # noqa: E402

from helpers.copies import DOTTEST, clone_built, copy_dottest, reuse_refusal  # noqa: E402
from helpers.repo import ROOT  # noqa: E402
from helpers.snakemake_cli import BUILD_TIMEOUT_S as LOCAL_BUILD_TIMEOUT_S  # noqa: E402
from helpers.snakemake_cli import DRY_RUN_TIMEOUT_S, job_stats, snakemake  # noqa: E402

#: The profile under test, and what docs/cluster.md tells a user to run.
PROFILE = Path("profiles") / "slurm"
USER_COMMAND = ("--workflow-profile", str(PROFILE), "--directory", DOTTEST)
#: The partition of the one-node cluster, exported as SBATCH_PARTITION as a user would.
PARTITION = "debug"
#: How long the scheduler shows a finished job (s): the whole run, so that squeue lists every
#: submission at the end (the plugin needs at least 3 times its first status check's delay).
MIN_JOB_AGE_S = 3600
#: Bounds of the runs through SLURM (s), on the 2-core machine (a loaded one may double them).
BUILD_TIMEOUT_S = 1500
FAILURE_TIMEOUT_S = 900
#: A single target, planned through the profile and locally.
SINGLE_TARGET = "results/tables/fig2_comparison.csv"
#: Batches the small configuration cuts into several parts (batch.target_s of .test/config): the
#: folder of each one's part files, and the start of its parts' submissions' comments (the slurm
#: plugin's ``rule_{rule}_wildcards_{wildcard values joined by _}``): a sweep, and a group's runs.
CUT_BATCHES = {
    "results/sweeps/ball_sweep-r10_l30/sem": "rule_solve_sweep_wildcards_ball_sweep-r10_l30_sem_",
    "results/runs/r10_l30/fem_axi": "rule_solve_wildcards_r10_l30_fem_axi_",
}
#: The run the failure check asks for, and the rule's log it must name.
FAILING_TARGET = "results/runs/model/sem/part0.h5"
FAILING_RULE_LOG = "logs/runs/model/sem/part0.log"
FAILURE_MESSAGE = "deliberate failure of the cluster check"
FAILING_SCRIPT = f'''"""The cluster check's broken solver: it fails inside the rule's logging, as a solver would."""

from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    raise RuntimeError("{FAILURE_MESSAGE}")
'''
#: How long a snakemake that was sent SIGINT may take to cancel its jobs and leave (s).
STOP_GRACE_S = 60

START = time.monotonic()


def say(message: str) -> None:
    """One line of progress, with the seconds since the start."""
    print(f"[{time.monotonic() - START:6.0f} s] {message}", flush=True)


class Interrupted(Exception):
    """SIGTERM or SIGHUP: leave through the ``finally`` blocks that stop what was started."""


def _interrupt(signum: int, _frame: FrameType | None) -> None:
    """The handler of SIGTERM and SIGHUP."""
    raise Interrupted(f"interrupted by {signal.Signals(signum).name}")


# --------------------------------------------------------------------------------------------
# the profile and the copies
# --------------------------------------------------------------------------------------------


def profile_settings() -> dict:
    """profiles/slurm/config.yaml as snakemake reads it (YTE evaluated in this environment)."""
    with open(ROOT / PROFILE / "config.yaml", encoding="utf-8") as handle:
        return yte.process_yaml(handle, require_use_yte=True)


def slurm_copy(dest: Path) -> Path:
    """A fresh copy of the project with ``.test/config`` (``copy_dottest``) and the checkout's
    ``profiles/``, every file committed."""
    project = copy_dottest(dest)
    shutil.copytree(ROOT / "profiles", project / "profiles")
    git = ["git", "-C", str(project), "-c", "user.name=rodimpact tests", "-c", "user.email=tests@localhost"]
    for args in (["add", "profiles"], ["commit", "-q", "-m", "the workflow profiles"]):
        subprocess.run([*git, *args], check=True, capture_output=True)
    return project


def user_environment(cluster: LocalSlurm) -> dict[str, str]:
    """What a user's shell holds: this environment without snakemake's own variables and
    PYTHONPATH (the workflow sets its own), the cluster's ``SLURM_CONF``, and the partition."""
    env = {
        key: value for key, value in cluster.env().items() if not key.startswith("SNAKEMAKE") and key != "PYTHONPATH"
    }
    env["SBATCH_PARTITION"] = PARTITION
    return env


# --------------------------------------------------------------------------------------------
# snakemake through the cluster
# --------------------------------------------------------------------------------------------


@dataclass
class SnakemakeRun:
    """A finished snakemake run: its exit status, output (stdout and stderr) and wall time."""

    returncode: int
    output: str
    seconds: float
    log: Path

    def tail(self, chars: int = 4000) -> str:
        """The end of the output."""
        return self.output[-chars:]

    @property
    def submitted(self) -> list[str]:
        """The SLURM job ids snakemake reports as submitted, in order."""
        return re.findall(r"has been submitted with SLURM jobid (\d+)", self.output)


class SnakemakeProcess:
    """``timeout -s INT <timeout_s> snakemake <args>`` started in ``project``, its output in ``log``,
    in a session of its own (a terminal's Ctrl-C reaches this script, which then stops it)."""

    def __init__(self, project: Path, args: tuple[str, ...], env: dict[str, str], timeout_s: int, log: Path) -> None:
        snakemake = Path(sys.executable).parent / "snakemake"
        self.log, self.started = log, time.monotonic()
        with open(log, "w", encoding="utf-8") as out:
            self.proc = subprocess.Popen(
                ["timeout", "-s", "INT", str(timeout_s), str(snakemake), *args],
                cwd=project,
                env=env,
                stdout=out,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        self.seconds: float | None = None

    def done(self) -> bool:
        """Whether it has ended (its wall time is then kept)."""
        if self.proc.poll() is None:
            return False
        if self.seconds is None:
            self.seconds = time.monotonic() - self.started
        return True

    def interrupt(self) -> None:
        """SIGINT to ``timeout``, which passes it to snakemake (which cancels its SLURM jobs)."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)

    def finish(self, deadline: float) -> None:
        """Wait for the end until ``deadline`` (``time.monotonic()``), then kill its process group."""
        try:
            self.proc.wait(timeout=max(deadline - time.monotonic(), 0.1))
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):  # it left meanwhile
                os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait()

    def result(self) -> SnakemakeRun:
        """The finished run."""
        self.done()
        return SnakemakeRun(
            self.proc.returncode, self.log.read_text(encoding="utf-8", errors="replace"), self.seconds or 0.0, self.log
        )


def stop(processes: list[SnakemakeProcess]) -> None:
    """Interrupt the processes still running, all at once, and give them :data:`STOP_GRACE_S`
    to leave before they are killed."""
    for process in processes:
        process.interrupt()
    deadline = time.monotonic() + STOP_GRACE_S
    for process in processes:
        process.finish(deadline)


def wait_until_done(processes: dict[str, SnakemakeProcess]) -> None:
    """Wait until every process has ended, saying when each does; stop those left on any
    exception (an interrupt included)."""
    try:
        left = dict(processes)
        while left:
            for name, process in list(left.items()):
                if process.done():
                    say(f"     {name} ended: exit {process.proc.returncode} after {process.seconds:.0f} s")
                    del left[name]
            time.sleep(0.1)
    finally:
        stop(list(processes.values()))


def run_snakemake(project: Path, args: tuple[str, ...], env: dict[str, str], timeout_s: int, log: Path) -> SnakemakeRun:
    """One snakemake run to its end (see :class:`SnakemakeProcess`)."""
    process = SnakemakeProcess(project, args, env, timeout_s, log)
    try:
        while not process.done():
            time.sleep(0.1)
    finally:
        stop([process])
    return process.result()


def scheduler_jobs(cluster: LocalSlurm) -> list[dict[str, str]]:
    """Every job the scheduler knows (pending, running, or finished less than MinJobAge ago):
    id, name (snakemake's run id), state, comment (``rule_<rule>_wildcards_...`` for a job,
    ``rule_<group>_<its rules>`` for a group), memory, time limit and CPUs as submitted, and its
    submission, start and end (ISO 8601, to the second; ``N/A`` before it starts)."""
    fields = ("id", "name", "state", "comment", "memory", "time_limit", "cpus", "submit", "start", "end")
    listed = cluster.command("squeue", "--states=all", "--noheader", "--format=%i|%j|%T|%k|%m|%l|%C|%V|%S|%e")
    return [dict(zip(fields, line.split("|"))) for line in listed.stdout.splitlines() if line.strip()]


def jobs_of(run: SnakemakeRun, jobs: list[dict[str, str]]) -> list[dict[str, str]]:
    """The scheduler's jobs of one snakemake run (named with its SLURM run id), by job id."""
    run_id = re.search(r"SLURM run ID: (\S+)", run.output)
    return sorted((job for job in jobs if run_id and job["name"] == run_id.group(1)), key=lambda j: int(j["id"]))


def submission_kinds(jobs: list[dict[str, str]], groups: set[str]) -> dict[str, int]:
    """Submissions per group (``group <name>``) or rule, from their comments."""
    kinds: dict[str, int] = {}
    for job in jobs:
        name = re.sub(r"_wildcards_.*", "", job["comment"]).removeprefix("rule_")
        group = next((g for g in sorted(groups) if name.startswith(f"{g}_") or name == g), None)
        kind = f"group {group}" if group else name
        kinds[kind] = kinds.get(kind, 0) + 1
    return kinds


# --------------------------------------------------------------------------------------------
# the checks
# --------------------------------------------------------------------------------------------


@dataclass
class Report:
    """What was checked: failures (one line each) and timings."""

    failures: list[str] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)

    def check(self, ok: bool, what: str, detail: str = "") -> bool:
        """Print ``what`` with ok or FAIL (and ``detail`` on failure); record a failure."""
        say(f"{'ok  ' if ok else 'FAIL'} {what}")
        if not ok:
            self.failures.append(what)
            if detail:
                print(detail.rstrip(), flush=True)
        return ok


def check_build(run: SnakemakeRun, jobs: list[dict[str, str]], project: Path, reference: Path, report: Report) -> None:
    """The build through SLURM: it succeeded, its submissions, and its results against ``reference``."""
    if not report.check(
        run.returncode == 0,
        f"the build through SLURM exits 0 (exit {run.returncode}, {run.seconds:.0f} s; log {run.log})",
        run.tail(),
    ):
        return
    report.check(
        sorted(run.submitted, key=int) == [job["id"] for job in jobs],
        f"snakemake reports the scheduler's {len(jobs)} sbatch submissions",
        f"snakemake: {run.submitted}\nsqueue: {jobs}",
    )
    report.check(
        all(job["state"] == "COMPLETED" for job in jobs),
        "every SLURM job completed",
        "\n".join(str(job) for job in jobs if job["state"] != "COMPLETED"),
    )
    kinds = submission_kinds(jobs, set(profile_settings().get("group-components", {})))
    say(f"     {len(jobs)} submissions: " + ", ".join(f"{kind} {n}" for kind, n in sorted(kinds.items())))
    for folder, comment in CUT_BATCHES.items():
        check_parts(jobs, project / DOTTEST / folder, comment, report)
    counts, problems = compare_builds(reference, project / DOTTEST)
    report.check(
        not problems,
        f"the SLURM build equals the local build {reference}: {counts['files']} files, "
        f"{counts['hdf5']} HDF5 files ({counts['datasets']} datasets), "
        f"{counts['tables']} tables",
        "\n".join(problems[:60]),
    )
    audit = subprocess.run(
        [sys.executable, "-m", "rodimpact.tools.audit", "--root", DOTTEST],
        cwd=project,
        capture_output=True,
        text=True,
        check=False,
    )
    last = (audit.stdout.strip().splitlines() or [""])[-1]
    report.check(
        audit.returncode == 0, f"provenance audit of the SLURM build: {last}", (audit.stdout + audit.stderr)[-3000:]
    )


def _times(job: dict[str, str], *keys: str) -> tuple[datetime, ...] | None:
    """The job's times of ``keys`` (None when one is ``N/A``: it never started)."""
    try:
        return tuple(datetime.fromisoformat(job[key]) for key in keys)
    except ValueError:
        return None


def submitted_side_by_side(jobs: list[dict[str, str]]) -> bool:
    """Whether every one of ``jobs`` was submitted before any of them ended: none waited for another."""
    times = [_times(job, "submit", "end") for job in jobs]
    return None not in times and max(t[0] for t in times) <= min(t[1] for t in times)


def ran_at_once(jobs: list[dict[str, str]]) -> bool:
    """Whether two of ``jobs`` ran at the same time (each started before the other ended); on a
    node of two cores, other jobs may hold them."""
    spans = [t for t in (_times(job, "start", "end") for job in jobs) if t is not None]
    return any(a[0] < b[1] and b[0] < a[1] for a, b in itertools.combinations(spans, 2))


def check_parts(jobs: list[dict[str, str]], folder: Path, comment: str, report: Report) -> None:
    """A batch the small configuration cuts into several parts (:data:`CUT_BATCHES`): one
    submission per part, in no group, all submitted before the first ended (side by side, none
    waiting for another); whether two ran at once is printed."""
    files = sorted(folder.glob("part*.h5"))
    parts = [job for job in jobs if job["comment"].startswith(comment)]
    report.check(
        len(files) >= 2 and len(parts) == len(files) and submitted_side_by_side(parts),
        f"{folder.relative_to(folder.parents[3])} in {len(files)} parts: {len(parts)} submissions, side by side",
        "\n".join(str(job) for job in parts),
    )
    say(f"     two of its parts {'ran' if ran_at_once(parts) else 'did not run'} at once")


def check_failure(run: SnakemakeRun, jobs: list[dict[str, str]], project: Path, report: Report) -> None:
    """The run with a failing job: a non-zero status before the timeout, the logs named, one
    submission per attempt, each asking for more."""
    timed_out = run.returncode in (124, -signal.SIGINT, 128 + signal.SIGINT)
    report.check(
        run.returncode != 0 and not timed_out,
        f"the run with a failing job exits non-zero before its timeout (exit {run.returncode}, "
        f"{run.seconds:.0f} s; log {run.log})",
        run.tail(),
    )
    workdir = project / DOTTEST
    named = sorted(set(re.findall(r"(\S*\.snakemake/slurm_logs/\S+?\.log)", run.output)))
    logs = [path for path in (Path(p) if Path(p).is_absolute() else workdir / p for p in named) if path.is_file()]
    holding = [
        str(path.relative_to(workdir))
        for path in logs
        if FAILURE_MESSAGE in path.read_text(encoding="utf-8", errors="replace")
    ]
    report.check(
        bool(holding),
        f"its output names the failed job's SLURM log, which holds the error: {holding}",
        f"named: {named}\n{run.tail()}",
    )
    rule_log = workdir / FAILING_RULE_LOG
    report.check(
        FAILING_RULE_LOG in run.output
        and rule_log.is_file()
        and FAILURE_MESSAGE in rule_log.read_text(encoding="utf-8", errors="replace"),
        f"its output names the rule's log {FAILING_RULE_LOG}, which holds the error",
        run.tail(),
    )
    retries = int(profile_settings().get("retries", 0))
    asked = [(job["memory"], job["time_limit"]) for job in jobs]
    first = re.fullmatch(r"(\d+)M", asked[0][0]) if asked else None
    more = bool(first) and [m for m, _ in asked] == [f"{int(first.group(1)) * k}M" for k in range(1, len(asked) + 1)]
    report.check(
        len(jobs) == retries + 1 and all(job["state"] == "FAILED" for job in jobs) and more,
        f"it was submitted {retries + 1} times (retries: {retries}), each attempt asking for more: "
        f"{', '.join(f'{m} {t}' for m, t in asked)}",
        str(jobs),
    )


def check_single_target(cluster: LocalSlurm, project: Path, report: Report) -> None:
    """A dry run of one target through the profile plans exactly the jobs a local dry run plans."""
    env = user_environment(cluster)
    planned = []
    for number, profile in enumerate((USER_COMMAND[:2], ())):
        run = run_snakemake(
            project,
            (*profile, "--directory", DOTTEST, "-n", SINGLE_TARGET),
            env,
            DRY_RUN_TIMEOUT_S,
            project.parent / f"dry_run_{number}.log",
        )
        planned.append(job_stats(run.output) if run.returncode == 0 else {"exit": run.returncode})
    slurm, local = planned
    report.check(
        slurm == local and bool(local),
        f"one target ({SINGLE_TARGET}) plans the same jobs through the profile as locally: {local}",
        f"{slurm} != {local}",
    )


def check_cluster_runs(
    cluster: LocalSlurm, pristine: Path, scratch: Path, reference: Path, local: BuildTiming | None, report: Report
) -> None:
    """The build, then the failing run (each in a copy of ``pristine``, the scheduler to itself:
    the build is timed), then one target's plan; check each, and write the benchmark."""
    env = user_environment(cluster)
    built, failing = clone_built(pristine, scratch / "slurm"), clone_built(pristine, scratch / "failing")
    (failing / "workflow" / "scripts" / "solve_part.py").write_text(FAILING_SCRIPT, encoding="utf-8")
    say(f"through SLURM, with SBATCH_PARTITION={PARTITION} (each in a fresh copy of the project):")
    say(f"     the build: snakemake {' '.join(USER_COMMAND)}  ({built})")
    build_process = SnakemakeProcess(built, USER_COMMAND, env, BUILD_TIMEOUT_S, scratch / "build.log")
    wait_until_done({"the build": build_process})
    build = build_process.result()
    report.timings["build through SLURM"] = build.seconds
    jobs = jobs_of(build, scheduler_jobs(cluster))
    check_build(build, jobs, built, reference, report)
    if build.returncode == 0:
        slurm = BuildTiming(
            build="slurm",
            jobs=job_count(built / DOTTEST),
            submissions=len(jobs),
            wall_s=build.seconds,
            measured="timed by the check (planning included)",
        )
        path = write_cluster_csv(ROOT / CLUSTER_CSV, local, slurm, ROOT)
        ratio = f", {slurm.wall_s / local.wall_s:.2f} times the local build's {local.wall_s:.0f} s" if local else ""
        say(f"     {slurm.jobs} jobs in {slurm.submissions} submissions, {slurm.wall_s:.0f} s{ratio} -> {path}")

    say(
        f"     a failing job: snakemake {' '.join(USER_COMMAND)} {FAILING_TARGET}  ({failing}: "
        f"workflow/scripts/solve_part.py raises)"
    )
    failure_process = SnakemakeProcess(
        failing, (*USER_COMMAND, FAILING_TARGET), env, FAILURE_TIMEOUT_S, scratch / "failing_run.log"
    )
    wait_until_done({"the failing run": failure_process})
    failure = failure_process.result()
    report.timings["failing run through SLURM"] = failure.seconds
    check_failure(failure, jobs_of(failure, scheduler_jobs(cluster)), failing, report)
    check_single_target(cluster, failing, report)


def reference_build(pristine: Path, scratch: Path) -> tuple[Path, BuildTiming | None]:
    """The ``.test/`` of a local build of the same code and configuration as ``pristine``, and
    that build's timing: the checkout's when it is up to date (``reuse_refusal``; timed by its
    job records), else a build (``snakemake -j2 --directory .test``) in a copy of ``pristine``,
    timed here."""
    why = reuse_refusal()
    if why is None:
        timing = recorded_build(ROOT / DOTTEST)
        spent = f", built in {timing.wall_s:.0f} s by its job records" if timing else ""
        say(f"local build to compare with: {ROOT / DOTTEST} (the checkout's, up to date{spent})")
        return ROOT / DOTTEST, timing
    say(f"building {DOTTEST} locally to compare with: {why.splitlines()[0]}")
    project = clone_built(pristine, scratch / "reference")
    started = time.monotonic()
    run = snakemake(project, "-j2", timeout=LOCAL_BUILD_TIMEOUT_S, workdir=DOTTEST)
    seconds = time.monotonic() - started
    if run.returncode != 0:
        raise SlurmError(f"the local build of {DOTTEST} failed, nothing to compare with:\n{run.describe()}")
    say(f"local build to compare with: {project / DOTTEST} ({seconds:.0f} s)")
    return project / DOTTEST, BuildTiming(
        build="local",
        jobs=job_count(project / DOTTEST),
        submissions=None,
        wall_s=seconds,
        measured="timed by the check (planning included)",
    )


# --------------------------------------------------------------------------------------------


#: How long SLURM's client may take to give up when no cluster is configured, s. With a
#: configuration that names a controller no longer running, ``scontrol`` waits for its message
#: timeout (9 s measured here), and so does every snakemake start: the executor plugin runs
#: ``scontrol show config`` when snakemake imports it (docs/cluster.md, "What the SLURM plugin
#: costs at every start").
NO_CLUSTER_S = 2.0


def check_no_trace(report: Report) -> None:
    """After the daemons stopped: the machine as it was. No configuration of the test cluster is
    left where SLURM's client looks without ``SLURM_CONF`` (``/etc/slurm/slurm.conf``, the
    configless ``/run/slurm/conf``), so ``scontrol show config`` gives up at once, and a plain
    ``snakemake --version`` pays nothing for the cluster that was."""
    env = {k: v for k, v in os.environ.items() if k != "SLURM_CONF"}
    report.check(not NODE_CONF_LINK.exists(), "no trace: the configless link is gone", str(NODE_CONF_LINK))
    started = time.monotonic()
    subprocess.run(["scontrol", "show", "config"], env=env, capture_output=True, check=False, timeout=60)
    scontrol_s = time.monotonic() - started
    started = time.monotonic()
    subprocess.run([sys.executable, "-m", "snakemake", "--version"], env=env, capture_output=True, check=False)
    version_s = time.monotonic() - started
    report.check(
        scontrol_s < NO_CLUSTER_S,
        f"no trace: SLURM's client finds no cluster at once (scontrol show config {scontrol_s:.1f} s, "
        f"snakemake --version {version_s:.1f} s)",
        f"scontrol show config took {scontrol_s:.1f} s, more than {NO_CLUSTER_S} s: a configuration names a "
        "controller that no longer runs",
    )


def main(argv: list[str] | None = None) -> int:
    """Run every check (see the module docstring); 0 when all pass, else 1."""
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--scratch", type=Path, help="work in this directory (kept) instead of a temporary one")
    parser.add_argument("--keep", action="store_true", help="keep the temporary directory")
    parser.add_argument(
        "--reference", type=Path, help="a built .test/ to compare with, instead of the checkout's or a new local build"
    )
    args = parser.parse_args(argv)
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, _interrupt)

    first_check = int(profile_settings().get("slurm-init-seconds-before-status-checks", 40))
    min_job_age = max(MIN_JOB_AGE_S, 3 * first_check)
    scratch = args.scratch or Path(tempfile.mkdtemp(prefix="rodimpact-cluster-"))
    scratch.mkdir(parents=True, exist_ok=True)
    report = Report()
    try:
        started = time.monotonic()
        installed = install()
        report.timings["install slurm-wlm munge"] = time.monotonic() - started
        say(f"SLURM and munge {'installed' if installed else 'present'}")

        # one copy of the project now: every run below works on a copy of it, the code and the
        # configuration of the checkout as they are at this moment
        pristine = slurm_copy(scratch / "pristine")
        started = time.monotonic()
        reference, local = (
            (args.reference.resolve(), recorded_build(args.reference.resolve()))
            if args.reference
            else reference_build(pristine, scratch)
        )
        report.timings["local build to compare with"] = time.monotonic() - started

        started = time.monotonic()
        with LocalSlurm(scratch / "slurm-cluster", min_job_age=min_job_age, partition=PARTITION) as cluster:
            report.timings["cluster start"] = time.monotonic() - started
            say(
                f"one-node SLURM up: node {cluster.node} idle, partition {PARTITION}, MinJobAge {min_job_age} s, "
                f"SLURM_CONF={cluster.conf}"
            )
            check_cluster_runs(cluster, pristine, scratch, reference, local, report)
        say("daemons stopped")
        check_no_trace(report)
    except (SlurmError, subprocess.CalledProcessError, AssertionError) as error:
        report.failures.append(f"{type(error).__name__}: {error}")
        say(f"FAIL {type(error).__name__}: {error}")
    except (KeyboardInterrupt, Interrupted) as error:
        say(f"stopped: {str(error) or 'interrupted'}; snakemake and the daemons stopped")
        return 1
    finally:
        if args.scratch is None and not args.keep and not report.failures:
            shutil.rmtree(scratch, ignore_errors=True)
        elif args.scratch is None:
            say(f"kept {scratch}")
    print("timings: " + ", ".join(f"{name} {seconds:.0f} s" for name, seconds in report.timings.items()))
    print(
        "not compared, as they record when or how long: table columns "
        + "; ".join(f"{table} {', '.join(columns)}" for table, columns in TIMING_COLUMNS.items())
        + f"; HDF5 attributes {', '.join(VOLATILE_ATTRIBUTES)}; in a run's config_json "
        + ", ".join(".".join(path) for path in VOLATILE_CONFIG_ENTRIES)
    )
    if report.failures:
        print(f"test-cluster: {len(report.failures)} check(s) failed:\n  " + "\n  ".join(report.failures))
        return 1
    print(f"test-cluster: every check passed in {time.monotonic() - START:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
