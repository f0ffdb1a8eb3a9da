"""Job resources estimated from the case (rodimpact.jobs.resources): what they follow, that they
cover what a real run takes, and that bad input is refused by name."""

from __future__ import annotations

import copy
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from rodimpact.analysis.studies import level_case
from rodimpact.analysis.sweeps import sweep_point_case, sweep_points
from rodimpact.jobs.resources import (
    MIN_MEM_MB,
    MIN_RUNTIME_MIN,
    PRESENTATION,
    SAFETY,
    JobResources,
    estimate_resources,
    estimate_sequence,
    run_cost,
    timed_cost,
)
from rodimpact.model.problem import ImpactProblem
from rodimpact.plumbing.sources import module_sources
from rodimpact.solvers.cost import Cost
from rodimpact.solvers.fem_axi.cost import fem_axi_dofs, fem_axi_indentation_cost
from rodimpact.tools.bench import resource_margins
from rodimpact.tools.bench_plan import fem_bench_runs, sem_bench_runs

from helpers.repo import ROOT as REPO

SRC = REPO / "src"
#: A coarse fem_axi run (the level the workflow tests use): a few seconds.
COARSE_AXI = {"elements_across": 4, "steps_per_contact": 80}


@pytest.fixture(scope="module")
def project(shipped_config, shipped_project):
    return shipped_config, shipped_project


@pytest.fixture(scope="module")
def model(project):
    return project[1].cases["model"]


def with_numerics(case, method, **settings):
    out = copy.deepcopy(dict(case))
    out["numerics"][method] = {**out["numerics"][method], **settings}
    return out


def test_finer_fem_axi_level_needs_more_memory_and_time(project, model):
    config, _ = project
    levels = config["work_precision"]["methods"]["fem_axi"]["levels"]
    estimates = [
        estimate_resources(level_case(model, "fem_axi", config["numerics"], level), "fem_axi") for level in levels
    ]
    dofs = [fem_axi_dofs(level_case(model, "fem_axi", config["numerics"], level)) for level in levels]
    assert dofs == sorted(dofs) and dofs[-1] > 2 * dofs[0]
    for coarse, fine in zip(estimates, estimates[1:]):
        assert fine.mem_mb >= coarse.mem_mb and fine.runtime_min >= coarse.runtime_min
    assert estimates[-1].mem_mb > estimates[0].mem_mb
    assert estimates[-1].runtime_min > estimates[0].runtime_min


def test_continuum_model_needs_more_than_the_sem(model):
    axi, sem = estimate_resources(model, "fem_axi"), estimate_resources(model, "sem")
    assert axi.mem_mb > sem.mem_mb and axi.runtime_min > sem.runtime_min


def test_more_steps_and_elements_cost_more(model):
    base = estimate_resources(with_numerics(model, "sem_paper", steps_per_contact=20000), "sem_paper")
    more = estimate_resources(with_numerics(model, "sem_paper", steps_per_contact=2_000_000), "sem_paper")
    assert more.mem_mb > base.mem_mb and more.runtime_min > base.runtime_min
    few = estimate_resources(with_numerics(model, "fem1d", elements=50, steps_per_contact=2000), "fem1d")
    many = estimate_resources(with_numerics(model, "fem1d", elements=50_000, steps_per_contact=20_000), "fem1d")
    assert many.mem_mb > few.mem_mb and many.runtime_min > few.runtime_min


def test_a_contact_over_many_round_trips_costs_more_per_step_only_off_the_grid(project):
    """A fixed dt_s that is not commensurate with the wave round trip sums a history term per
    round trip: the longer contact costs more at the same step count. The step that
    steps_per_contact gives is made commensurate, and costs the same at every round trip."""
    stress = project[1].cases
    short, long = stress["short_rod"], stress["seconds_contact"]

    def runtime(case, **numerics):
        return estimate_resources(with_numerics(case, "sem_paper", **numerics), "sem_paper").runtime_min

    def off_grid(case):  # the case's 20000th of its Hertz time, nudged off the round trip
        return {
            "dt_s": ImpactProblem.from_case(case).rigid_contact.contact_time_s / 20000 * (1 + 1e-6),
            "steps_per_contact": None,
        }

    assert runtime(long, **off_grid(long)) > runtime(short, **off_grid(short))
    on_grid = {"dt_s": None, "steps_per_contact": 20000}
    assert runtime(long, **on_grid) == runtime(short, **on_grid)


def test_floors_and_attempts(model):
    small = estimate_resources(model, "sem")
    assert small.mem_mb >= MIN_MEM_MB and small.runtime_min >= MIN_RUNTIME_MIN and small.threads == 1
    third = small.for_attempt(3)
    assert (third.mem_mb, third.runtime_min, third.threads) == (3 * small.mem_mb, 3 * small.runtime_min, 1)
    assert small.for_attempt(1) == small


