# Parameter sweeps: a case that declares `sweep:` is run at every point of its grid
# (a snakemake Paramspace per sweep case, see common.smk), one HDF5 file per point.


rule solve_sweep_point:
    """One point of a case's sweep, one method; a failure stops the build like a case's."""
    input:
        case=case_file(lambda w: w.case),
        code=solver_sources(),
    output:
        h5="results/sweeps/{case}/{method}/{sweep_point}.h5",
    params:
        case=sweep_point_of,
        method="{method}",
        study=lambda w: {"name": "sweep", "sweep": w.case, "point": w.sweep_point},
    log:
        "logs/sweeps/{case}/{method}/{sweep_point}.log",
    threads: 1
    resources:
        **solver_resources(sweep_point_of),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_sweep.py"


rule sweep_table:
    """Every point of every sweep of a case set: swept values, contact time and force."""
    input:
        runs=lambda w: sweep_point_runs(PROJECT.sweeps_in(w.set)),
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/sweep_{set}.csv",
            caption="../report/sweep_table.rst",
            category="Parameter sweeps",
            subcategory="{set}",
            labels={"artifact": "Every sweep point of {set}", "format": "CSV"},
        ),
        md="results/tables/sweep_{set}.md",
        provenance="results/tables/sweep_{set}.provenance.json",
    log:
        "logs/tables/sweep_{set}.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/sweep_table.py"
