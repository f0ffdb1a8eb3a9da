"""Snakemake adapter: one part of a sweep (its points by one method), every run into the one file
of runs that is the rule's output."""

from rodimpact.jobs.batch import run_batch_file
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    run_batch_file(
        snakemake.params.runs,
        snakemake.output.runs,
        case_file=snakemake.input.case,
        keep_failed=snakemake.params.keep_failed,
    )
