"""Snakemake adapter: the contact force with and without the sensor film."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_fig_film_force

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_fig_film_force(
        snakemake.params.runs,
        snakemake.params.rows,
        pdf=out.pdf,
        png=out.png,
        provenance=out.provenance,
    )
