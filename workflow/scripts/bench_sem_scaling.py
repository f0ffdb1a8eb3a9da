"""Snakemake adapter: the SEM's cost per step against the wave round trips in the contact."""

from rodimpact.jobs.logs import script_logging
from rodimpact.tools.bench import write_benchmark
from rodimpact.tools.bench_scaling import benchmark_sem_scaling

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    frame = benchmark_sem_scaling(snakemake.params.model, snakemake.params.stress)
    write_benchmark(frame, csv=snakemake.output.csv, provenance=snakemake.output.provenance)
