"""What the workflow sends to a cluster: every job's threads, memory and run time.

A temporary copy of the project is run through snakemake's cluster-generic executor with a
stand-in submit command (tests/data/fake_submit.py) that records its arguments, runs the
jobscript and prints a job id. Without a status command the executor learns that a job
ended from the marker file the jobscript touches at its end (``<jobid>.jobfinished`` or
``.jobfailed`` in snakemake's temporary directory), so a submit command that returns only
when the job is over works. No SLURM here: the stand-in proves what a real submit command
(sbatch through profiles/slurm) would be given.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from rodimpact.jobs.resources import PRESENTATION, estimate_resources

from helpers.copies import copy_project, project_cases
from helpers.snakemake_cli import snakemake

pytestmark = pytest.mark.workflow

FAKE_SUBMIT = Path(__file__).resolve().parent / "data" / "fake_submit.py"
TABLE = "results/tables/fig2_comparison.csv"
TIMEOUT_S = 300


def test_every_job_is_submitted_with_its_estimated_resources(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    record = tmp_path / "submissions.jsonl"
    submit = (f"{sys.executable} {FAKE_SUBMIT} --record={record} --mem={{resources.mem_mb}} "
              f"--time={{resources.runtime}} --cpus={{threads}} --name={{rule}}")
    model = project_cases(project).cases["model"]
    runs = [f"results/runs/model/{method}.h5" for method in model["methods"]]

    run = snakemake(project, "--executor", "cluster-generic", "--cluster-generic-submit-cmd", submit,
                    "--jobs", "2", "--latency-wait", "10", *runs, TABLE, timeout=TIMEOUT_S)

    assert run.returncode == 0, run.describe()
    for path in (*runs, TABLE):
        assert (project / path).is_file(), f"{path} was not built\n{run.describe()}"
    entries = [json.loads(line) for line in record.read_text(encoding="utf-8").splitlines()]
    submitted = sorted((e["rule"], e["wildcards"].get("method", "")) for e in entries)
    assert submitted == sorted([("solve", m) for m in model["methods"]] + [("fig2_comparison", "")]), submitted
    for entry in entries:
        assert entry["returncode"] == 0, entry
        if entry["rule"] == "solve":
            expected = estimate_resources(model, entry["wildcards"]["method"])
        else:
            expected = PRESENTATION
        options = dict(arg.lstrip("-").split("=", 1) for arg in entry["argv"])
        assert options == {"mem": str(expected.mem_mb), "time": str(expected.runtime_min),
                           "cpus": str(expected.threads), "name": entry["rule"]}, entry
        # what the command line carried is what snakemake holds for the job (its jobscript)
        assert entry["resources"]["mem_mb"] == expected.mem_mb, entry
        assert entry["resources"]["runtime"] == expected.runtime_min, entry
        assert entry["threads"] == expected.threads, entry
    # the estimate follows the case: the continuum model asks for more than the SEM
    by_method = {e["wildcards"]["method"]: e["resources"] for e in entries if e["rule"] == "solve"}
    assert by_method["fem_axi"]["mem_mb"] > by_method["sem"]["mem_mb"]
