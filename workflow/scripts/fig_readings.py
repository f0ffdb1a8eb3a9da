"""Snakemake adapter: a set's readings, contact time against ball mass: the headline figure (the sensor as
built) and its companion (every rod and approximation)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_fig_readings

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    make_fig_readings(
        snakemake.params.runs,
        snakemake.params.variants,
        pdf=snakemake.output.pdf,
        png=snakemake.output.png,
        provenance=snakemake.output.provenance,
        companion_pdf=snakemake.output.companion_pdf,
        companion_png=snakemake.output.companion_png,
        companion_provenance=snakemake.output.companion_provenance,
        sweep_runs=snakemake.params.sweep_runs,
        film_variants=snakemake.params.film_variants,
        band_files=snakemake.input.bands,
        descriptions=snakemake.params.descriptions,
        sensors=snakemake.params.sensors,
        sensor_band_files=snakemake.params.sensor_bands,
        title=snakemake.params.title,
    )
