"""Snakemake adapter: the continuum's static indentation of one case, as its contact-law curve."""

from rodimpact.jobs.indentation import indentation_to_file
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    indentation_to_file(snakemake.params.case, snakemake.output.h5, snakemake.params.numerics)  # noqa: F821
