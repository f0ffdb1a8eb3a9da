"""Snakemake adapter: solve one case with one method, write its HDF5 file."""

from rodimpact.jobs.logs import script_logging
from rodimpact.jobs.runner import run_to_file

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    curve = list(snakemake.input.curve)  # noqa: F821 (one file for a tabulated law, else none)
    run_to_file(snakemake.params.case, snakemake.params.method, snakemake.output.h5,  # noqa: F821
                case_file=snakemake.input.case, contact_curve=curve[0] if curve else None)  # noqa: F821
