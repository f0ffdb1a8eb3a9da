"""Snakemake adapter: the table of every sweep point of one case set."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_sweep_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_sweep_table(snakemake.params.runs, csv=out.csv, md=out.md, html=out.html,  # noqa: F821
                     provenance=out.provenance)
