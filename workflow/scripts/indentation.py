"""Snakemake adapter: the continuum's static indentation of each calibrated case of one group, as
its contact-law curve (one file per case in the rule's output directory)."""

from rodimpact.jobs.indentation import indentations_into
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    indentations_into(snakemake.params.cases, snakemake.output.curves, snakemake.params.numerics)
