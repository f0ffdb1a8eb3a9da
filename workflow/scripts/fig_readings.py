"""Snakemake adapter: a set's readings, contact time against ball mass, per rod, with and without the film."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_fig_readings

with script_logging(snakemake.log[0], outputs=snakemake.output):  # noqa: F821 (injected by snakemake)
    make_fig_readings(snakemake.params.runs, snakemake.params.variants,  # noqa: F821
                    pdf=snakemake.output.pdf, png=snakemake.output.png,  # noqa: F821
                    provenance=snakemake.output.provenance,  # noqa: F821
                    sweep_runs=snakemake.params.sweep_runs,  # noqa: F821
                    film_variants=snakemake.params.film_variants,  # noqa: F821
                    band_files=snakemake.input.bands,  # noqa: F821
                    descriptions=snakemake.params.descriptions,  # noqa: F821
                    sensors=snakemake.params.sensors,  # noqa: F821
                    sensor_band_files=snakemake.params.sensor_bands,  # noqa: F821
                    title=snakemake.params.title)  # noqa: F821
