"""Input and code that must not get through the workflow: a job runs its own checkout's code,
bad input stops everything before any job with one line, and a failing solver leaves no file.

Each test works in a fresh, shrunk copy of the project (``helpers.copies.copy_project``).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from helpers.copies import batch_part, copy_project
from helpers.snakemake_cli import BUILD_TIMEOUT_S, snakemake

pytestmark = pytest.mark.workflow


def test_jobs_run_the_checkouts_own_code(tmp_path: Path) -> None:
    """A job imports the copy's src/, not the repository's installed package."""
    project = copy_project(tmp_path / "project")
    runner = project / "src" / "rodimpact" / "jobs" / "runner.py"
    runner.write_text(runner.read_text() + '\nraise ImportError("runner.py of the copy")\n')
    run = snakemake(project, "-j1", batch_part("model", "sem"), timeout=BUILD_TIMEOUT_S)
    assert run.returncode != 0, run.describe()
    log = project / "logs" / "runs" / "model" / "sem" / "part0.log"
    assert "runner.py of the copy" in run.output + (log.read_text() if log.exists() else ""), run.describe()


def _negative_mass(project: Path) -> None:
    path = project / "config/cases/model.yaml"
    text = path.read_text(encoding="utf-8")
    assert text.count("mass_kg: 0.5\n") == 1
    path.write_text(text.replace("mass_kg: 0.5\n", "mass_kg: -0.5\n"), encoding="utf-8")


def _unknown_method(project: Path) -> None:
    path = project / "config/cases/model.yaml"
    text = path.read_text(encoding="utf-8")
    assert text.count("methods: [sem, sem_paper, fem1d, fem_axi]") == 1
    path.write_text(
        text.replace("methods: [sem, sem_paper, fem1d, fem_axi]", "methods: [sem, fem2d]"), encoding="utf-8"
    )


def _unknown_variant(project: Path) -> None:
    path = project / "config/cases/table2.yaml"
    text = path.read_text(encoding="utf-8")
    anchor = "  - id: ball_4.75mm\n"
    assert text.count(anchor) == 1
    path.write_text(text.replace(anchor, anchor + "    variants: [r10_l30, r2_l30]\n"), encoding="utf-8")


@pytest.mark.parametrize(
    ("break_config", "file", "case", "field"),
    [
        pytest.param(_negative_mass, "config/cases/model.yaml", "model", "impactor.mass_kg", id="negative-mass"),
        pytest.param(_unknown_method, "config/cases/model.yaml", "model", "methods[1]", id="unknown-method"),
        pytest.param(_unknown_variant, "config/cases/table2.yaml", "ball_4.75mm", "variants[1]", id="unknown-variant"),
    ],
)  # fmt: skip
def test_bad_input_stops_before_any_job(tmp_path: Path, break_config, file: str, case: str, field: str) -> None:
    project = copy_project(tmp_path / "project")
    break_config(project)
    run = snakemake(project, "-n", "-j2")
    assert run.returncode != 0, run.describe()
    lines = [line for line in run.output.splitlines() if line.strip()]
    assert len(lines) == 1, f"expected one line, got:\n{run.output}"
    message = lines[0]
    assert message.startswith("rodimpact: invalid configuration: ")
    assert file in message and f"case '{case}'" in message and f"field '{field}'" in message, message
    assert "Traceback" not in run.output
    assert not (project / "results").exists()
    assert not (project / "logs").exists()


# --------------------------------------------------------------------------------------------
# atomic outputs
# --------------------------------------------------------------------------------------------

# A 1 ms step is longer than the whole horizon (1.0001 x the ~0.88 ms contact-time estimate of
# 'model'): the first step ends past the horizon with the first contact not over, so the
# solver reports failure and runner.run_case raises SolverFailed (checked with the library).
FAILING_NUMERICS = """\
    numerics:
      sem: {dt_s: 1.0e-3, max_time_factor: 1.0001}
