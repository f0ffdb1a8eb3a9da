"""Snakemake adapter: one level of a convergence study, written to its HDF5 file."""

from rodimpact.logs import script_logging
from rodimpact.runner import run_to_file

with script_logging(snakemake.log[0]):  # noqa: F821 (injected by snakemake)
    run_to_file(snakemake.params.case, snakemake.params.method, snakemake.output.h5,  # noqa: F821
                level=snakemake.params.level)  # noqa: F821
