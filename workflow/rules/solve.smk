# Solvers: one HDF5 file per (case, method).


rule solve:
    """Run one method on one case; the HDF5 file appears whole or not at all."""
    input:
        code=SRC_SOLVE,
    output:
        h5="results/runs/{case}/{method}.h5",
    params:
        case=case_of_run,
        method="{method}",
    log:
        "logs/runs/{case}/{method}.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve.py"


rule solve_level:
    """One level of a work-precision sweep: the case with the level's numerics, timed."""
    input:
        code=SRC_SOLVE,
    output:
        h5="results/convergence/{case}/{method}_level{level}.h5",
    params:
        case=lambda w: sweep_case(w.case, w.method, int(w.level)),
        method="{method}",
        level=lambda w: int(w.level),
        study=lambda w: {"name": "work_precision", "level": int(w.level),
                         "overrides": sweep_level(w.method, int(w.level))},
        timing=config.get("work_precision", {}).get("timing", {}),
    log:
        "logs/convergence/{case}/{method}_level{level}.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_level.py"


rule solve_stress:
    """One method on one stress case; a failure is stored as data (the study checks it)."""
    input:
        code=SRC_SOLVE,
    output:
        h5="results/stress/{case}/{method}.h5",
    params:
        case=case_of_run,
        method="{method}",
    log:
        "logs/stress/{case}/{method}.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_study.py"


rule solve_stress_reference:
    """The sem reference of a stress case, at the study's reference tolerance."""
    input:
        code=SRC_SOLVE,
    output:
        h5="results/stress/{case}/reference.h5",
    params:
        case=lambda w: reference_case(PROJECT.cases[w.case], config["numerics"],
                                      config["stability"]["reference_tolerance"]),
        method="sem",
    log:
        "logs/stress/{case}/reference.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_study.py"


rule solve_map_point:
    """One point of the stability map with one method (or its sem reference)."""
    input:
        code=SRC_SOLVE,
    output:
        h5="results/stability_map/{point}/{map_method}.h5",
    params:
        case=lambda w: map_point_case(PROJECT.cases[MAP["base_case"]], MAP, w.point, w.map_method,
                                      config["numerics"]),
        method=lambda w: "sem" if w.map_method == "reference" else w.map_method,
    log:
        "logs/stability_map/{point}/{map_method}.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_study.py"
