"""Snakemake adapter: one rod's readings without and with the sensor film, side by side."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_film_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_film_table(
        snakemake.params.runs,
        snakemake.params.variants,
        snakemake.input.band,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
        sensor_bands=snakemake.params.sensor_bands,
    )
