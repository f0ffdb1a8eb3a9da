# Benchmarks (make bench; not part of the paper's default target). Run with -j1 for clean timings.


rule bench_sem:
    """Wall time and error of both SEM schemes on 'model' at several step sizes."""
    input:
        code=SRC_BENCH,
    output:
        csv="results/benchmarks/sem.csv",
    params:
        case=lambda w: PROJECT.cases["model"],
    log:
        "logs/benchmarks/sem.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/bench_sem.py"
