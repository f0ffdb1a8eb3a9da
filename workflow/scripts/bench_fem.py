"""Snakemake adapter: fem1d and fem_axi benchmarks into one table."""

import pandas as pd

from rodimpact.jobs.logs import script_logging
from rodimpact.tools.bench import benchmark_fem1d, benchmark_fem_axi, write_benchmark

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    frame = pd.concat(
        [
            benchmark_fem1d(snakemake.params.case),
            benchmark_fem_axi(snakemake.params.axi_cases),
        ],
        ignore_index=True,
    )
    write_benchmark(frame, csv=snakemake.output.csv, provenance=snakemake.output.provenance)
