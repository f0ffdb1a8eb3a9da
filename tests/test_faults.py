"""Faults a careless user or the machine causes, run through snakemake in a copy of the project.

Each fault stops with one line (no traceback) that names what is wrong, leaves nothing
readable half-written, and one documented command recovers: the same snakemake command (or
``make paper``) run again. The copies are ``helpers.copies.copy_project``'s (coarse fem_axi,
small studies); the configuration's own refusals are tested in tests/test_config.py.
"""

from __future__ import annotations

import contextlib
import os
import shlex
import shutil
import signal
import subprocess
import time
from pathlib import Path

import h5py
import pytest

from rodimpact.plumbing.locks import RUNS_DIR, live_job_pids
from rodimpact.storage.curves import read_contact_curve
from rodimpact.storage.faults import DIRECTORY_TIMESTAMP, REBUILD_HINT, StoredFileError
from rodimpact.storage.runs import read_run, run_references

from helpers.copies import clone_built, copy_project
from helpers.snakemake_cli import Run, job_stats, snakemake, snakemake_command, snakemake_environment, start

pytestmark = pytest.mark.workflow

SOLVE_BATCH = "results/runs/model/sem/part0.h5"  # the batch of one SEM solve (about 2 s): a target
SOLVE = f"{SOLVE_BATCH}#model"  # its run
TABLE = "results/tables/fig2_comparison.csv"  # reads the four runs of 'model'
LONG = "results/tables/table2_r10_l30.csv"  # 25 jobs: six cases, four methods each
BUILD_TIMEOUT_S = 600


def last_line(run: Run) -> str:
    lines = [line for line in run.output.splitlines() if line.strip()]
    return lines[-1] if lines else ""


def assert_one_line_refusal(run: Run, expected_start: str) -> None:
    assert run.returncode != 0, run.describe()
    assert "Traceback" not in run.output, run.describe()
    assert last_line(run).startswith(expected_start), run.describe()


def locks(project: Path) -> list[Path]:
    directory = project / ".snakemake" / "locks"
    return sorted(directory.glob("*.lock")) if directory.is_dir() else []


def wait_for(condition, timeout: float, what: str) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.02)


