"""Snakemake adapter: one reading of a set with variants (for the paper's set: Table 2 for one reading of the rod)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_readings_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    make_readings_table(
        snakemake.params.runs,
        params.variant,
        title=params.title,
        reference=params.reference,
        csv=out.csv,
        md=out.md,
        html=out.html,
        tex=out.tex,
        provenance=out.provenance,
    )
