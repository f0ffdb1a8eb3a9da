# Parameter sweeps: a case that declares `sweep:` is run at every point of its grid
# (a snakemake Paramspace per sweep case, see common.smk), one HDF5 file per point. A point
# solves in a fraction of a second and a job costs more to start, so every point of a sweep by
# one method is solved in one job, whose output is the directory of its points' files
# (results/sweeps/{case}/{method}/{point}.h5, each written whole with its own provenance). A
# failure stops the build like a case's.


rule solve_sweep:
    """Every point of one case's sweep, one method."""
    input:
        case="results/cases/{case}.yaml",
    output:
        runs=directory("results/sweeps/{case}/{method}"),
    log:
        "logs/sweeps/{case}/{method}.log",
    wildcard_constraints:
        case=one_of(PROJECT.sweeps),
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **batch_resources(sweep_batch_runs),
    params:
        code=sweep_sources,
        runs=sweep_batch_runs,
        keep_failed=False,
        timing=None,
    script:
        "../scripts/solve_batch.py"


rule sweep_table:
    """Every point of every sweep of a case set: swept values, contact time and force."""
    input:
        points=lambda w: sweep_point_dirs(PROJECT.sweeps_in(w.set)),
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
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.sweep_table:make_sweep_table"),
        runs=lambda w: sweep_point_runs(PROJECT.sweeps_in(w.set)),
    script:
        "../scripts/artifact.py"


# The sweep table of every built set that has sweeps.
default_target(
    lambda: expand(
        "results/tables/sweep_{set}.{ext}",
        set=[name for name in config["targets"]["sets"] if PROJECT.sweeps_in(name)],
        ext=["csv", "md", "provenance.json"],
    )
)
