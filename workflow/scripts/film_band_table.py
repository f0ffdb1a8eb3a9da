"""Snakemake adapter: a table of the film's prediction bands of every case of every film reading
(``study`` film_band: the bands; film_band_axes: each constant's range)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_film_axes_table, make_film_band_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make = {"film_band": make_film_band_table, "film_band_axes": make_film_axes_table}[snakemake.params.study]
    make(snakemake.input.bands, snakemake.input.cases, csv=out.csv, md=out.md, html=out.html, provenance=out.provenance)
