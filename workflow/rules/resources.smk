# Resources of the jobs (threads, mem_mb in MB, runtime in minutes), and the case each solver
# job runs (its params and its resources call the same function). Solver jobs are estimated
# from that case by rodimpact.jobs.resources (twice the cost model, calibrated on measured runs),
# tables and figures get constants. A retry (--retries, the slurm profile) gets `attempt`
# times the memory and the run time.
import importlib

from rodimpact.config.project import ConfigFile
from rodimpact.jobs.parts import TooManyParts, cut_runs
from rodimpact.jobs.resources import PRESENTATION, estimate_sequence, run_cost
from rodimpact.tools.bench_plan import fem_bench_runs, sem_bench_runs, sem_scaling_runs


@per_job
def level_runs(wildcards):
    """The levels of the method of the wildcard in the work-precision sweep on the case of the
    wildcard, by file name (level0, level1, ...); refuses a method the study does not sweep there."""
    levels = WORK_PRECISION.get("methods", {}).get(wildcards.method, {}).get("levels", [])
    runs = {
        f"level{k}": {
            "case": sweep_case(wildcards.case, wildcards.method, k),
            "method": wildcards.method,
            "level": k,
            "study": {"name": "work_precision", "level": k, "overrides": sweep_level(wildcards.method, k)},
        }
        for k in range(len(levels))
    }
    return runs or refuse(f"the work-precision study does not sweep {wildcards.method!r}")


@functools.cache
def sweep_runs_of(case_id, method):
    """Every point of the sweep ``case_id`` by ``method``, by its name (in the grid's order): its
    run (the point's case, the method, the study, and the curve its batch computes when its law
    needs one); refuses a sweep or method the configuration does not define."""
    if case_id not in PROJECT.sweeps:
        refuse(f"unknown sweep {case_id!r}; known: {', '.join(PROJECT.sweeps)}")
    case = PROJECT.sweeps[case_id]
    if method not in case["sweep"]["methods"]:
        refuse(f"sweep {case_id!r} does not run {method!r}; its methods: {', '.join(case['sweep']['methods'])}")
    runs = {}
    for name, values in SWEEP_POINTS[case_id].items():
        point = sweep_point_case(case, values, name)
        runs[name] = {"case": point, "method": method, "study": {"name": "sweep", "sweep": case_id, "point": name}}
        builder = curve_rule_of(point)
        if builder is not None:  # no rule computes a point's curve, its batch does
            runs[name]["curve"] = {"rule": builder, "settings": CURVE_SETTINGS[builder]}
    return runs


@functools.cache
def sweep_parts_of(case_id, method):
    """The parts of the sweep ``case_id`` by ``method`` (rodimpact.jobs.parts.cut_runs of its
    points' costs at batch.target_s: names, typical cost, resources), each point costed once.
    Refuses a target that cuts the sweep into too many jobs, in one line."""
    runs = sweep_runs_of(case_id, method)
    costs = {
        name: [run_cost(run["case"], method), *([curve_cost(run)] if "curve" in run else [])]
        for name, run in runs.items()
    }
    try:
        return cut_runs(costs, config["batch"]["target_s"])
    except TooManyParts as error:
        where = ConfigFile.under(CONFIG_FILE, Path(WORKDIR))
        refuse(
            f"invalid configuration: {where.error(f'sweep by {method}: {error}', case=case_id, field='batch.target_s')}"
        )


def curve_cost(run):
    """The cost of the curve a run's batch computes for its law (CURVE_COSTS; its module imported
    only when a batch needs it)."""
    dotted, _, function = CURVE_COSTS[run["curve"]["rule"]].partition(":")
    return getattr(importlib.import_module(dotted), function)(run["case"], run["curve"]["settings"])


