"""Snakemake adapter: a batch of runs of one case file (sweep points, a stability-map row,
work-precision levels), each written to its own HDF5 file."""

from rodimpact.jobs.batch import run_batch
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    params = snakemake.params  # noqa: F821
    run_batch(params.runs, dict(snakemake.output.items()), case_file=snakemake.input.case,  # noqa: F821
              keep_failed=params.keep_failed, timing=params.timing)
