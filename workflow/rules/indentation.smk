# The contact law calibrated by the continuum: for each case whose law is `tabulated`, fem_axi's
# static indentation of the case's ball, film and rod, as the force-approach curve its 1-D runs
# take (results/indentation/{case}.h5). The case file is its input, so a change of the case's
# ball, film or rod reruns the indentation and the runs that read it, and nothing else.


rule indentation:
    """Static indentation of one case's bodies by the continuum: its contact-law curve."""
    input:
        case=case_file(lambda w: w.case),
        code=SRC_INDENTATION,
    output:
        h5="results/indentation/{case}.h5",
    params:
        case=tabulated_case_of,
        numerics=lambda w: config["numerics"]["fem_axi"],
    log:
        "logs/indentation/{case}.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/indentation.py"
