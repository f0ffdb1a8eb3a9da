"""Snakemake adapter: one level of a work-precision sweep, timed, written to its HDF5 file."""

from rodimpact.workflow.logs import script_logging
from rodimpact.workflow.runner import Timing, run_to_file

with script_logging(snakemake.log[0]):  # noqa: F821 (injected by snakemake)
    params = snakemake.params  # noqa: F821
    run_to_file(params.case, params.method, snakemake.output.h5, level=params.level,  # noqa: F821
                timing=Timing(**params.timing), study=params.study, case_file=snakemake.input.case)  # noqa: F821
