"""Snakemake adapter: fem_axi time, DOFs and peak memory per case (one process per run)."""

from rodimpact.atomic import atomic_output
from rodimpact.bench import benchmark_fem_axi
from rodimpact.logs import script_logging

with script_logging(snakemake.log[0]):  # noqa: F821 (injected by snakemake)
    frame = benchmark_fem_axi(snakemake.params.cases)  # noqa: F821
    with atomic_output(snakemake.output.csv) as tmp:  # noqa: F821
        frame.to_csv(tmp, index=False, float_format="%.6g")
