"""Snakemake adapter: one run of the stability study; a failure is written as data."""

from rodimpact.jobs.logs import script_logging
from rodimpact.jobs.runner import run_to_file

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    params = snakemake.params  # noqa: F821
    run_to_file(params.case, params.method, snakemake.output.h5, keep_failed=True,  # noqa: F821
                case_file=snakemake.input.case)  # noqa: F821