@pytest.fixture(scope="module")
def project(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An unbuilt copy, for dry runs."""
    return copy_project(tmp_path_factory.mktemp("faults") / "project")


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A copy with Fig. 2's comparison table and its four runs built."""
    path = copy_project(tmp_path_factory.mktemp("faults_built") / "project")
    run = snakemake(path, "-j2", TABLE, timeout=BUILD_TIMEOUT_S)
    assert run.returncode == 0, run.describe()
    return path


# ------------------------------------------------------------------ targets and config.yaml


@pytest.mark.parametrize(
    "target, expected",
    [
        ("results/runs/nosuch/sem/part0.h5", "rodimpact: unknown group of runs 'nosuch'; known: "),
        (
            "results/runs/smooth/fem_axi/part0.h5",
            "rodimpact: no case of group 'smooth' runs 'fem_axi'; its cases' methods: fem1d, sem, sem_paper",
        ),
        (
            "results/convergence/model/sem/level9.h5",
            "rodimpact: no rule makes 'results/convergence/model/sem/level9.h5'; "
            "results/convergence/ holds: results/convergence/{case}/{method}/part{part}.h5",
        ),
        (
            "results/convergence/model/nosuch/part0.h5",
            "rodimpact: no rule makes 'results/convergence/model/nosuch/part0.h5'; "
            "results/convergence/ holds: results/convergence/{case}/{method}/part{part}.h5",
        ),
        (
            "results/runs/model/sem/part1.h5",
            "rodimpact: group 'model' by sem has one part: part0 (batch.target_s = 30 s)",
        ),
        (
            "results/sweeps/ball_sweep-r1_l301/sem/ball_diameter_m~0.5.h5",
            "rodimpact: no rule makes 'results/sweeps/ball_sweep-r1_l301/sem/ball_diameter_m~0.5.h5'; "
            "results/sweeps/ holds: results/sweeps/{case}/{method}/part{part}.h5",
        ),
        (
            "results/sweeps/ball_sweep-r1_l301/sem/part3.h5",
            "rodimpact: sweep 'ball_sweep-r1_l301' by sem has one part: part0 (batch.target_s = 30 s)",
        ),
        ("tables", "rodimpact: no rule makes 'tables' and no rule has that name; rules: all, "),
    ],
    ids=[
        "unknown group",
        "method no case of the group runs",
        "a level (a run in its part's file)",
        "an unknown method's levels",
        "a part the group's batch does not have",
        "a sweep point (a run in its part's file)",
        "a part the sweep does not have",
        "unknown rule",
    ],
)
def test_a_target_the_configuration_does_not_define_is_one_line(project: Path, target: str, expected: str) -> None:
    assert_one_line_refusal(snakemake(project, "-n", target), expected)


def test_a_batchs_folder_as_a_target_is_one_line_naming_its_parts(project: Path, tmp_path: Path) -> None:
    """A batch's folder (which holds its parts' files once built) is no output: asked for, it is
    refused in one line that names the parts' pattern, also when it exists."""
    path = clone_built(project, tmp_path / "project")
    (path / "results/runs/model/sem").mkdir(parents=True)
    assert_one_line_refusal(
        snakemake(path, "-n", "results/runs/model/sem"),
        "rodimpact: no rule makes 'results/runs/model/sem'; results/runs/ holds: results/runs/{group}/{method}/"
        "part{part}.h5",
    )


@pytest.mark.parametrize(
    "text, expected",
    [
        ("targets:\n  sets: [model\n", "rodimpact: invalid configuration: config/config.yaml: invalid YAML at line "),
        (
            "- just\n- a list\n",
            "rodimpact: invalid configuration: config/config.yaml: must be a mapping of settings, got list",
        ),
    ],
    ids=["syntax error", "not a mapping"],
)
def test_a_broken_config_yaml_is_one_line(project: Path, text: str, expected: str) -> None:
    config = project / "config" / "config.yaml"
    original = config.read_text(encoding="utf-8")
    try:
        config.write_text(original + text if text.startswith("targets") else text, encoding="utf-8")
        run = snakemake(project, "-n", SOLVE_BATCH)
    finally:
        config.write_text(original, encoding="utf-8")
    assert_one_line_refusal(run, expected)
    if text.startswith("targets"):
        assert ", column " in last_line(run)


def test_a_directory_among_the_case_files_is_refused_after_a_good_dry_run(project: Path) -> None:
    """Planning keeps nothing between runs: the dry run after a good one reads config/cases/ anew."""
    assert snakemake(project, "-n", SOLVE_BATCH).returncode == 0
    odd = project / "config" / "cases" / "dir.yaml"
    odd.mkdir()
    try:
        run = snakemake(project, "-n", SOLVE_BATCH)
    finally:
        odd.rmdir()
    assert_one_line_refusal(run, "rodimpact: invalid configuration: ")
    assert "dir.yaml" in last_line(run), run.describe()


# ------------------------------------------------------------------ kills and concurrent builds


@pytest.mark.parametrize("wrapper", [(), ("timeout", "500"), ("/usr/bin/time",)], ids=["plain", "timeout", "time"])
def test_a_killed_build_leaves_a_lock_that_the_next_run_releases(tmp_path: Path, wrapper: tuple[str, ...]) -> None:
    """The same command again releases the killed run's lock, also under a wrapper whose own
    command line names snakemake (it is no live run)."""
    path = copy_project(tmp_path / "project")
    build = start(path, "-j1", SOLVE_BATCH)
    try:
        wait_for(lambda: locks(path) or build.poll() is not None, 120, "the build to lock the directory")
        os.killpg(build.pid, signal.SIGKILL)  # a power cut: snakemake and its job die at once
    finally:
        build.wait(30)
    assert locks(path), "the killed run left no lock: the test did not kill it in time"
    target = path / SOLVE_BATCH
    assert not target.exists() or read_run(path / SOLVE).case_id == "model"  # nothing readable is half-written
    # what a kill during the part's write leaves beside it: its temporary file, half-written
    stale = path / "results/runs/model/sem/part0.tmp-0123abcd.h5"
    stale.parent.mkdir(parents=True, exist_ok=True)
    stale.write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(64))
    rerun = snakemake(path, "-j1", SOLVE_BATCH, timeout=BUILD_TIMEOUT_S, wrapper=wrapper)
    assert rerun.returncode == 0, rerun.describe()
    assert "rodimpact: released snakemake's lock of " in rerun.output
    assert not stale.exists() and read_run(path / SOLVE).case_id == "model"
    assert not locks(path)


