# Resources of the jobs (threads, mem_mb in MB, runtime in minutes), and the case each solver
# job runs (its params and its resources call the same function). Solver jobs are estimated
# from that case by rodimpact.workflow.resources (twice the cost model, calibrated on measured runs),
# tables and figures get constants. A retry (--retries, the slurm profile) gets `attempt`
# times the memory and the run time.
from rodimpact.workflow.bench_plan import fem_bench_runs, sem_bench_runs
from rodimpact.workflow.resources import PRESENTATION, estimate_resources, estimate_sequence


def level_case_of(wildcards):
    """The case of one work-precision level (rule solve_level)."""
    return sweep_case(wildcards.case, wildcards.method, int(wildcards.level))


def reference_case_of(wildcards):
    """The sem reference case of a stress case (rule solve_stress_reference)."""
    return reference_case(PROJECT.cases[wildcards.case], config["numerics"],
                          config["stability"]["reference_tolerance"])


def map_case_of(wildcards):
    """The case of one stability-map point and method (rule solve_map_point)."""
    return map_point_case(PROJECT.cases[MAP["base_case"]], MAP, wildcards.point, wildcards.map_method,
                          config["numerics"])


def map_method_of(wildcards):
    """The solver a map run uses: its method, sem for the reference."""
    return "sem" if wildcards.map_method == "reference" else wildcards.map_method


def _resources(estimate):
    """``resources:`` entries from ``estimate(wildcards) -> JobResources``, scaled by the attempt."""
    return {"mem_mb": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).mem_mb,
            "runtime": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).runtime_min}


def solver_resources(case, method=None, timing=None):
    """Resources of a solver rule: ``case(wildcards)`` is the case its params run, ``method(wildcards)``
    the method (default: the wildcard), ``timing`` the study's timing when the solve is repeated."""
    return _resources(lambda w: estimate_resources(case(w), method(w) if method else w.method, timing=timing))


def bench_resources(runs):
    """Resources of a benchmark rule: ``runs()`` lists its solves (case, method, repeats)."""
    return _resources(lambda w: estimate_sequence(runs()))


PRESENTATION_RESOURCES = _resources(lambda w: PRESENTATION)
