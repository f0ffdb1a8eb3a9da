# Tables: read HDF5 runs only.


rule table2:
    """Table 2 of the paper for one reading of the experiment's rod geometry."""
    input:
        runs=lambda w: table2_runs(w.variant),
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/table2_{variant}.csv",
            caption="../report/table2.rst",
            category="Paper, Table 2",
            subcategory="{variant}",
            labels={"artifact": "Table 2, rod reading {variant}", "format": "CSV"},
        ),
        md="results/tables/table2_{variant}.md",
        tex="results/tables/table2_{variant}.tex",
        provenance="results/tables/table2_{variant}.provenance.json",
    params:
        variant="{variant}",
    log:
        "logs/tables/table2_{variant}.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/table2.py"


rule table2_variants:
    """Mean and max error against the measurements per geometry variant and method."""
    input:
        runs=[run for v in TABLE2_VARIANTS for run in table2_runs(v)],
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/table2_variants.csv",
            caption="../report/table2_variants.rst",
            category="Paper, Table 2",
            subcategory="All readings",
            labels={"artifact": "Error per reading and method", "format": "CSV"},
        ),
        md="results/tables/table2_variants.md",
        provenance="results/tables/table2_variants.provenance.json",
    params:
        variants=TABLE2_VARIANTS,
    log:
        "logs/tables/table2_variants.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/table2_variants.py"


rule fig2_comparison:
    """Fig. 2's numbers: contact time and maxima per method against the SEM and the paper's."""
    input:
        runs=lambda w: runs_of([PROJECT.cases["model"]]),
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/fig2_comparison.csv",
            caption="../report/fig2_comparison.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 2",
            labels={"artifact": "Fig. 2 in numbers", "format": "CSV"},
        ),
        md="results/tables/fig2_comparison.md",
        provenance="results/tables/fig2_comparison.provenance.json",
    log:
        "logs/tables/fig2_comparison.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig2_comparison.py"
