# Resources of the jobs (threads, mem_mb in MB, runtime in minutes), and the case each solver
# job runs (its params and its resources call the same function). Solver jobs are estimated
# from that case by rodimpact.jobs.resources (twice the cost model, calibrated on measured runs),
# tables and figures get constants. A retry (--retries, the slurm profile) gets `attempt`
# times the memory and the run time.
import importlib

from rodimpact.tools.bench_plan import fem_bench_runs, sem_bench_runs, sem_scaling_runs
from rodimpact.jobs.resources import PRESENTATION, estimate_sequence


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


@per_job
def sweep_batch_runs(wildcards):
    """Every point of the sweep of the wildcard's case by the method of the wildcard, by file name
    (the point's name); refuses a method the sweep does not run."""
    case_id = wildcards.case
    case = PROJECT.sweeps[case_id]
    if wildcards.method not in case["sweep"]["methods"]:
        refuse(
            f"sweep {case_id!r} does not run {wildcards.method!r}; its methods: "
            f"{', '.join(case['sweep']['methods'])}"
        )
    runs = {}
    for name, values in SWEEP_POINTS[case_id].items():
        point = sweep_point_case(case, values, name)
        runs[name] = {
            "case": point,
            "method": wildcards.method,
            "study": {"name": "sweep", "sweep": case_id, "point": name},
        }
        builder = curve_rule_of(point)
        if builder is not None:  # no rule computes a point's curve, its batch does
            runs[name]["curve"] = {"rule": builder, "settings": CURVE_SETTINGS[builder]}
    return runs


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
        lambda w: _estimate_batch(
            [(r["case"], r["method"], 1) for r in runs(w).values()],
            timing,
            [(r["case"], r["curve"]) for r in runs(w).values() if "curve" in r],
        )
    )


def _estimate_batch(runs, timing, curves):
    costs = {
        name: getattr(importlib.import_module(path.partition(":")[0]), path.partition(":")[2])
        for name, path in CURVE_COSTS.items()
        if any(curve["rule"] == name for _, curve in curves)
    }
    return estimate_sequence(
        runs, timing=timing, extra=[costs[curve["rule"]](case, curve["settings"]) for case, curve in curves]
    )


def bench_resources(runs):
    """Resources of a benchmark rule: ``runs()`` lists its solves (case, method, repeats)."""
    return _resources(lambda w: estimate_sequence(runs()))


PRESENTATION_RESOURCES = _resources(lambda w: PRESENTATION)
