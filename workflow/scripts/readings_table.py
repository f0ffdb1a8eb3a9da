"""Snakemake adapter: Table 2 for one rod geometry variant."""

from rodimpact.present.artifacts import make_table2
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_table2(snakemake.input.runs, snakemake.params.variant,  # noqa: F821
                csv=out.csv, md=out.md, html=out.html, tex=out.tex, provenance=out.provenance)
