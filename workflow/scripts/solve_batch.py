"""Snakemake adapter: a batch of runs (sweep points, the stability map's points or a stress set's
cases by one method, work-precision levels), each written to its own HDF5 file in the rule's
output directory."""

from rodimpact.jobs.batch import run_batch_into
from rodimpact.jobs.logs import script_logging

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    params = snakemake.params
    # the case file of the batch's runs (a run of another case names its own, run["case_file"])
    case_file = snakemake.input.get("case")
    run_batch_into(
        params.runs,
        snakemake.output.runs,
        case_file=case_file,
        keep_failed=params.keep_failed,
        timing=params.timing,
    )
