"""Snakemake adapter: one set's calibration as tables and a figure (a fit, not a prediction)."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.calibration_artifacts import make_calibration_artifacts

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out = snakemake.output
    make_calibration_artifacts(
        snakemake.input.h5,
        snakemake.params.title,
        csv=out.csv,
        parameters_csv=out.parameters_csv,
        md=out.md,
        html=out.html,
        pdf=out.pdf,
        png=out.png,
        provenance=out.provenance,
    )
