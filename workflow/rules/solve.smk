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
    """One level of a convergence study: the case with the level's numerics."""
    input:
        code=SRC_SOLVE,
    output:
        h5="results/convergence/{case}/{method}_level{level}.h5",
    params:
        case=lambda w: case_at_level(case_of_run(w), w.method, convergence_level(w.method, int(w.level))),
        method="{method}",
        level=lambda w: int(w.level),
    log:
        "logs/convergence/{case}/{method}_level{level}.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_level.py"
