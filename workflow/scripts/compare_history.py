"""Snakemake adapter: one case's measured force history against its methods' forces."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.compare_artifacts import make_history_figure

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_history_figure(snakemake.params.runs, pdf=out.pdf, png=out.png, provenance=out.provenance)
