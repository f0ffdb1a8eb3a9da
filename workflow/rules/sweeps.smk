# Parameter sweeps: a case that declares `sweep:` is run at every point of its grid (a snakemake
# Paramspace per sweep case, see common_studies.smk). A point solves in a fraction of a second
# and a job costs seconds to start, so a sweep's points by one method are cut into parts of about
# batch.target_s of typical solve time (rodimpact.jobs.parts, known when the workflow is parsed):
# the paper's sweeps are one part each, a sweep of thousands of points many, run side by side.
# A part is one job and one file of runs (results/sweeps/{case}/{method}/part{k}.h5, a group per
# point; common_batches.smk). A failure stops the build like a case's.


rule solve_sweep:
    """One part of one case's sweep by one method: its points, one after another."""
    input:
        cases=part_input("solve_sweep", case_files),
    output:
        runs=BATCHES["solve_sweep"].file,
    log:
        "logs/sweeps/{case}/{method}/part{part}.log",
    wildcard_constraints:
        case=one_of(PROJECT.sweeps),
    group:
        part_group("solve_sweep")
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **part_resources("solve_sweep"),
    params:
        code=sweep_sources,
        runs=part_runs("solve_sweep"),
        keep_failed=False,
        timing=None,
    script:
        "../scripts/solve_part.py"


rule sweep_table:
    """Every point of every sweep of a case set: swept values, contact time and force."""
    input:
        parts=lambda w: sweep_part_files(PROJECT.sweeps_in(w.set)),
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
    # a large sweep's points are read by as many processes (snakemake gives at most its cores)
    threads: 8
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
