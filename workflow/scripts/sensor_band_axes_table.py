"""Snakemake adapter: each constant of the sensor stack along its range by the continuum (make sensor-axes)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.sensor_artifacts import make_sensor_axes_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_sensor_axes_table(
        snakemake.params.bands,
        snakemake.input.cases,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
    )
