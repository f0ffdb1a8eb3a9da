"""Snakemake adapter: every run of a case set, its force as CSV and its closed form as JSON."""

from rodimpact.present.forces import export_forces
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    export_forces(snakemake.params.runs, out.csvs, out.jsons, provenance=out.provenance)  # noqa: F821
