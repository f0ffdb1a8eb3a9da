"""Snakemake adapter: write the case file of one group of runs, or of one sweep case (the chain's first stage)."""

from rodimpact.jobs.cases import write_case_file
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    write_case_file(snakemake.params.name, snakemake.params.cases, snakemake.output.yaml)