def test_a_rerun_while_a_killed_runs_job_still_runs_starts_nothing(tmp_path: Path) -> None:
    """snakemake killed alone (its job keeps running and writing): a rerun at once keeps the lock
    and stops in one line naming the job, so the job's output is written once, by the job."""
    path = copy_project(tmp_path / "project")
    batch = "results/runs/r10_l30/fem_axi/part0.h5"  # continuum solves: tens of seconds in one job

    def solving() -> dict[int, str]:
        return {pid: script for pid, script in (live_job_pids(path) or {}).items() if script == "solve_part.py"}

    build = start(path, "-j1", batch)
    try:
        wait_for(lambda: solving() or build.poll() is not None, 180, "the build to start its batch")
        jobs = solving()
        assert jobs, "the build ended before its job was seen"
        os.kill(build.pid, signal.SIGKILL)  # snakemake alone: its job is orphaned and goes on
        build.wait(30)
        rerun = snakemake(path, "-j1", batch, timeout=BUILD_TIMEOUT_S)
        assert rerun.returncode != 0, rerun.describe()
        assert last_line(rerun).startswith("rodimpact: a killed run's jobs still run in "), rerun.describe()
        assert all(f"pid {pid} " in last_line(rerun) for pid in jobs), rerun.describe()
        assert "Select jobs to execute" not in rerun.output  # nothing planned, nothing started
        assert locks(path), "the lock of the orphaned job was released"
        wait_for(lambda: not live_job_pids(path), 300, "the orphaned job to end")
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(build.pid, signal.SIGKILL)
    written = run_references(path / batch)  # the orphan finished its part, once, whole
    assert written and all(read_run(run).method == "fem_axi" for run in written)


def test_a_second_build_under_a_live_one_is_refused_and_the_lock_kept(tmp_path: Path) -> None:
    path = copy_project(tmp_path / "project")
    first = start(path, "-j1", LONG)  # many jobs one after another: longer than the second's planning
    try:
        wait_for(lambda: locks(path) or first.poll() is not None, 120, "the first build to lock the directory")
        second = snakemake(path, "-j1", LONG, timeout=BUILD_TIMEOUT_S)
        output, _ = first.communicate(timeout=BUILD_TIMEOUT_S)
    finally:
        if first.poll() is None:
            os.killpg(first.pid, signal.SIGKILL)
    assert first.returncode == 0, output
    # snakemake refuses it: the live run's lock, or the job it is writing (its incomplete output)
    assert second.returncode != 0, second.describe()
    assert "LockException" in second.output or "IncompleteFilesException" in second.output, second.describe()
    assert "released snakemake's lock" not in second.output
    assert (path / LONG).is_file()


def _on_another_host(project: Path, *args: str) -> list[str]:
    """A snakemake command run as on a compute node sharing this file system: its own host name
    and process namespace (``unshare``, as root), so that it sees none of this machine's runs."""
    if os.geteuid() != 0 or shutil.which("unshare") is None:
        pytest.skip("needs root and unshare to give snakemake a host of its own")
    probe = subprocess.run(
        ["unshare", "--uts", "--pid", "--fork", "--mount-proc", "true"], capture_output=True, check=False
    )
    if probe.returncode != 0:
        pytest.skip(f"unshare refused here: {probe.stderr.decode(errors='replace').strip()}")
    inner = " ".join(shlex.quote(part) for part in snakemake_command(args, None))
    return ["unshare", "--uts", "--pid", "--fork", "--mount-proc", "sh", "-c", f"hostname node7 && exec {inner}"]


