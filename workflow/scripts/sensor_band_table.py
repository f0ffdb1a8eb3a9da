"""Snakemake adapter: the sensor stack's bands of every case of the band readings."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.sensor_artifacts import make_sensor_band_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_sensor_band_table(
        snakemake.params.bands,
        snakemake.input.cases,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
    )
