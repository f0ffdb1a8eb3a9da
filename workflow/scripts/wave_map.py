"""Snakemake adapter: the axial strain over the rod against time, for one case."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.wave_figures import make_wave_map

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_wave_map(snakemake.params.runs, pdf=out.pdf, png=out.png, provenance=out.provenance)
