# Solvers: one HDF5 file per (case, method), written in batches (below).


rule solve:
    """One method on every case of one group (a reading of a set with variants, else a set) that
    lists it: one file per case, results/runs/{group}/{method}/{case}.h5, each written whole."""
    input:
        cases=lambda w: sorted({run["case_file"] for run in group_runs(w).values()}),
        curves=lambda w: sorted(
            {os.path.dirname(run["contact_curve"]) for run in group_runs(w).values() if "contact_curve" in run}
        ),
    output:
        runs=directory("results/runs/{group}/{method}"),
    log:
        "logs/runs/{group}/{method}.log",
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **batch_resources(group_runs),
    params:
        code=batch_sources(),
        runs=group_runs,
        keep_failed=False,
        timing=None,
    script:
        "../scripts/solve_batch.py"


# Batches: one method on a group of runs in one job, written into the rule's output directory,
# one HDF5 file per run (each whole, with its own provenance; rodimpact.jobs.batch). A run of a
# fraction of a second costs less than starting a job.


rule solve_levels:
    """Every level of one method's work-precision sweep on one case, each timed: one file per
    level, results/convergence/{case}/{method}/level{k}.h5."""
    input:
        case=case_file(lambda w: w.case),
    output:
        runs=directory("results/convergence/{case}/{method}"),
    log:
        "logs/convergence/{case}/{method}.log",
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **batch_resources(level_runs, timing=WORK_PRECISION.get("timing", {})),
    params:
        code=batch_sources(),
        runs=level_runs,
        keep_failed=False,
        timing=WORK_PRECISION.get("timing", {}),
    script:
        "../scripts/solve_batch.py"


rule solve_stress:
    """One method on every case of a stress set that lists it, or (``reference``) the sem reference of
    each case at the study's reference tolerance: one file per case,
    results/stress/{set}/{stress_method}/{case}.h5; a failure is stored as data (the study checks it)."""
    input:
        cases=lambda w: sorted({run["case_file"] for run in stress_runs(w).values()}),
    output:
        runs=directory("results/stress/{set}/{stress_method}"),
    log:
        "logs/stress/{set}/{stress_method}.log",
    wildcard_constraints:
        set=one_of(STABILITY.get("sets", [])),
        stress_method=one_of([*METHOD_REGISTRY, "reference"]),
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **batch_resources(stress_runs),
    params:
        code=batch_sources(stress_method_of),
        runs=stress_runs,
        keep_failed=True,
        timing=None,
    script:
        "../scripts/solve_batch.py"


if MAP:

    rule solve_map:
        """Every point of the stability map (each impactor mass at every rod impedance) with one
        method or its sem reference: one file per point, results/stability_map/{map_method}/m{i}_z{j}.h5;
        a failure is stored as data."""
        input:
            case=case_file(lambda w: MAP["base_case"]),
        output:
            runs=directory("results/stability_map/{map_method}"),
        log:
            "logs/stability_map/{map_method}.log",
        group:
            GROUP_SOLVERS
        conda:
            "../envs/rodimpact.yaml"
        threads: 1
        resources:
            **batch_resources(map_runs),
        params:
            code=batch_sources(map_method_of),
            runs=map_runs,
            keep_failed=True,
            timing=None,
        script:
            "../scripts/solve_batch.py"


# Every run of the built sets' cases, by their batches' directories.
default_target(
    lambda: [batch for name in config["targets"]["sets"] for batch in run_batches(runs_of(PROJECT.cases_in(name)))]
)
