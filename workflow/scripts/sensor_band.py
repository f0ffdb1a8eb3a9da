"""Snakemake adapter: the sensor stack's band (and the fit's grid) of one case by the calibrated SEM."""

from rodimpact.jobs.logs import script_logging
from rodimpact.jobs.sensor_band import sensor_band_to_file

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    params = snakemake.params  # noqa: F821
    sensor_band_to_file(params.case, params.variant, snakemake.output.h5, params.numerics,  # noqa: F821
                        grid=params.grid, band=params.band, curve_file=snakemake.input.curve)  # noqa: F821
