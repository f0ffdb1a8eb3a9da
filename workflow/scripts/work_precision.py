"""Snakemake adapter: the work-precision table and the fitted orders."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_work_precision

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    make_work_precision(
        params.runs,
        params.methods,
        params.fit_levels,
        arrival_window=params.arrival_window,
        per_case=params.per_case,
        csv=out.csv,
        orders_csv=out.orders_csv,
        orders_md=out.orders_md,
        orders_html=out.orders_html,
        provenance=out.provenance,
    )
