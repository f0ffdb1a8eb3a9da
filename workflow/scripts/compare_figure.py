"""Snakemake adapter: one case set's measured and computed values against the impactor's mass, or what the set names."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.compare_artifacts import make_compare_figure

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out, params = snakemake.output, snakemake.params  # noqa: F821
    make_compare_figure(snakemake.params.runs, params.set_name, params.title, pdf=out.pdf, png=out.png,  # noqa: F821
                        provenance=out.provenance, descriptions=params.descriptions or None,
                        x=params.x or None)
