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
