"""Snakemake adapter: Fig. 2 (contact force against time, case 'model')."""

from rodimpact.present.artifacts import make_fig2
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_fig2(snakemake.params.runs, pdf=out.pdf, png=out.png, provenance=out.provenance)  # noqa: F821
