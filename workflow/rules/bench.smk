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
    """Wall time of fem1d on 'model' and its agreement with the SEM, per mesh and step."""
    input:
        code=SRC_BENCH,
    output:
        csv="results/benchmarks/fem.csv",
    params:
        case=lambda w: PROJECT.cases["model"],
    log:
        "logs/benchmarks/fem.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/bench_fem.py"


rule bench_fem_axi:
    """fem_axi on 'model' and every Table 2 row at the shipped level: time, DOFs, memory."""
    input:
        code=SRC_BENCH,
    output:
        csv="results/benchmarks/fem_axi.csv",
    params:
        cases=lambda w: [PROJECT.cases["model"], *PROJECT.cases_in("table2")],
    log:
        "logs/benchmarks/fem_axi.log",
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/bench_fem_axi.py"
