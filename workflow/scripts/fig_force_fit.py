"""Snakemake adapter: the contact force's closed form over the computed force, case 'model'."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_fig_force_fit

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_fig_force_fit(
        snakemake.params.runs,
        snakemake.params.jsons,
        pdf=out.pdf,
        png=out.png,
        provenance=out.provenance,
    )
