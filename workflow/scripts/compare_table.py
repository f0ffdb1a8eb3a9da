"""Snakemake adapter: one case set's runs against its measurements (table and summary)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.compare_artifacts import make_compare_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_compare_table(snakemake.params.runs, snakemake.params.set_name, csv=out.csv, summary=out.summary,  # noqa: F821
                       md=out.md, html=out.html, tex=out.tex, provenance=out.provenance)
