# Solvers: one HDF5 file per (case, method).


rule solve:
    """Run one method on one case; the HDF5 file appears whole or not at all."""
    input:
        case=case_file(lambda w: w.case),
        curve=contact_curve,
        code=solver_sources(),
    output:
        h5="results/runs/{case}/{method}.h5",
    params:
        case=case_of_run,
        method="{method}",
    log:
        "logs/runs/{case}/{method}.log",
    threads: 1
    resources:
        **solver_resources(case_of_run),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve.py"


rule solve_level:
    """One level of a work-precision sweep: the case with the level's numerics, timed."""
    input:
        case=case_file(lambda w: w.case),
        code=solver_sources(),
    output:
        h5="results/convergence/{case}/{method}_level{level}.h5",
    params:
        case=level_case_of,
        method="{method}",
        level=lambda w: int(w.level),
        study=lambda w: {"name": "work_precision", "level": int(w.level),
                         "overrides": sweep_level(w.method, int(w.level))},
        timing=config.get("work_precision", {}).get("timing", {}),
    log:
        "logs/convergence/{case}/{method}_level{level}.log",
    threads: 1
    resources:
        **solver_resources(level_case_of, timing=WORK_PRECISION.get("timing", {})),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_level.py"


rule solve_stress:
    """One method on one stress case; a failure is stored as data (the study checks it)."""
    input:
        case=case_file(lambda w: w.case),
        code=solver_sources(),
    output:
        h5="results/stress/{case}/{method}.h5",
    params:
        case=case_of_run,
        method="{method}",
    log:
        "logs/stress/{case}/{method}.log",
    threads: 1
    resources:
        **solver_resources(case_of_run),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_study.py"


rule solve_stress_reference:
    """The sem reference of a stress case, at the study's reference tolerance."""
    input:
        case=case_file(lambda w: w.case),
        code=solver_sources(lambda w: "sem"),
    output:
        h5="results/stress/{case}/reference.h5",
    params:
        case=reference_case_of,
        method="sem",
    log:
        "logs/stress/{case}/reference.log",
    threads: 1
    resources:
        **solver_resources(reference_case_of, lambda w: "sem"),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_study.py"


rule solve_map_point:
    """One point of the stability map with one method (or its sem reference)."""
    input:
        case=case_file(lambda w: MAP["base_case"]),
        code=solver_sources(map_method_of),
    output:
        h5="results/stability_map/{point}/{map_method}.h5",
    params:
        case=map_case_of,
        method=map_method_of,
    log:
        "logs/stability_map/{point}/{map_method}.log",
    threads: 1
    resources:
        **solver_resources(map_case_of, map_method_of),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_study.py"
