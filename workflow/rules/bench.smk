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


rule bench_fem:
    """fem1d on 'model' (time and agreement with the SEM per mesh and step), and fem_axi on
    'model' and every Table 2 row at the shipped level (time, DOFs, steps, peak memory)."""
    input:
        code=SRC_BENCH,
    output:
        csv="results/benchmarks/fem.csv",
    params:
        case=lambda w: PROJECT.cases["model"],
        axi_cases=lambda w: [PROJECT.cases["model"], *PROJECT.cases_in("table2")],
    log:
        "logs/benchmarks/fem.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/bench_fem.py"

