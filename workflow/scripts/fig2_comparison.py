"""Snakemake adapter: the numbers of Fig. 2 per method, against the SEM and the paper."""

from rodimpact.present.artifacts import make_comparison
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_comparison(snakemake.params.runs, csv=out.csv, md=out.md, html=out.html,  # noqa: F821
                    provenance=out.provenance)
