"""Snakemake adapter: the table of every sweep point of one case set."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_sweep_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_sweep_table(
        snakemake.params.runs,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
    )
