"""Snakemake adapter: SEM wall time against accuracy on the case 'model'."""

from rodimpact.jobs.logs import script_logging
from rodimpact.tools.bench import benchmark_sem, write_benchmark

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    frame = benchmark_sem(snakemake.params.case)
    write_benchmark(frame, csv=snakemake.output.csv, provenance=snakemake.output.provenance)
