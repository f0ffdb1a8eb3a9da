# Resources of the jobs (threads, mem_mb in MB, runtime in minutes). A solver job's are its part's
# (common_batches.smk, part_resources), a benchmark's its solves' (rodimpact.jobs.resources: twice
# the cost model, calibrated on measured runs); tables and figures get constants. A retry
# (--retries, the slurm profile) gets `attempt` times the memory and the run time.
from rodimpact.jobs.resources import PRESENTATION, estimate_sequence
from rodimpact.tools.bench_plan import fem_bench_runs, sem_bench_runs, sem_scaling_runs


def _resources(estimate):
    """``resources:`` entries from ``estimate(wildcards) -> JobResources``, scaled by the attempt."""
    estimate = per_job(estimate)
    return {
        "mem_mb": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).mem_mb,
        "runtime": lambda wildcards, attempt: estimate(wildcards).for_attempt(attempt).runtime_min,
    }


def bench_resources(runs):
    """Resources of a benchmark rule: ``runs()`` lists its solves (case, method, repeats)."""
    return _resources(lambda w: estimate_sequence(runs()))


PRESENTATION_RESOURCES = _resources(lambda w: PRESENTATION)
