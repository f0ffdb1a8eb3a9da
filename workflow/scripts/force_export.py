"""Snakemake adapter: every run of a case set, its force as CSV and its closed form as JSON."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.forces import export_forces_into

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    export_forces_into(params.runs, params.names, out.forces, provenance=out.provenance)