def test_timed_runs_ask_for_the_repeats(model):
    case = with_numerics(model, "fem_axi", **COARSE_AXI)
    once = estimate_resources(case, "fem_axi")
    timed = estimate_resources(case, "fem_axi", timing={"min_repeats": 30, "min_total_s": 1.0, "max_total_s": 10_000.0})
    assert timed.runtime_min > once.runtime_min and timed.mem_mb == once.mem_mb


def test_a_timed_run_costs_its_repeats_upper_side_and_typically():
    """timed_cost: the upper-side time repeats the upper-side solve as Timing would, the typical
    time repeats the typical solve (a short solve repeated more often to reach min_total_s);
    memory and steps are the solve's; no timing is the cost itself."""
    cost = Cost(time_step_s=1e-8, steps=1000.0, solve_s=1.0, mem_mib=40.0, typical_share=0.1)
    assert timed_cost(cost, None) is cost
    timing = {"min_repeats": 3, "min_total_s": 0.2, "max_total_s": 1.5}
    timed = timed_cost(cost, timing)
    # upper: max(3 x 1.0, 0.2 + 1.0) = 3.0, capped at 1.5 + 1.0; typical: max(3 x 0.1, 0.2 + 0.1) = 0.3
    assert timed.solve_s == pytest.approx(2.5, rel=1e-12)
    assert timed.typical_s == pytest.approx(0.3, rel=1e-12)
    assert (timed.mem_mib, timed.steps, timed.time_step_s) == (cost.mem_mib, cost.steps, cost.time_step_s)
    short = timed_cost(Cost(1e-8, 10.0, 0.5, 1.0, typical_share=0.02), timing)  # a 10 ms solve: 21 repeats
    assert short.typical_s == pytest.approx(0.21, rel=1e-12)
    with pytest.raises(ValueError, match="^timing"):
        timed_cost(cost, {"min_repeats": 0})


def test_a_sequence_sums_times_and_keeps_the_largest_memory(model):
    runs = [(model, "sem", 1), (model, "fem_axi", 3)]
    total = estimate_sequence(runs)
    assert total.mem_mb == estimate_resources(model, "fem_axi").mem_mb
    assert total.runtime_min >= estimate_resources(model, "fem_axi").runtime_min
    bench_sem = estimate_sequence(sem_bench_runs(model))
    bench_fem = estimate_sequence(fem_bench_runs(model, [model]))
    assert bench_sem.runtime_min > estimate_resources(model, "sem").runtime_min
    assert bench_fem.mem_mb >= estimate_resources(model, "fem_axi").mem_mb


