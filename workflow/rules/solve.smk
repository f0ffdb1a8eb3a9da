# Solvers: every batch of runs (common_batches.smk) cut into parts, one job and one file of runs
# each: results/{runs,convergence,stress,stability_map}/.../part{k}.h5, a run named
# part{k}.h5#{name}. A batch below batch.target_s is one part in the job group of the solvers (its
# submission shared with other small jobs); a batch cut into parts is submitted part by part.


rule solve:
    """One part of one group's batch (a reading of a set with variants, else a set): one method on
    its cases that list it, results/runs/{group}/{method}/part{part}.h5, a run per case."""
    input:
        cases=part_input("solve", case_files),
        curves=part_input(
            "solve",
            lambda runs: sorted({os.path.dirname(r["contact_curve"]) for r in runs.values() if "contact_curve" in r}),
        ),
    output:
        runs=BATCHES["solve"].file,
    log:
        "logs/runs/{group}/{method}/part{part}.log",
    group:
        part_group("solve")
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **part_resources("solve"),
    params:
        code=batch_sources(),
        runs=part_runs("solve"),
        keep_failed=False,
        timing=None,
    script:
        "../scripts/solve_part.py"


rule solve_levels:
    """One part of one method's work-precision levels on one case, each timed:
    results/convergence/{case}/{method}/part{part}.h5, a run per level (level{k})."""
    input:
        cases=part_input("solve_levels", case_files),
    output:
        runs=BATCHES["solve_levels"].file,
    log:
        "logs/convergence/{case}/{method}/part{part}.log",
    group:
        part_group("solve_levels")
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **part_resources("solve_levels"),
    params:
        code=batch_sources(),
        runs=part_runs("solve_levels"),
        keep_failed=False,
        timing=BATCHES["solve_levels"].timing,
    script:
        "../scripts/solve_part.py"


rule solve_stress:
    """One part of one method on the cases of a stress set that list it, or (``reference``) of the
    sem references at the study's tolerance: results/stress/{set}/{stress_method}/part{part}.h5, a
    run per case; a failure is stored as data (the study checks it)."""
    input:
        cases=part_input("solve_stress", case_files),
    output:
        runs=BATCHES["solve_stress"].file,
    log:
        "logs/stress/{set}/{stress_method}/part{part}.log",
    wildcard_constraints:
        set=one_of(STABILITY.get("sets", [])),
        stress_method=one_of([*METHOD_REGISTRY, "reference"]),
    group:
        part_group("solve_stress")
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **part_resources("solve_stress"),
    params:
        code=batch_sources(lambda w: solver_of(w.stress_method)),
        runs=part_runs("solve_stress"),
        keep_failed=True,
        timing=None,
    script:
        "../scripts/solve_part.py"


if MAP:

    rule solve_map:
        """One part of the stability map's points (each impactor mass at every rod impedance) by one
        method or its sem reference: results/stability_map/{map_method}/part{part}.h5, a run per
        point (m{i}_z{j}); a failure is stored as data."""
        input:
            cases=part_input("solve_map", case_files),
        output:
            runs=BATCHES["solve_map"].file,
        log:
            "logs/stability_map/{map_method}/part{part}.log",
        group:
            part_group("solve_map")
        conda:
            "../envs/rodimpact.yaml"
        threads: 1
        resources:
            **part_resources("solve_map"),
        params:
            code=batch_sources(lambda w: solver_of(w.map_method)),
            runs=part_runs("solve_map"),
            keep_failed=True,
            timing=None,
        script:
            "../scripts/solve_part.py"


# Every run of the built sets' cases, by their parts' files.
default_target(
    lambda: [batch for name in config["targets"]["sets"] for batch in run_batches(runs_of(PROJECT.cases_in(name)))]
)
