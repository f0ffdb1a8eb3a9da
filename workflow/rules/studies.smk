# Numerical studies: error against run time, and stability on stiff and extreme cases.
# Tables and figures read HDF5 runs only.


rule work_precision_table:
    """Errors of every level against the converged reference, and the fitted orders."""
    input:
        runs=sweep_runs(),
        code=SRC_PRESENT,
    output:
        csv="results/tables/work_precision.csv",
        orders_csv="results/tables/work_precision_orders.csv",
        orders_md="results/tables/work_precision_orders.md",
        provenance="results/tables/work_precision.provenance.json",
    params:
        methods=WORK_PRECISION.get("methods", {}),
        fit_levels=WORK_PRECISION.get("fit_levels", 4),
    log:
        "logs/tables/work_precision.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/work_precision.py"


rule work_precision_figure:
    """Error against wall time for one case, one line per method and quantity."""
    input:
        runs=lambda w: sweep_runs([w.case]),
        code=SRC_PRESENT,
    output:
        pdf="results/figures/work_precision_{case}.pdf",
        png="results/figures/work_precision_{case}.png",
    params:
        methods=WORK_PRECISION.get("methods", {}),
        fit_levels=WORK_PRECISION.get("fit_levels", 4),
    log:
        "logs/figures/work_precision_{case}.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/work_precision_figure.py"


rule stability_table:
    """Every method on every stress case: ok, or failed with a message; a violation stops here."""
    input:
        runs=[f"results/stress/{c['id']}/{m}.h5" for c in STRESS_CASES for m in c["methods"]],
        references=[f"results/stress/{c['id']}/reference.h5" for c in STRESS_CASES],
        code=SRC_PRESENT,
    output:
        csv="results/tables/stability.csv",
        md="results/tables/stability.md",
        provenance="results/tables/stability.provenance.json",
    params:
        tolerances=STABILITY.get("tolerances", {}),
    log:
        "logs/tables/stability.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/stability.py"


rule stability_map:
    """Where each SEM scheme is stable and accurate at one step, over mass and impedance."""
    input:
        runs=[f"results/stability_map/{p}/{m}.h5" for p in MAP_POINTS for m in MAP.get("methods", [])],
        references=[f"results/stability_map/{p}/reference.h5" for p in MAP_POINTS],
        code=SRC_PRESENT,
    output:
        csv="results/tables/stability_map.csv",
        pdf="results/figures/stability_map.pdf",
        png="results/figures/stability_map.png",
        provenance="results/tables/stability_map.provenance.json",
    params:
        spec=MAP,
    log:
        "logs/figures/stability_map.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/stability_map.py"