def test_a_job_parsing_the_workflow_on_another_host_keeps_a_live_builds_lock(tmp_path: Path) -> None:
    """Every cluster job parses the workflow on its node, where the build's process is not
    visible: the run registry (the build's record) keeps the lock."""
    path = copy_project(tmp_path / "project")
    build = start(path, "-j1", LONG)
    try:
        wait_for(
            lambda: (locks(path) and registered(path)) or build.poll() is not None,
            120,
            "the build to lock the directory and register itself",
        )
        held = locks(path)
        assert held and build.poll() is None, "the build ended before the node's parse: nothing was tested"
        node = subprocess.run(
            _on_another_host(path, "-n", SOLVE_BATCH),
            cwd=path,
            env=snakemake_environment(),
            capture_output=True,
            text=True,
            timeout=BUILD_TIMEOUT_S,
            check=False,
        )
        still_live = build.poll() is None
        kept = all(lock.exists() for lock in held)
    finally:
        if build.poll() is None:
            os.killpg(build.pid, signal.SIGKILL)
        build.wait(30)
    assert still_live, "the build ended during the node's parse: nothing was tested"
    assert "released snakemake's lock" not in node.stdout + node.stderr, node.stdout + node.stderr
    assert kept


def registered(project: Path) -> list[Path]:
    directory = project / RUNS_DIR
    return sorted(directory.iterdir()) if directory.is_dir() else []


# ------------------------------------------------------------------ damaged and edited inputs