def test_a_batch_that_indents_its_points_asks_for_the_indentations(shipped_project, shipped_config):
    """A calibrated sweep's batch computes each point's curve: its request adds each
    indentation's cost (the continuum's meshes, one solve per candidate column) to the SEM's."""
    sweep = shipped_project.sweeps["ball_sweep_sensor-r10_l30_sensor_cal"]
    settings = shipped_config["numerics"]["fem_axi"]
    points = [sweep_point_case(sweep, point, f"p{k}") for k, point in enumerate(sweep_points(sweep["sweep"]))]
    runs = [(point, "sem", 1) for point in points]
    indentations = [fem_axi_indentation_cost(point, settings) for point in points]
    plain, indenting = estimate_sequence(runs), estimate_sequence(runs, extra=indentations)
    seconds = sum(cost.solve_s for cost in indentations)
    assert indenting.runtime_min >= plain.runtime_min + math.floor(SAFETY * seconds / 60.0)
    assert indenting.mem_mb >= max(cost.mem_mib for cost in indentations) * SAFETY * 2**20 / 1e6
    assert all(cost.solve_s > 2.5 for cost in indentations)  # the heaviest row's indentation took 2.5 s


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda case: estimate_resources(case, "fem2d"), "method"),
        (lambda case: estimate_resources(case, 3), "method"),
        (lambda case: estimate_resources([case], "sem"), "case"),
        (lambda case: estimate_resources({**case, "numerics": {}}, "sem"), "case"),
        (lambda case: estimate_resources({k: v for k, v in case.items() if k != "rod"}, "sem"), "case"),
        (lambda case: estimate_resources(case, "sem", timing={"min_repeats": 0}), "timing"),
        (lambda case: estimate_sequence([]), "runs"),
        (lambda case: estimate_sequence([(case, "sem", 0)]), "runs"),
        (lambda case: estimate_resources(case, "sem").for_attempt(0), "attempt"),
        (lambda case: JobResources(threads=1, mem_mb=0, runtime_min=1), "mem_mb"),
        (lambda case: JobResources(threads=1.5, mem_mb=1, runtime_min=1), "threads"),
    ],
)
def test_bad_input_is_refused_by_name(model, call, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        call(model)


def test_presentation_is_constant_and_small():
    assert PRESENTATION.threads == 1 and PRESENTATION.mem_mb <= 2000 and PRESENTATION.runtime_min <= 10


def test_resources_are_not_solver_code():
    """The solvers' rerun trigger lists their sources: a new calibration reruns no solver."""
    solver = {Path(f).name for f in module_sources(SRC, ["rodimpact.jobs.runner"])}
    assert "resources.py" not in solver
    assert "resources.py" in {Path(f).name for f in module_sources(SRC, ["rodimpact.tools.bench"])}


def test_dof_bound_covers_the_meshes(model):
    """The closed-form DOF bound against the meshes fem_axi builds (coarse, so quick)."""
    from rodimpact.solvers.fem_axi.aximodel import build_model as _build
    from rodimpact.solvers.fem_axi.options import FEMAxiOptions
    from rodimpact.solvers.fem_axi.problem import AxiImpact

    for case in (
        with_numerics(model, "fem_axi", **COARSE_AXI),
        with_numerics(model, "fem_axi", elements_across=6, element="P1"),
    ):
        model = _build(AxiImpact.from_case(case), FEMAxiOptions.from_settings(case["numerics"]["fem_axi"]))
        rod, imp = model.rod, model.impactor
        built = rod.basis.N + imp.basis.N
        assert built <= fem_axi_dofs(case) <= 3 * built


_MEASURE = r"""
import json, resource, sys, time
from rodimpact.jobs.runner import run_case
case, method = json.loads(sys.argv[1]), sys.argv[2]
started = time.perf_counter()
result = run_case(case, method)
# VmHWM is this process's own peak; ru_maxrss keeps the forking parent's across exec on Linux
try:
    peak_kib = next(int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("VmHWM:"))
except OSError:
    peak_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"wall_s": time.perf_counter() - started, "success": result.success,
                  "peak_MiB": peak_kib / 1024}))
"""


@pytest.mark.parametrize("method, settings", [("sem", {}), ("fem_axi", COARSE_AXI)])
def test_estimate_covers_a_measured_run(model, method, settings):
    """A real run in a fresh process (the job's solver process): the estimate asks for at
    least SAFETY times its peak memory and its wall time."""
    case = with_numerics(model, method, **settings)
    done = subprocess.run(
        [sys.executable, "-c", _MEASURE, json.dumps(case), method],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    measured = json.loads(done.stdout.splitlines()[-1])
    assert measured["success"]
    estimate = estimate_resources(case, method)
    assert estimate.mem_mb * 1e6 / 2**20 >= SAFETY * measured["peak_MiB"]
    assert estimate.runtime_min * 60.0 >= SAFETY * measured["wall_s"]


def test_bench_margins_table():
    import pandas as pd

    frame = pd.DataFrame(
        [
            {
                "case": "model",
                "method": "fem_axi",
                "n_dofs": 100,
                "n_dofs_estimate": 150,
                "wall_time_s": 10.0,
                "runtime_estimate_s": 60.0,
                "runtime_margin": 6.0,
                "peak_memory_MiB": 200.0,
                "mem_estimate_MiB": 800.0,
                "mem_margin": 4.0,
            },
            {"case": "model", "method": "fem1d"},
        ]
    )
    assert list(resource_margins(frame)["case"]) == ["model"]
    with pytest.raises(ValueError, match="^frame"):
        resource_margins(frame.drop(columns=["mem_estimate_MiB"]))


def test_each_method_declares_a_typical_share_of_its_upper_side_time(model):
    """The cost models are upper-side; each declares the share of its time a solve typically
    takes (below one), and the central estimate is that share of the model's time."""
    for method in model["methods"]:
        cost = run_cost(model, method)
        assert 0.0 < cost.typical_share < 1.0, method
        assert cost.typical_s == pytest.approx(cost.typical_share * cost.solve_s, rel=1e-15)
    paper = run_cost(model, "sem_paper").typical_share
    assert paper != run_cost(model, "sem").typical_share  # the two SEM schemes, measured apart


def test_the_cost_share_tool_measures_what_the_stored_runs_took(model, tmp_path):
    """cost_share: measured over modelled time of every stored run (a run file, and each run of a
    file of runs), per method, next to the share the method declares."""
    import numpy as np

    from rodimpact.jobs.runner import run_config
    from rodimpact.storage.runs import write_run, write_runs
    from rodimpact.tools.cost_share import cost_shares

    solve_s = run_cost(model, "sem").solve_s
    run = {
        "config": run_config(model, "sem"),
        "method": "sem",
        "series": {"time": (np.zeros(1), "s", "time")},
        "summary": {"contact_time_s": 1e-4, "peak_force_N": np.ones(1), "peak_time_s": np.ones(1),
                    "rebound_velocity_m_s": 0.0, "energy_error": 0.0},
        "code_version": "0+gabc",
    }  # fmt: skip
    write_run(tmp_path / "results/runs/model/sem.h5", **run, wall_time_s=0.1 * solve_s)
    with write_runs(tmp_path / "results/sweeps/s/sem/part0.h5") as writer:
        writer.add("a", **run, wall_time_s=0.2 * solve_s)
        writer.add("b", **run, wall_time_s=0.6 * solve_s)
    (share,) = cost_shares(tmp_path)
    assert (share.method, share.runs) == ("sem", 3)
    assert share.median == pytest.approx(0.2, rel=1e-12) and share.max == pytest.approx(0.6, rel=1e-12)
    assert share.typical_share == run_cost(model, "sem").typical_share
