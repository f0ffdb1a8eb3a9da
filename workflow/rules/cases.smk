# Cases: the first stage of the chain. One YAML file per group of runs (the cases whose runs
# are batched together: a reading of a set with variants, else a set) or sweep case: each
# resolved case with its derived scales and each method's step and cost. Every solver rule
# takes its group's file as an input, so a change of a case reruns its group's chain and
# nothing else. The file holds the cost model's estimates: a new calibration of the cost model
# rewrites the case files and so reruns the runs whose file changed. A case file takes about a
# second: on a cluster it is written on the head node, not submitted.


rule case_file:
    """The resolved cases of one group (or one sweep case), their derived scales and each method's
    step and estimated cost."""
    output:
        yaml="results/cases/{name}.yaml",
    log:
        "logs/cases/{name}.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        code=SRC_CASES,
        name="{name}",
        cases=case_file_cases,
    script:
        "../scripts/case_file.py"
