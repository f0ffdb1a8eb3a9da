"""Snakemake adapter: a set's measured strain or velocity records against its methods' signals."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.compare_artifacts import make_signal_figure

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    make_signal_figure(params.runs, params.key, params.title, pdf=out.pdf, png=out.png, provenance=out.provenance)