def _damage(run_file: Path, name: str, how: str) -> None:
    """Truncate the file of runs ``run_file``, or edit its run ``name``."""
    if how == "truncated":
        data = run_file.read_bytes()
        run_file.write_bytes(data[: len(data) // 2])
    else:
        with h5py.File(run_file, "r+") as h5:
            h5[name]["contact_force"][3] = 7.0


@pytest.mark.parametrize(
    "how, reason",
    [
        ("truncated", "results/runs/model/sem/part0.h5"),
        (
            "edited",
            "results/runs/model/sem/part0.h5#model: its content differs from its data_sha256 (changed after it was "
            "written)",
        ),
    ],
)
def test_a_damaged_run_is_named_marked_and_remade(built: Path, tmp_path: Path, how: str, reason: str) -> None:
    """A damaged part's file: the job that reads its run refuses it in one line that names it,
    marks the file out of date, and the next build remakes the part and what reads it."""
    path = clone_built(built, tmp_path / "project")
    run_file = path / SOLVE_BATCH
    _damage(run_file, "model", how)
    # snakemake sees a newer input (not the damage): the table is planned, its part is not
    planned = snakemake(path, "-n", TABLE)
    assert planned.returncode == 0 and "paper_model" in planned.output, planned.describe()
    assert "rule solve:" not in planned.output, planned.describe()
    failed = snakemake(path, "-j1", TABLE, timeout=BUILD_TIMEOUT_S)
    assert failed.returncode != 0, failed.describe()
    assert "Traceback" not in failed.output, failed.describe()
    refusal = [line for line in failed.output.splitlines() if "failed: " in line and reason in line]
    assert refusal and refusal[0].endswith(REBUILD_HINT), failed.describe()
    assert run_file.stat().st_mtime == 0.0  # marked out of date: its part is remade
    table = path / TABLE
    assert not table.exists() or table.read_text(encoding="utf-8").count("\n") > 1
    recovered = snakemake(path, "-j1", TABLE, timeout=BUILD_TIMEOUT_S)
    assert recovered.returncode == 0, recovered.describe()
    assert "rule solve:" in recovered.output, recovered.describe()
    assert read_run(path / SOLVE).case_id == "model" and table.is_file()


BATCH = "results/convergence/model/sem/part0.h5"  # one job: the SEM's work-precision levels on model


def test_a_damaged_run_of_a_batch_is_named_marked_and_remade(project: Path, tmp_path: Path) -> None:
    """A run in a part's file of runs: its reader names the run and marks the file out of date,
    and the next build remakes the part."""
    path = clone_built(project, tmp_path / "project")
    built = snakemake(path, "-j1", BATCH, timeout=BUILD_TIMEOUT_S)
    assert built.returncode == 0, built.describe()
    run_file = path / BATCH
    _damage(run_file, "level0", "edited")
    with pytest.raises(ValueError, match="level0: its content differs from its data_sha256") as refused:
        read_run(f"{run_file}#level0")
    assert str(refused.value).endswith(REBUILD_HINT)
    assert run_file.stat().st_mtime == 0.0
    planned = snakemake(path, "-n", BATCH)
    assert planned.returncode == 0 and "solve_levels" in planned.output, planned.describe()
    recovered = snakemake(path, "-j1", BATCH, timeout=BUILD_TIMEOUT_S)
    assert recovered.returncode == 0, recovered.describe()
    assert read_run(f"{run_file}#level0").case_id == "model"


CURVES = "results/indentation/r10_l30_cal"  # one job: the continuum's indentation of the reading's balls


def test_a_damaged_file_of_a_directory_output_is_marked_with_its_directory(project: Path, tmp_path: Path) -> None:
    """A file inside a rule's output directory (a group's contact-law curves): its reader marks the
    file and the directory's timestamp, by which snakemake dates the directory, and the next
    build remakes the directory."""
    path = clone_built(project, tmp_path / "project")
    built = snakemake(path, "-j1", CURVES, timeout=BUILD_TIMEOUT_S)
    assert built.returncode == 0, built.describe()
    curve = sorted((path / CURVES).glob("*.h5"))[0]
    with h5py.File(curve, "r+") as h5:
        h5["force_N"][3] *= 1.01
    assert "Nothing to be done" in snakemake(path, "-n", CURVES).output  # the edit alone plans nothing
    with pytest.raises(StoredFileError, match="data_sha256"):
        read_contact_curve(curve)
    assert curve.stat().st_mtime == 0.0 and (path / CURVES / DIRECTORY_TIMESTAMP).stat().st_mtime == 0.0
    planned = snakemake(path, "-n", CURVES)
    assert planned.returncode == 0 and "indentation" in job_stats(planned.output), planned.describe()


# ------------------------------------------------------------------ a full disk


def test_a_full_disk_is_one_line_and_leaves_no_temporary(tmp_path: Path) -> None:
    path = copy_project(tmp_path / "project")
    mount = path / "results" / "runs"  # the run's folder is made inside it (snakemake removes it on failure)
    mount.mkdir(parents=True)
    mounted = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", "size=4m", "tmpfs", str(mount)], capture_output=True, text=True, check=False
    )
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a small file system here ({mounted.stderr.strip() or 'mount failed'})")
    try:
        filler = mount / "filler"
        try:  # fill it to the last block
            with open(filler, "wb", buffering=0) as handle:
                while True:
                    handle.write(bytes(4096))
        except OSError:
            pass
        failed = snakemake(path, "-j1", SOLVE_BATCH, timeout=BUILD_TIMEOUT_S)
        assert failed.returncode != 0, failed.describe()
        assert "Traceback" not in failed.output, failed.describe()
        assert any("failed: " in line and "No space left on device" in line for line in failed.output.splitlines()), (
            failed.describe()
        )
        left = (
            sorted(p.name for p in (mount / "model").rglob("*") if not p.is_dir()) if (mount / "model").is_dir() else []
        )
        assert left == []  # no temporary, no half-written run
        filler.unlink()
        recovered = snakemake(path, "-j1", SOLVE_BATCH, timeout=BUILD_TIMEOUT_S)
        assert recovered.returncode == 0, recovered.describe()
        assert read_run(path / SOLVE).case_id == "model"
    finally:
        subprocess.run(["umount", str(mount)], capture_output=True, check=False)
        shutil.rmtree(mount, ignore_errors=True)
