"""Snakemake adapter: the inverse analysis of the sensor stack as a figure (a fit, labelled as such)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.sensor_artifacts import make_fig_sensor_fit

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, inp = snakemake.output, snakemake.input
    make_fig_sensor_fit(
        snakemake.params.fitted,
        snakemake.params.applied,
        inp.cases,
        snakemake.params.layer,
        pdf=out.pdf,
        png=out.png,
        provenance=out.provenance,
        descriptions=snakemake.params.descriptions,
    )
