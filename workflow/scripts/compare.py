"""Snakemake adapter: one case set's runs against its measurements (table and summary), and its measured
and computed values against the impactor's mass, or what the set names (figure)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.compare_artifacts import make_compare_figure, make_compare_table

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    make_compare_table(
        params.runs,
        params.set_name,
        csv=out.csv,
        summary=out.summary,
        md=out.md,
        html=out.html,
        tex=out.tex,
        provenance=out.provenance,
    )
    make_compare_figure(
        params.runs,
        params.set_name,
        params.title,
        pdf=out.pdf,
        png=out.png,
        provenance=out.figure_provenance,
        descriptions=params.descriptions or None,
        x=params.x or None,
    )
