"""Snakemake adapter: Fig. 2 (contact force against time, case 'model')."""

from rodimpact.artifacts import make_fig2
from rodimpact.logs import script_logging

with script_logging(snakemake.log[0]):  # noqa: F821 (injected by snakemake)
    make_fig2(snakemake.input.runs, pdf=snakemake.output.pdf, png=snakemake.output.png)  # noqa: F821
