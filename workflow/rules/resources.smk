# Resources of the jobs (threads, mem_mb in MB, runtime in minutes), and the case each solver
# job runs (its params and its resources call the same function). Solver jobs are estimated
# from that case by rodimpact.jobs.resources (twice the cost model, calibrated on measured runs),
# tables and figures get constants. A retry (--retries, the slurm profile) gets `attempt`
# times the memory and the run time.
import importlib

from rodimpact.tools.bench_plan import fem_bench_runs, sem_bench_runs, sem_scaling_runs
from rodimpact.jobs.resources import PRESENTATION, estimate_resources, estimate_sequence


def level_runs(method):
    """Input function: the levels of ``method``'s work-precision sweep on the case of the
    wildcard, by output name (level0, level1, ...)."""

    @per_job
    def runs(wildcards):
        count = len(WORK_PRECISION["methods"][method]["levels"])
        return {f"level{k}": {"case": sweep_case(wildcards.case, method, k), "method": method, "level": k,
                              "study": {"name": "work_precision", "level": k, "overrides": sweep_level(method, k)}}
                for k in range(count)}

    return runs


def sweep_batch_runs(case_id, names):
    """Input function: the runs of the points ``names`` of a sweep by the method of the
    wildcard, by output name (p0, p1, ...); refuses a method the sweep does not run."""

    @per_job
    def runs(wildcards):
        case = PROJECT.sweeps[case_id]
        if wildcards.method not in case["sweep"]["methods"]:
            refuse(f"sweep {case_id!r} does not run {wildcards.method!r}; its methods: "
                   f"{', '.join(case['sweep']['methods'])}")
        runs = {}
        for k, name in enumerate(names):
            point = sweep_point_case(case, SWEEP_POINTS[case_id][name], name)
            runs[f"p{k}"] = {"case": point, "method": wildcards.method,
                             "study": {"name": "sweep", "sweep": case_id, "point": name}}
            builder = curve_rule_of(point)
            if builder is not None:  # no rule computes a point's curve, its batch does
                runs[f"p{k}"]["curve"] = {"rule": builder, "settings": CURVE_SETTINGS[builder]}
        return runs

    return runs


@per_job
def reference_case_of(wildcards):
    """The sem reference case of a stress case (rule solve_stress_reference)."""
    return reference_case(PROJECT.cases[wildcards.case], config["numerics"],
                          config["stability"]["reference_tolerance"])


@per_job
def map_row_runs(wildcards):
    """The runs of one row of the stability map (rule solve_map_row), by output name (z0, z1, ...)."""
    base, method = PROJECT.cases[MAP["base_case"]], map_method_of(wildcards)
    return {f"z{j}": {"case": map_point_case(base, MAP, f"m{wildcards.row}_z{j}", wildcards.map_method,
                                             config["numerics"]), "method": method}
            for j in range(len(MAP["impedance_kg_s"]))}


def map_method_of(wildcards):
    """The solver a map run uses: its method, sem for the reference."""
    return "sem" if wildcards.map_method == "reference" else wildcards.map_method


def _resources(estimate):
    """``resources:`` entries from ``estimate(wildcards) -> JobResources``, scaled by the attempt."""
    estimate = per_job(estimate)
    return {"mem_mb": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).mem_mb,
            "runtime": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).runtime_min}


def solver_resources(case, method=None, timing=None):
    """Resources of a solver rule: ``case(wildcards)`` is the case its params run, ``method(wildcards)``
    the method (default: the wildcard), ``timing`` the study's timing when the solve is repeated."""
    return _resources(lambda w: PLAN.remember((case(w), method(w) if method else w.method, timing), _estimate))


def _estimate(case, method, timing):
    return estimate_resources(case, method, timing=timing)


def batch_resources(runs, timing=None):
    """Resources of a batch rule: ``runs(wildcards)`` maps its outputs to their runs (``case``,
    ``method``), solved one after another; ``timing`` when each is timed."""
    return _resources(lambda w: PLAN.remember(([(r["case"], r["method"], 1) for r in runs(w).values()], timing,
                                               [(r["case"], r["curve"]) for r in runs(w).values() if "curve" in r]),
                                              _estimate_batch))


def _estimate_batch(runs, timing, curves):
    costs = {name: getattr(importlib.import_module(path.partition(":")[0]), path.partition(":")[2])
             for name, path in CURVE_COSTS.items() if any(curve["rule"] == name for _, curve in curves)}
    return estimate_sequence(runs, timing=timing, extra=[costs[curve["rule"]](case, curve["settings"])
                                                         for case, curve in curves])


def bench_resources(runs):
    """Resources of a benchmark rule: ``runs()`` lists its solves (case, method, repeats)."""
    return _resources(lambda w: estimate_sequence(runs()))


PRESENTATION_RESOURCES = _resources(lambda w: PRESENTATION)
