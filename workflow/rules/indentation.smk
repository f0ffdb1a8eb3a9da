# The contact law calibrated by the continuum: for each case whose law needs the indentation's
# curve (its needs.curve_rule, rodimpact.contact.law), fem_axi's static indentation of the
# case's ball, film and rod, as the force-approach curve its 1-D runs take
# (results/indentation/{group}/{case}.h5, one job per group of runs). The group's case file is
# its input, so a change of a case's ball, film or rod reruns its group's indentations and the
# runs that read them, and nothing else.


rule indentation:
    """Static indentation of each case of one group whose law the continuum calibrates: one curve
    file per case, results/indentation/{group}/{case}.h5."""
    input:
        case=lambda w: case_file_of(indentation_cases_of(w)[0]["id"]),
    output:
        curves=directory("results/indentation/{group}"),
    log:
        "logs/indentation/{group}.log",
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        code=SRC_INDENTATION,
        cases=indentation_cases_of,
        numerics=lambda w: config["numerics"]["fem_axi"],
    script:
        "../scripts/indentation.py"


rule film_band:
    """The film's prediction band for one reading with a film (of a set with variants): the SEM's contact time
    at the corners of the film constants' ranges (study film_band_axes, make film-axes: also along each
    range, the evidence that the corners bound it)."""
    input:
        cases=lambda w: sorted({case_file_of(c["id"]) for c in reading_cases(w.variant)}),
    output:
        h5="results/studies/{study}_{variant}.h5",
    log:
        "logs/studies/{study}_{variant}.log",
    wildcard_constraints:
        study="film_band|film_band_axes",
        variant=one_of(FILM_VARIANTS),
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        code=SRC_BAND,
        cases=lambda w: reading_cases(w.variant),
        variant="{variant}",
        axes=lambda w: w.study == "film_band_axes",
    script:
        "../scripts/film_band.py"
