"""Snakemake adapter: a table of the sensor stack's bands of every case of the band readings (``study``
sensor_band: the bands; sensor_band_axes: each constant's range by the continuum)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.sensor_artifacts import make_axes_table, make_sensor_band_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    files = {"csv": out.csv, "md": out.md, "html": out.html, "provenance": out.provenance}
    if snakemake.params.study == "sensor_band_axes":
        make_axes_table(snakemake.params.bands, snakemake.input.cases, kind="sensor", **files)
    else:
        make_sensor_band_table(snakemake.params.bands, snakemake.input.cases, **files)
