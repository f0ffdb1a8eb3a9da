"""Snakemake adapter: fem1d wall time against agreement with the SEM on the case 'model'."""

from rodimpact.atomic import atomic_output
from rodimpact.bench import benchmark_fem1d
from rodimpact.logs import script_logging

with script_logging(snakemake.log[0]):  # noqa: F821 (injected by snakemake)
    frame = benchmark_fem1d(snakemake.params.case)  # noqa: F821
    with atomic_output(snakemake.output.csv) as tmp:  # noqa: F821
        frame.to_csv(tmp, index=False, float_format="%.6g")
