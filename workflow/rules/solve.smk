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
    group: GROUP_SOLVERS
    threads: 1
    resources:
        **solver_resources(case_of_run),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve.py"


# The levels of a method's work-precision sweep on one case: one job (a rule per method,
# solve_levels_<method>), one timed HDF5 file per level.
for method, levels in WORK_PRECISION.get("methods", {}).items():
    runs_of_levels = level_runs(method)

    rule:
        """Every level of one method's work-precision sweep on one case, each timed."""
        name:
            f"solve_levels_{method}"
        input:
            case=case_file(lambda w: w.case),
            code=BATCH_SOURCES[method],
        output:
            **{f"level{k}": f"results/convergence/{{case}}/{method}_level{k}.h5" for k in range(len(levels["levels"]))},
        params:
            runs=runs_of_levels,
            keep_failed=False,
            timing=WORK_PRECISION.get("timing", {}),
        log:
            f"logs/convergence/{{case}}/{method}.log",
        group: GROUP_SOLVERS
        threads: 1
        resources:
            **batch_resources(runs_of_levels, timing=WORK_PRECISION.get("timing", {})),
        conda:
            "../envs/rodimpact.yaml"
        script:
            "../scripts/solve_batch.py"


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
    group: GROUP_SOLVERS
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
    group: GROUP_SOLVERS
    threads: 1
    resources:
        **solver_resources(reference_case_of, lambda w: "sem"),
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/solve_study.py"


if MAP:

    rule solve_map_row:
        """One row of the stability map (one impactor mass, every rod impedance) with one method
        or its sem reference: one HDF5 file per point; a failure is stored as data."""
        input:
            case=case_file(lambda w: MAP["base_case"]),
            code=batch_sources(map_method_of),
        output:
            **{f"z{j}": f"results/stability_map/m{{row}}_z{j}/{{map_method}}.h5"
               for j in range(len(MAP["impedance_kg_s"]))},
        params:
            runs=map_row_runs,
            keep_failed=True,
            timing=None,
        log:
            "logs/stability_map/m{row}/{map_method}.log",
        group: GROUP_SOLVERS
        threads: 1
        resources:
            **batch_resources(map_row_runs),
        conda:
            "../envs/rodimpact.yaml"
        script:
            "../scripts/solve_batch.py"
