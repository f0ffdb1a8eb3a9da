"""Snakemake adapter: the continuum's indentation curves against the analytic contact laws."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_film_indentation_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_film_indentation_table(
        snakemake.params.curves,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
    )
