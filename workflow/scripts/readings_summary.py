"""Snakemake adapter: the per-variant error summary of Table 2."""

from rodimpact.present.artifacts import make_table2_variants
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_table2_variants(snakemake.input.runs, snakemake.params.variants,  # noqa: F821
                         csv=out.csv, md=out.md, html=out.html, provenance=out.provenance)
