"""Snakemake adapter: the per-reading error summary of a set with variants."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_readings_summary

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_readings_summary(
        snakemake.params.runs,
        snakemake.params.variants,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
    )
