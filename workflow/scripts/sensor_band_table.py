"""Snakemake adapter: a table of the sensor stack's bands of every case of the band readings (``study``
sensor_band: the bands; sensor_band_axes: each constant's range by the continuum)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.sensor_artifacts import make_sensor_axes_table, make_sensor_band_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make = {"sensor_band": make_sensor_band_table, "sensor_band_axes": make_sensor_axes_table}[snakemake.params.study]
    make(
        snakemake.params.bands, snakemake.input.cases, csv=out.csv, md=out.md, html=out.html, provenance=out.provenance
    )
