# The contact law calibrated by the continuum: for each case whose law needs the indentation's
# curve (its needs.curve_rule, rodimpact.contact.law), fem_axi's
# static indentation of the case's ball, film and rod, as the force-approach curve its 1-D runs
# take (results/indentation/{case}.h5). The case file is its input, so a change of the case's
# ball, film or rod reruns the indentation and the runs that read it, and nothing else.


rule indentation:
    """Static indentation of one case's bodies by the continuum: its contact-law curve."""
    input:
        case=case_file(lambda w: w.case),
    output:
        h5=CURVE_FILES["indentation"],
    params:
        code=SRC_INDENTATION,
        case=indentation_case_of,
        numerics=lambda w: config["numerics"]["fem_axi"],
    log:
        "logs/indentation/{case}.log",
    group: GROUP_SOLVERS
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/indentation.py"


rule film_band:
    """The film's prediction band for one reading with a film (of a set with variants): the SEM's contact time
    at the corners of the film constants' ranges, and along each range (monotonicity)."""
    input:
        cases=lambda w: sorted({case_file_of(c["id"]) for c in reading_cases(w.variant)}),
    output:
        h5="results/studies/film_band_{variant}.h5",
    params:
        code=SRC_BAND,
        cases=lambda w: reading_cases(w.variant),
        variant="{variant}",
    log:
        "logs/studies/film_band_{variant}.log",
    group: GROUP_SOLVERS
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/film_band.py"
