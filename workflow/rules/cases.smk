# Cases: the first stage of the chain. One YAML file per case (or sweep case): the resolved
# case with its derived scales and each method's step and cost. Every solver rule takes it
# as an input (ancient: the case's own hash, a parameter, decides reruns, so that a new cost
# calibration rewrites the file without rerunning a solver).


rule case_file:
    """The resolved case, its derived scales and each method's step and estimated cost."""
    input:
        code=SRC_CASES,
    output:
        yaml="results/cases/{case}.yaml",
    params:
        case=resolved_case_of,
    log:
        "logs/cases/{case}.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/case_file.py"
