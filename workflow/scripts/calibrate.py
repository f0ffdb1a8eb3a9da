"""Snakemake adapter: one set's declared constants fitted to its measurements, with leave-one-out."""

from rodimpact.jobs.calibrate import run_calibration
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    params = snakemake.params
    run_calibration(params.set_name, params.cases, params.block, params.numerics, snakemake.output.h5, params.curves)
