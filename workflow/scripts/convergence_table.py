"""Snakemake adapter: the table of a convergence study."""

from rodimpact.artifacts import make_convergence
from rodimpact.logs import script_logging

with script_logging(snakemake.log[0]):  # noqa: F821 (injected by snakemake)
    out = snakemake.output  # noqa: F821
    make_convergence(snakemake.input.runs, csv=out.csv, md=out.md, provenance=out.provenance)  # noqa: F821
