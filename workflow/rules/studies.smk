# Numerical studies: error against run time, and stability on stiff and extreme cases.
# Tables and figures read HDF5 runs only.


rule work_precision_table:
    """Errors of every level against the converged reference; the orders, expected and observed,
    and the uncertainty of a method measured against its own finest level."""
    input:
        levels=level_files(),
    output:
        csv=report(
            "results/tables/work_precision.csv",
            caption="../report/work_precision.rst",
            category="Error against run time",
            subcategory="All cases",
            labels={"artifact": "Every level: errors and wall times", "format": "CSV"},
        ),
        orders_csv=report(
            "results/tables/work_precision_orders.csv",
            caption="../report/work_precision_orders.rst",
            category="Error against run time",
            subcategory="All cases",
            labels={"artifact": "Observed orders of convergence", "format": "CSV"},
        ),
        orders_md="results/tables/work_precision_orders.md",
        orders_html="results/tables/work_precision_orders.html",
        provenance="results/tables/work_precision.provenance.json",
    log:
        "logs/tables/work_precision.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.study_tables:make_work_precision"),
        runs=level_runs(),
        study=work_precision_study(),
    script:
        "../scripts/artifact.py"


if WORK_PRECISION_SEPARATE:

    # The same table and orders for the sweep's separate cases (levels over a minute each), with
    # their methods only: outside rule all (make convergence-separate). The rule above, its
    # script, group and resources; its own levels, files and report entry.
    use rule work_precision_table as work_precision_separate_table with:
        input:
            levels=level_files(WORK_PRECISION_SEPARATE["cases"], WORK_PRECISION_SEPARATE["methods"]),
        output:
            csv="results/tables/work_precision_separate.csv",
            orders_csv=report(
                "results/tables/work_precision_separate_orders.csv",
                caption="../report/work_precision_separate.rst",
                category="Error against run time",
                subcategory="Separate cases",
                labels={"artifact": "Orders and uncertainty, separate cases", "format": "CSV"},
            ),
            orders_md="results/tables/work_precision_separate_orders.md",
            orders_html="results/tables/work_precision_separate_orders.html",
            provenance="results/tables/work_precision_separate.provenance.json",
        log:
            "logs/tables/work_precision_separate.log",
        params:
            **presentation("rodimpact.present.study_tables:make_work_precision"),
            runs=level_runs(WORK_PRECISION_SEPARATE["cases"], WORK_PRECISION_SEPARATE["methods"]),
            study=work_precision_study(WORK_PRECISION_SEPARATE["methods"]),


rule work_precision_figure:
    """Error against wall time for one case, one panel per error quantity, one line per method,
    with a slope guide of each method's expected order."""
    input:
        levels=lambda w: level_files([w.case]),
    output:
        pdf=report(
            "results/figures/work_precision_{case}.pdf",
            caption="../report/work_precision_figure.rst",
            category="Error against run time",
            subcategory="{case}",
            labels={"artifact": "Error against wall time, {case}", "format": "PDF"},
        ),
        png=report(
            "results/figures/work_precision_{case}.png",
            caption="../report/work_precision_figure.rst",
            category="Error against run time",
            subcategory="{case}",
            labels={"artifact": "Error against wall time, {case}", "format": "PNG"},
        ),
        provenance="results/figures/work_precision_{case}.provenance.json",
    log:
        "logs/figures/work_precision_{case}.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.study_figures:make_work_precision_figure"),
        runs=lambda w: level_runs([w.case]),
        study=work_precision_study(),
    script:
        "../scripts/artifact.py"


rule stability_table:
    """Every method on every stress case: ok, or failed with a message; a violation stops here."""
    input:
        batches=[f for keys in stress_batches() for f in part_files("solve_stress", keys)],
    output:
        csv=report(
            "results/tables/stability.csv",
            caption="../report/stability.rst",
            category="Stability",
            subcategory="Stress cases",
            labels={"artifact": "Every stress run, checked", "format": "CSV"},
        ),
        md="results/tables/stability.md",
        html="results/tables/stability.html",
        provenance="results/tables/stability.provenance.json",
    log:
        "logs/tables/stability.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.study_tables:make_stability"),
        runs=stress_runs(reference=False),
        references=stress_runs(reference=True),
        tolerances=STABILITY.get("tolerances", {}),
    script:
        "../scripts/artifact.py"


rule stability_map:
    """Where each SEM scheme is stable and accurate at one step, over mass and impedance."""
    input:
        batches=map_files(),
    output:
        csv=report(
            "results/tables/stability_map.csv",
            caption="../report/stability_map.rst",
            category="Stability",
            subcategory="Stability map",
            labels={"artifact": "Stability map of the SEM schemes", "format": "CSV"},
        ),
        pdf=report(
            "results/figures/stability_map.pdf",
            caption="../report/stability_map.rst",
            category="Stability",
            subcategory="Stability map",
            labels={"artifact": "Stability map of the SEM schemes", "format": "PDF"},
        ),
        png=report(
            "results/figures/stability_map.png",
            caption="../report/stability_map.rst",
            category="Stability",
            subcategory="Stability map",
            labels={"artifact": "Stability map of the SEM schemes", "format": "PNG"},
        ),
        provenance="results/tables/stability_map.provenance.json",
    log:
        "logs/figures/stability_map.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.study_figures:make_stability_map"),
        runs=map_runs(MAP.get("methods", [])) if MAP else [],
        references=map_runs(["reference"]) if MAP else [],
        spec=MAP,
    script:
        "../scripts/artifact.py"


default_target(study_targets)
