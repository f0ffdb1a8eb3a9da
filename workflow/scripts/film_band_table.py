"""Snakemake adapter: the film's prediction band of every case of every film reading."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_film_band_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_film_band_table(
        snakemake.input.bands,
        snakemake.input.cases,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
    )
