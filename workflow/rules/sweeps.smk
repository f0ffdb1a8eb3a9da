# Parameter sweeps: a case that declares `sweep:` is run at every point of its grid
# (a snakemake Paramspace per sweep case, see common.smk), one HDF5 file per point. A point
# solves in a fraction of a second and a job costs more to start, so the points of a sweep are
# solved in batches of at most SWEEP_BATCH points, one job each: a rule per batch, named
# solve_sweep_<case>_<k>, whose outputs are its points' files (each written whole, with its
# own provenance; asking for one point's file runs its batch). A failure stops the build like a
# case's.

SWEEP_BATCH = 16


for case_id, names, k in ((c, n, k) for c, space in SWEEPS.items()
                          for k, n in enumerate(batches(space.instance_patterns, SWEEP_BATCH))):
    runs_of_batch = sweep_batch_runs(case_id, names)

    rule:
        """One batch of the points of a case's sweep, one method."""
        name:
            f"solve_sweep_{rule_name(case_id)}_{k}"
        input:
            case=f"results/cases/{case_id}.yaml",
            code=sweep_sources(case_id),
        output:
            **{f"p{i}": f"results/sweeps/{case_id}/{{method}}/{name}.h5" for i, name in enumerate(names)},
        params:
            runs=runs_of_batch,
            keep_failed=False,
            timing=None,
        log:
            f"logs/sweeps/{case_id}/{{method}}/batch{k}.log",
        group: GROUP_SOLVERS
        threads: 1
        resources:
            **batch_resources(runs_of_batch),
        conda:
            "../envs/rodimpact.yaml"
        script:
            "../scripts/solve_batch.py"


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
        html="results/tables/sweep_{set}.html",
        provenance="results/tables/sweep_{set}.provenance.json",
    log:
        "logs/tables/sweep_{set}.log",
    group: GROUP_TABLES
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/sweep_table.py"