"""


def test_failing_solver_leaves_no_file(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    with open(project / "config/cases/model.yaml", "a", encoding="utf-8") as handle:
        handle.write(FAILING_NUMERICS)
    target = batch_part("model", "sem")
    # --keep-incomplete: snakemake must not be the one that cleans up; the rule itself must
    # never leave a (half-)file behind.
    run = snakemake(project, "-j1", "--keep-incomplete", target, timeout=BUILD_TIMEOUT_S)
    assert run.returncode != 0, run.describe()
    assert "Error in rule solve" in run.output, run.describe()
    log = (project / "logs/runs/model/sem/part0.log").read_text(encoding="utf-8")
    assert "SolverFailed" in log and "before the first contact ended" in log, log
    assert not (project / target).exists()
    run_dir = project / "results/runs/model"
    leftovers = [p.name for p in run_dir.rglob("*") if not p.is_dir()] if run_dir.exists() else []
    assert not [name for name in leftovers if ".tmp" in name], leftovers
    assert leftovers == [], leftovers


# --------------------------------------------------------------------------------------------
# files a case points to, read safely
# --------------------------------------------------------------------------------------------


def test_a_fifo_for_a_case_file_is_one_line_not_a_hang(tmp_path: Path) -> None:
    """A FIFO named like a case file blocked planning for ever (a read waits for a writer): it is
    refused in one line naming the file and what it is."""
    import os

    project = copy_project(tmp_path / "project")
    os.mkfifo(project / "config/cases/pipe.yaml")
    run = snakemake(project, "-n", timeout=120)
    assert run.returncode != 0, run.describe()
    lines = [line for line in run.output.splitlines() if line.strip()]
    assert lines[-1] == (
        "rodimpact: invalid configuration: config/cases/pipe.yaml: is a FIFO (named pipe), not a regular file"
    ), run.output


def test_a_history_linked_outside_is_refused(tmp_path: Path) -> None:
    """A history replaced, after a good dry run, by a link to a copy of its bytes outside the case
    file's directory: refused in one line."""
    project = copy_project(tmp_path / "project")
    assert snakemake(project, "-n", timeout=120).returncode == 0
    history = project / "config/cases/example/ball_10mm.synthetic.csv"
    outside = tmp_path / "elsewhere.csv"
    outside.write_bytes(history.read_bytes())
    history.unlink()
    history.symlink_to(outside)
    run = snakemake(project, "-n", timeout=120)
    assert run.returncode != 0, run.describe()
    assert "lies outside the directory of its case file" in run.output, run.output


#: A strain record's rows for the large-record test: 64-character cells (the longest a cell may
#: be), so that ~800,000 rows make a file between 64 and 128 MiB.
_WIDE = "{:064.9f},{:064.9f}\n"


def test_a_large_record_edited_at_the_same_size_reaches_the_next_plan(tmp_path: Path) -> None:
    """A record of about 100 MiB (between the 64 MiB other inputs may have and the 128 MiB a record
    may have) passes a dry run; one cell then set to NaN, the file's size and time kept, is
    refused by the next dry run: every plan reads each record whole, whatever its size."""
    project = copy_project(tmp_path / "project")
    record = project / "config/cases/example/gauge_8mm.synthetic.csv"
    shipped = np.loadtxt(record, delimiter=",", skiprows=1)
    times = np.linspace(shipped[0, 0], shipped[-1, 0], 800_000)
    strain = np.interp(times, shipped[:, 0], shipped[:, 1])
    with open(record, "w", encoding="utf-8") as stream:
        stream.write("time_us,strain_microstrain\n")
        stream.writelines(_WIDE.format(t, s) for t, s in zip(times, strain, strict=True))
    size = record.stat().st_size
    assert 64 * 2**20 < size < 128 * 2**20, size
    run = snakemake(project, "-n", timeout=300)
    assert run.returncode == 0, run.describe()
    stat = record.stat()
    with open(record, "r+b") as stream:  # the 400,000th row's strain: 64 characters, NaN
        stream.seek(len("time_us,strain_microstrain\n") + 400_000 * 130 + 65)
        stream.write(b" " * 61 + b"nan")
    os.utime(record, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert record.stat().st_size == size
    run = snakemake(project, "-n", timeout=300)
    assert run.returncode != 0, run.describe()
    lines = [line for line in run.output.splitlines() if line.strip()]
    assert len(lines) == 1 and "field 'measured.strain_history.file'" in lines[0], run.output
    assert "line 400002: not a finite number" in lines[0], lines[0]
