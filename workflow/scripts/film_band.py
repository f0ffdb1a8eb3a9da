"""Snakemake adapter: the film's prediction band for one Table 2 reading (``study`` film_band_axes:
with each constant's range)."""

from rodimpact.jobs.band import band_to_file
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    band_to_file(snakemake.params.cases, snakemake.params.variant, snakemake.output.h5, axes=snakemake.params.axes)
