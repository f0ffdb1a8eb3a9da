"""Snakemake adapter: Fig. 2, its numbers, Fig. 4 and the force's closed form (the runs of the case 'model')."""

from rodimpact.jobs.logs import script_logging
from rodimpact.present.artifacts import make_comparison, make_fig2, make_fig4, make_fig_force_fit

with script_logging(snakemake.log[0], outputs=snakemake.output):  # `snakemake`: injected by snakemake
    out, params = snakemake.output, snakemake.params
    make_fig2(params.runs, pdf=out.fig2_pdf, png=out.fig2_png, provenance=out.fig2_provenance)
    make_comparison(params.runs, csv=out.csv, md=out.md, html=out.html, provenance=out.table_provenance)
    make_fig4(params.runs, params.fraction, pdf=out.fig4_pdf, png=out.fig4_png, provenance=out.fig4_provenance)
    make_fig_force_fit(
        params.runs, params.jsons, pdf=out.force_fit_pdf, png=out.force_fit_png, provenance=out.force_fit_provenance
    )
