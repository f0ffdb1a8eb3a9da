# Cases: the first stage of the chain. One YAML file per case (or sweep case): the resolved
# case with its derived scales and each method's step and cost. Every solver rule takes it
# as an input, so a change of the case reruns that case's chain and nothing else. The file
# holds the cost model's estimates: a new calibration of the cost model rewrites the case
# files and so reruns the runs whose file changed. A case file takes a fraction of a second:
# on a cluster it is written on the head node, not submitted.

localrules:
    case_file,



rule case_file:
    """The resolved case, its derived scales and each method's step and estimated cost."""
    output:
        yaml="results/cases/{case}.yaml",
    params:
        code=SRC_CASES,
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
