"""Snakemake adapter: the stability map of the SEM schemes (table and figure)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_stability_map

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    make_stability_map(
        params.runs,
        params.references,
        params.spec,
        csv=out.csv,
        pdf=out.pdf,
        png=out.png,
        provenance=out.provenance,
    )
