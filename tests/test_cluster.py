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

import dataclasses
import json
import re
import sys
from pathlib import Path

import pytest
import yte

from rodimpact.jobs.resources import PRESENTATION, estimate_sequence

from helpers.copies import copy_project, project_cases
from helpers.snakemake_cli import snakemake

pytestmark = pytest.mark.workflow

FAKE_SUBMIT = Path(__file__).resolve().parent / "data" / "fake_submit.py"
TABLE = "results/tables/fig2_comparison.csv"
TIMEOUT_S = 300


def test_every_job_is_submitted_with_its_estimated_resources(tmp_path: Path) -> None:
    project = copy_project(tmp_path / "project")
    record = tmp_path / "submissions.jsonl"
    submit = (
        f"{sys.executable} {FAKE_SUBMIT} --record={record} --mem={{resources.mem_mb}} "
        f"--time={{resources.runtime}} --cpus={{threads}} --name={{rule}}"
    )
    model = project_cases(project).cases["model"]
    runs = [f"results/runs/model/{method}" for method in model["methods"]]  # a batch each (one case)

    run = snakemake(
        project,
        "--executor",
        "cluster-generic",
        "--cluster-generic-submit-cmd",
        submit,
        "--jobs",
        "2",
        "--latency-wait",
        "10",
        *runs,
        TABLE,
        timeout=TIMEOUT_S,
    )

    assert run.returncode == 0, run.describe()
    for path in (*runs, TABLE):
        assert (project / path).exists(), f"{path} was not built\n{run.describe()}"
    entries = [json.loads(line) for line in record.read_text(encoding="utf-8").splitlines()]
    # every rule of a cluster run is in a group (workflow/rules/common.smk): with no
    # group-components (the stand-in has none), each job is a group of its own, sized as the job
    expected_of = {run: estimate_sequence([(model, Path(run).name, 1)]) for run in runs}
    # the table's job (paper_model) also draws the force's closed form, so its group holds the
    # force export it reads: two presentation jobs one after another, their run times summed
    expected_of[TABLE] = dataclasses.replace(PRESENTATION, runtime_min=2 * PRESENTATION.runtime_min)
    group_of = {**{run: "solvers" for run in runs}, TABLE: "tables"}
    submitted = sorted(next(o for o in entry["output"] if o in expected_of) for entry in entries)
    assert submitted == sorted(expected_of), entries
    for entry in entries:
        assert entry["returncode"] == 0, entry
        target = next(o for o in entry["output"] if o in expected_of)
        expected = expected_of[target]
        assert (entry["type"], entry["groupid"]) == ("group", group_of[target]), entry
        options = dict(arg.lstrip("-").split("=", 1) for arg in entry["argv"])
        assert options == {
            "mem": str(expected.mem_mb),
            "time": str(expected.runtime_min),
            "cpus": str(expected.threads),
            "name": "GROUP",
        }, entry
        # what the command line carried is what snakemake holds for the job (its jobscript)
        assert entry["resources"]["mem_mb"] == expected.mem_mb, entry
        assert entry["resources"]["runtime"] == expected.runtime_min, entry
        assert entry["threads"] == expected.threads, entry
    # the estimate follows the case: the continuum model asks for more than the SEM
    by_method = {Path(e["output"][0]).stem: e["resources"] for e in entries if e["groupid"] == "solvers"}
    assert by_method["fem_axi"]["mem_mb"] > by_method["sem"]["mem_mb"]


def test_every_submitted_rule_is_in_a_group_the_slurm_profile_sizes() -> None:
    """Every rule a cluster runs declares its group (the case files are local rules, the
    benchmarks want a node of their own), and the profile sizes exactly the declared groups."""
    rules_dir = Path(__file__).resolve().parents[1] / "workflow" / "rules"
    common = (rules_dir / "common.smk").read_text(encoding="utf-8")
    groups = dict(re.findall(r'^(GROUP_\w+) = "(\w+)"$', common, re.M))
    ungrouped = {"case_file", "bench_sem", "bench_fem", "bench_sem_scaling"}
    missing, unknown = [], []
    for path in sorted(rules_dir.glob("*.smk")):
        blocks = re.split(r"^\s*rule(?= |:)", path.read_text(encoding="utf-8"), flags=re.M)[1:]
        for block in blocks:
            name = re.match(r"\s*(\w*):", block).group(1) or re.search(r'name:\s*\n\s*f"(\w+?)_?\{', block).group(1)
            if "script:" not in block or name in ungrouped:
                continue
            declared = re.search(r"^\s+group:\s+(\w+)\s*$", block, re.M)  # its value on the line or the next
            if declared is None:
                missing.append(f"{path.name}: {name}")
            elif declared.group(1) not in groups:
                unknown.append(f"{path.name}: {name}: {declared.group(1)}")
    assert not missing and not unknown, (missing, unknown)
    with open(rules_dir.parents[1] / "profiles" / "slurm" / "config.yaml", encoding="utf-8") as handle:
        profile = yte.process_yaml(handle, require_use_yte=True)
    assert set(profile["group-components"]) == set(groups.values())
