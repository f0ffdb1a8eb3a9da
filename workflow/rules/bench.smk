# Benchmarks (make bench; not part of the paper's default target). Run with -j1 for clean timings.


rule bench_sem:
    """Wall time and error of both SEM schemes on 'model' at several step sizes."""
    output:
        csv=report(
            "results/benchmarks/sem.csv",
            caption="../report/bench_sem.rst",
            category="Benchmarks",
            subcategory="SEM",
            labels={"artifact": "Both SEM schemes: time and error", "format": "CSV"},
        ),
        provenance="results/benchmarks/sem.provenance.json",
    log:
        "logs/benchmarks/sem.log",
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **bench_resources(lambda: sem_bench_runs(PROJECT.cases["model"])),
    params:
        code=SRC_BENCH,
        case=lambda w: PROJECT.cases["model"],
    script:
        "../scripts/bench_sem.py"


# 'model' and every case of the reading sets (the paper's: Table 2) that fem_axi runs
FEM_AXI_BENCH_CASES = [
    PROJECT.cases["model"],
    *(c for name in READING_SETS for c in PROJECT.cases_in(name) if "fem_axi" in c["methods"]),
]


rule bench_fem:
    """fem1d on 'model' (time and agreement with the SEM per mesh and step), and fem_axi on
    'model' and every Table 2 case it runs, with and without the film, at the shipped level
    (time, DOFs, steps, peak memory); 'model' and the slowest Table 2 row again with the whole
    rod a continuum, to check the far bar."""
    output:
        csv=report(
            "results/benchmarks/fem.csv",
            caption="../report/bench_fem.rst",
            category="Benchmarks",
            subcategory="FEM",
            labels={"artifact": "fem1d and fem_axi: time, size, agreement", "format": "CSV"},
        ),
        provenance="results/benchmarks/fem.provenance.json",
    log:
        "logs/benchmarks/fem.log",
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **bench_resources(lambda: fem_bench_runs(PROJECT.cases["model"], FEM_AXI_BENCH_CASES)),
    params:
        code=SRC_BENCH,
        case=lambda w: PROJECT.cases["model"],
        axi_cases=lambda w: FEM_AXI_BENCH_CASES,
    script:
        "../scripts/bench_fem.py"


rule bench_sem_scaling:
    """The SEM's time per step against the wave round trips in the contact ('model' with its
    rod shortened to 10 to 10,000 round trips, and 'seconds_contact'); the automatic step's
    cost over a fixed-step run at the step it chose."""
    output:
        csv=report(
            "results/benchmarks/sem_scaling.csv",
            caption="../report/bench_sem_scaling.rst",
            category="Benchmarks",
            subcategory="SEM",
            labels={"artifact": "SEM: time per step against round trips", "format": "CSV"},
        ),
        provenance="results/benchmarks/sem_scaling.provenance.json",
    log:
        "logs/benchmarks/sem_scaling.log",
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **bench_resources(lambda: sem_scaling_runs(PROJECT.cases["model"], PROJECT.cases["seconds_contact"])),
    params:
        code=SRC_BENCH,
        model=lambda w: PROJECT.cases["model"],
        stress=lambda w: PROJECT.cases["seconds_contact"],
    script:
        "../scripts/bench_sem_scaling.py"
