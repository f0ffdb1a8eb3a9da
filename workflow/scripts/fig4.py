"""Snakemake adapter: Fig. 4 (displacement of a cross-section of the rod, case 'model')."""

from rodimpact.present.artifacts import make_fig4
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    make_fig4(snakemake.params.runs, snakemake.params.fraction,  # noqa: F821
              pdf=snakemake.output.pdf, png=snakemake.output.png,  # noqa: F821
              provenance=snakemake.output.provenance)  # noqa: F821
