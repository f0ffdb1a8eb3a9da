"""Snakemake adapter: the sensor stack's band of each case of one reading by the calibrated SEM
(one file per case in the rule's output directory)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.jobs.sensor_band import sensor_bands_into

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    params = snakemake.params
    sensor_bands_into(
        params.cases,
        params.variant,
        snakemake.output.bands,
        params.numerics,
        curve_files=params.curves,
        axes=params.axes,
    )
