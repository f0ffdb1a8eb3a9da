"""Snakemake adapter: Table 2 on the text's rod without and with the sensor film."""

from rodimpact.present.artifacts import make_table2_film
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_table2_film(snakemake.input.runs, snakemake.params.variants, snakemake.input.band,  # noqa: F821
                     csv=out.csv, md=out.md, html=out.html, provenance=out.provenance,
                     sensor_bands=snakemake.input.sensor_bands)  # noqa: F821