def sweep_part(wildcards):
    """The part of the wildcards (case, method, part) of a sweep; refuses a part it does not have."""
    parts = sweep_parts_of(wildcards.case, wildcards.method)
    index = int(wildcards.part)
    if index >= len(parts):
        held = "one part: part0" if len(parts) == 1 else f"{len(parts)} parts: part0 to part{len(parts) - 1}"
        refuse(
            f"sweep {wildcards.case!r} by {wildcards.method} has {held} (batch.target_s = {config['batch']['target_s']:g} s)"
        )
    return parts[index]


def sweep_part_runs(wildcards):
    """The runs of one part of a sweep, by point name (rule solve_sweep's params)."""
    runs = sweep_runs_of(wildcards.case, wildcards.method)
    return {name: runs[name] for name in sweep_part(wildcards).names}


def sweep_part_case_file(wildcards):
    """The input of solve_sweep, the sweep's case file, once the part is known to exist
    (an input function may refuse; its resources may not)."""
    sweep_part(wildcards)
    return f"results/cases/{wildcards.case}.yaml"


@per_job
def stress_runs(wildcards):
    """One method on every case of a stress set that lists it, or (``reference``) the sem reference
    of every case at the study's tolerance, by file name (the case); a run records its case file."""
    cases = PROJECT.cases_in(wildcards.set)
    if wildcards.stress_method == "reference":
        tolerance = config["stability"]["reference_tolerance"]
        return {
            c["id"]: {
                "case": reference_case(c, config["numerics"], tolerance),
                "method": "sem",
                "case_file": case_file_of(c["id"]),
            }
            for c in cases
        }
    runs = {
        c["id"]: {"case": c, "method": wildcards.stress_method, "case_file": case_file_of(c["id"])}
        for c in cases
        if wildcards.stress_method in c["methods"]
    }
    if not runs:
        refuse(f"no case of the stress set {wildcards.set!r} runs {wildcards.stress_method!r}")
    return runs


def stress_method_of(wildcards):
    """The solver a stress batch uses: its method, sem for the reference."""
    return "sem" if wildcards.stress_method == "reference" else wildcards.stress_method


@per_job
def map_runs(wildcards):
    """Every point of the stability map (each impactor mass at every rod impedance) by one method
    or its sem reference, by file name (m{i}_z{j})."""
    base, method = PROJECT.cases[MAP["base_case"]], map_method_of(wildcards)
    return {
        name: {"case": map_point_case(base, MAP, name, wildcards.map_method, config["numerics"]), "method": method}
        for name in MAP_POINTS
    }


def map_method_of(wildcards):
    """The solver a map run uses: its method, sem for the reference."""
    return "sem" if wildcards.map_method == "reference" else wildcards.map_method


def _resources(estimate):
    """``resources:`` entries from ``estimate(wildcards) -> JobResources``, scaled by the attempt."""
    estimate = per_job(estimate)
    return {
        "mem_mb": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).mem_mb,
        "runtime": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).runtime_min,
    }


def batch_resources(runs, timing=None):
    """Resources of a batch rule: ``runs(wildcards)`` maps its outputs to their runs (``case``,
    ``method``), solved one after another; ``timing`` when each is timed."""
    return _resources(
        lambda w: estimate_sequence(
            [(r["case"], r["method"], 1) for r in runs(w).values()],
            timing=timing,
            extra=[curve_cost(r) for r in runs(w).values() if "curve" in r],
        )
    )


def sweep_part_resources():
    """The resources of solve_sweep, its part's (sweep_parts_of), scaled by the attempt."""
    return {
        "mem_mb": lambda wildcards, attempt: sweep_part(wildcards).resources.for_attempt(attempt).mem_mb,
        "runtime": lambda wildcards, attempt: sweep_part(wildcards).resources.for_attempt(attempt).runtime_min,
    }


def bench_resources(runs):
    """Resources of a benchmark rule: ``runs()`` lists its solves (case, method, repeats)."""
    return _resources(lambda w: estimate_sequence(runs()))


PRESENTATION_RESOURCES = _resources(lambda w: PRESENTATION)
