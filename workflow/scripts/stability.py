"""Snakemake adapter: the stress runs checked against their stated tolerances."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_stability

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_stability(
        snakemake.params.runs,
        snakemake.params.references,
        snakemake.params.tolerances,
        csv=out.csv,
        md=out.md,
        html=out.html,
        provenance=out.provenance,
    )
