"""Snakemake adapter: error against wall time for one case."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_work_precision_figure

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    make_work_precision_figure(
        params.runs,
        params.methods,
        params.fit_levels,
        arrival_window=params.arrival_window,
        per_case=params.per_case,
        pdf=out.pdf,
        png=out.png,
        provenance=out.provenance,
    )
