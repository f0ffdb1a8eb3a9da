"""Snakemake adapter: one part of a batch of runs (a group's cases, work-precision levels, a stress
set's cases, the stability map's points or a sweep's points, by one method), every run into the
one file of runs that is the rule's output."""

from rodimpact.jobs.batch import run_batch_file
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    params = snakemake.params
    run_batch_file(  # each run names its case file (run["case_file"], the rule's inputs)
        params.runs,
        snakemake.output.runs,
        keep_failed=params.keep_failed,
        timing=params.timing,
    )
