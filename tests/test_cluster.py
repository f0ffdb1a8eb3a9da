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
import re
import sys
from pathlib import Path

import pytest
import yaml
import yte

from rodimpact.jobs.resources import estimate_sequence
from rodimpact.storage.runs import read_run, run_references

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
    runs = [f"results/runs/model/{method}/part0.h5" for method in model["methods"]]  # a batch each (one case)

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
    # every solver rule is in the group `solvers` (workflow/rules/common.smk): with no
    # group-components (the stand-in has none), each job is a group of its own, sized as the job;
    # the table, and the force export its job reads, are local rules: written here, never submitted
    expected_of = {run: estimate_sequence([(model, Path(run).parent.name, 1)]) for run in runs}
    submitted = sorted(next(o for o in entry["output"] if o in expected_of) for entry in entries)
    assert submitted == sorted(expected_of), entries
    local = [o for entry in entries for o in entry["output"] if o == TABLE or o.startswith("results/forces/")]
    assert not local, entries
    for entry in entries:
        assert entry["returncode"] == 0, entry
        target = next(o for o in entry["output"] if o in expected_of)
        expected = expected_of[target]
        assert (entry["type"], entry["groupid"]) == ("group", "solvers"), entry
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
    by_method = {Path(e["output"][0]).parent.name: e["resources"] for e in entries}
    assert by_method["fem_axi"]["mem_mb"] > by_method["sem"]["mem_mb"]


def test_every_rule_is_local_or_in_a_group_the_slurm_profile_sizes() -> None:
    """Every rule a cluster runs is either a local rule (the case files, the tables, the figures
    and the force export: written where snakemake runs) or in a declared group (the solvers: a
    batch's part is in it when the batch is one part, ``part_group``); only the benchmarks (each
    wants a node of its own) are neither. The profile sizes exactly the declared groups."""
    rules_dir = Path(__file__).resolve().parents[1] / "workflow" / "rules"
    common = (rules_dir / "common.smk").read_text(encoding="utf-8")
    groups = dict(re.findall(r'^(GROUP_\w+) = "(\w+)"$', common, re.M))
    alone = {"bench_sem", "bench_fem", "bench_sem_scaling"}
    local, grouped, neither, both, unknown = set(), set(), [], [], []
    for path in sorted(rules_dir.glob("*.smk")):
        blocks = re.split(r"^\s*rule(?= |:)", path.read_text(encoding="utf-8"), flags=re.M)[1:]
        for block in blocks:
            name = re.match(r"\s*(\w*):", block).group(1) or re.search(r'name:\s*\n\s*f"(\w+?)_?\{', block).group(1)
            if "script:" not in block or name in alone:
                continue
            is_local = re.search(r"^\s+localrule:\s+True\s*$", block, re.M) is not None
            # its value on the line or the next: a group's name, or part_group (a batch's parts)
            declared = re.search(r"^\s+group:\s+(\w+)(?:\(\"\w+\"\))?\s*$", block, re.M)
            if is_local and declared:
                both.append(f"{path.name}: {name}")
            elif is_local:
                local.add(name)
            elif declared is None:
                neither.append(f"{path.name}: {name}")
            elif declared.group(1) not in (*groups, "part_group"):
                unknown.append(f"{path.name}: {name}: {declared.group(1)}")
            else:
                grouped.add(name)
    assert not neither and not both and not unknown, (neither, both, unknown)
    assert {"case_file", "paper_model", "compare", "forces"} <= local, local
    assert {"solve", "solve_levels", "solve_stress", "solve_sweep", "indentation", "calibrate"} <= grouped, grouped
    with open(rules_dir.parents[1] / "profiles" / "slurm" / "config.yaml", encoding="utf-8") as handle:
        profile = yte.process_yaml(handle, require_use_yte=True)
    assert set(profile["group-components"]) == set(groups.values())


def test_a_batch_cut_into_parts_is_submitted_part_by_part(tmp_path: Path) -> None:
    """A batch the target cuts into several parts (the stability map's references at a target
    below one point's cost: a part per point) sends each part alone, in no group, with its own
    part's resources; a batch of one part (model by sem) still goes in the group of the solvers."""
    project = copy_project(tmp_path / "project")
    config = project / "config" / "config.yaml"
    document = yaml.safe_load(config.read_text(encoding="utf-8"))
    document["batch"] = {"target_s": 1.0e-3}
    config.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    record = tmp_path / "submissions.jsonl"
    submit = f"{sys.executable} {FAKE_SUBMIT} --record={record} --name={{rule}}"
    parts = [f"results/stability_map/reference/part{k}.h5" for k in range(2)]
    single = "results/runs/model/sem/part0.h5"
    run = snakemake(
        project,
        *("--executor", "cluster-generic", "--cluster-generic-submit-cmd", submit, "--jobs", "2"),
        *("--latency-wait", "10", *parts, single),
        timeout=TIMEOUT_S,
    )
    assert run.returncode == 0, run.describe()
    entries = [json.loads(line) for line in record.read_text(encoding="utf-8").splitlines()]
    by_output = {o: entry for entry in entries for o in entry["output"] if o in (*parts, single)}
    assert sorted(by_output) == sorted([*parts, single]), entries
    assert all(by_output[p]["type"] == "single" and not by_output[p]["groupid"] for p in parts), entries
    assert (by_output[single]["type"], by_output[single]["groupid"]) == ("group", "solvers"), entries
    for path in parts:  # a point each, its run named in its part's file
        assert len(run_references(project / path)) == 1
    assert {read_run(r).config["row"] for p in parts for r in run_references(project / p)} == {"m0_z0", "m0_z1"}
