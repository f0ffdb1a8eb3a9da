# Every case set of targets.sets whose cases carry measurements (measured: contact time, peak
# force, rebound velocity, a force, strain or velocity history; rodimpact.analysis.measured)
# against its runs, with no set named here: results/tables/compare_{set}.*,
# results/figures/compare_{set}.*, and for each kind of history the set measures
# results/figures/compare_{set}_{force,strain,velocity}.*, a row per case. The history files
# are inputs: a changed record reruns its comparison.


rule compare:
    """One case set's runs against its measurements: the table per case, method and quantity with a
    summary, and the figure of the measured and computed values against the impactor's mass (or
    its compare.x); one job, as both read the same runs."""
    input:
        runs=run_batches(lambda w: compare_runs(w.set)),
        histories=lambda w: compare_histories(w.set),
    output:
        csv=report(
            "results/tables/compare_{set}.csv",
            caption="../report/compare_table.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Measured against computed", "format": "CSV"},
        ),
        summary="results/tables/compare_{set}_summary.csv",
        md="results/tables/compare_{set}.md",
        html="results/tables/compare_{set}.html",
        tex="results/tables/compare_{set}.tex",
        provenance="results/tables/compare_{set}.provenance.json",
        pdf=report(
            "results/figures/compare_{set}.pdf",
            caption="../report/compare_figure.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Measured and computed against the mass", "format": "PDF"},
        ),
        png=report(
            "results/figures/compare_{set}.png",
            caption="../report/compare_figure.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Measured and computed against the mass", "format": "PNG"},
        ),
        figure_provenance="results/figures/compare_{set}.provenance.json",
    log:
        "logs/tables/compare_{set}.log",
    wildcard_constraints:
        set=one_of(COMPARE_SETS),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.compare_figures:make_compare"),
        runs=lambda w: compare_runs(w.set),
        set_name="{set}",
        title=lambda w: f"{set_title(w.set)[:1].upper()}{set_title(w.set)[1:]}: measured and computed",
        x=lambda w: PROJECT.compare.get(w.set, {}).get("x", ""),
        descriptions=lambda w: PROJECT.variants.get(w.set, {})
        and {v: d.get("description", v) for v, d in PROJECT.variants[w.set].items()},
    script:
        "../scripts/artifact.py"


rule compare_signal:
    """A set's measured forces, strains at a gauge, or velocities, against each method's signals
    and their difference, one row per case (for fem_axi's strain, the section's mean beside the
    surface's); one job, as every row reads the same set's runs."""
    input:
        runs=run_batches(lambda w: signal_runs(w.set, w.ending)),
        records=lambda w: compare_histories(w.set),
    output:
        pdf=report(
            "results/figures/compare_{set}_{ending}.pdf",
            caption="../report/compare_signal.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Records ({ending}) against the methods", "format": "PDF"},
        ),
        png=report(
            "results/figures/compare_{set}_{ending}.png",
            caption="../report/compare_signal.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Records ({ending}) against the methods", "format": "PNG"},
        ),
        provenance="results/figures/compare_{set}_{ending}.provenance.json",
    log:
        "logs/figures/compare_{set}_{ending}.log",
    wildcard_constraints:
        set=one_of({s for sets in SIGNAL_SETS.values() for s in sets}),
        ending=one_of(SIGNAL_RECORDS),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.compare_figures:make_signal_figure"),
        runs=lambda w: signal_runs(w.set, w.ending),
        key=lambda w: SIGNAL_RECORDS[w.ending],
        title=lambda w: f"{set_title(w.set)[:1].upper()}{set_title(w.set)[1:]}: measured and computed {w.ending}",
    script:
        "../scripts/artifact.py"


default_target(compare_targets)
