"""Snakemake adapter: the inverse analysis of the sensor stack (a fit, labelled as such)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.sensor_artifacts import make_sensor_fit_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, inp = snakemake.output, snakemake.input
    make_sensor_fit_table(
        snakemake.params.fitted,
        snakemake.params.applied,
        inp.cases,
        snakemake.params.layer,
        csv=out.csv,
        md=out.md,
        html=out.html,
        summary=out.summary,
        provenance=out.provenance,
    )
