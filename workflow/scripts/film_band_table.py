"""Snakemake adapter: a table of the film's prediction bands of every case of every film reading
(``study`` film_band: the bands; film_band_axes: each constant's range)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_axes_table, make_film_band_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    files = {"csv": out.csv, "md": out.md, "html": out.html, "provenance": out.provenance}
    if snakemake.params.study == "film_band_axes":
        make_axes_table(snakemake.input.bands, snakemake.input.cases, kind="film", **files)
    else:
        make_film_band_table(snakemake.input.bands, snakemake.input.cases, **files)
