# The sensor as built (docs/sensor.md). For each case of the readings config["sensor"] names, the
# SEM with the law the continuum calibrates on the case's stack, over the stack's sourced ranges
# (results/studies/sensor_band/{case}.h5; a reading of the fit only gets its layer's thickness
# grid); then the bands' table and the inverse analysis, labelled as a fit.
rule sensor_band:
    """The calibrated SEM over the sensor stack of each case of one reading: its band, and the fit's
    thickness grid; one file per case, results/studies/sensor_band/{variant}/{case}.h5."""
    input:
        case=lambda w: case_file_of(reading_cases(w.variant)[0]["id"]),
        # the nominal stacks' calibrated laws: the curves the cases' own runs take
        curves=lambda w: sorted({os.path.dirname(curve_file_of(c)) for c in reading_cases(w.variant)}),
    output:
        bands=directory("results/studies/sensor_band/{variant}"),
    log:
        "logs/studies/sensor_band/{variant}.log",
    wildcard_constraints:
        variant=one_of(SENSOR_READINGS),
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        code=SRC_SENSOR,
        cases=lambda w: reading_cases(w.variant),
        curves=lambda w: {c["id"]: curve_file_of(c) for c in reading_cases(w.variant)},
        variant="{variant}",
        band=lambda w: SENSOR_READINGS[w.variant],
        grid=SENSOR_GRID,
        numerics=lambda w: config["numerics"]["fem_axi"],
    script:
        "../scripts/sensor_band.py"


rule sensor_band_table:
    """The sensor's band of every case of the band readings."""
    input:
        bands=sensor_band_dirs([v for v, band in SENSOR_READINGS.items() if band]),
        cases=sorted({case_file_of(case) for case, v in SENSOR_READING_OF.items() if SENSOR_READINGS[v]}),
    output:
        csv=report(
            "results/tables/sensor_band.csv",
            caption="../report/sensor_band.rst",
            category="The experiment's sensor",
            subcategory="The sensor as built",
            labels={"artifact": "The sensor's prediction band", "format": "CSV"},
        ),
        md="results/tables/sensor_band.md",
        html="results/tables/sensor_band.html",
        provenance="results/tables/sensor_band.provenance.json",
    log:
        "logs/tables/sensor_band.log",
    group:
        GROUP_TABLES
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        code=SRC_SENSOR_TABLES,
        bands=sensor_band_files([v for v, band in SENSOR_READINGS.items() if band]),
    script:
        "../scripts/sensor_band_table.py"


rule sensor_fit:
    """The inverse analysis: one layer's thickness fitted to the measurements, with leave-one-out."""
    input:
        bands=sensor_band_dirs(SENSOR_FIT_READINGS),
        cases=sorted({case_file_of(c) for c in SENSOR_READING_OF}),
    output:
        csv=report(
            "results/tables/sensor_fit.csv",
            caption="../report/sensor_fit.rst",
            category="The experiment's sensor",
            subcategory="The sensor as built",
            labels={"artifact": "A fit of the bond line", "format": "CSV"},
        ),
        md="results/tables/sensor_fit.md",
        html="results/tables/sensor_fit.html",
        summary="results/tables/sensor_fit.json",
        provenance="results/tables/sensor_fit.provenance.json",
    log:
        "logs/tables/sensor_fit.log",
    group:
        GROUP_SOLVERS
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        code=SRC_SENSOR_TABLES,
        fitted=sensor_band_files([SENSOR_FIT["reading"]] if SENSOR_FIT else []),
        applied=sensor_band_files(SENSOR_FIT.get("apply_to", []) if SENSOR_FIT else []),
        layer=SENSOR_FIT["layer"] if SENSOR_FIT else "",
    script:
        "../scripts/sensor_fit.py"


rule fig_sensor_fit:
    """The inverse analysis as a figure: measured, the sourced stack, the fitted one, the rows held out."""
    input:
        bands=sensor_band_dirs(SENSOR_FIT_READINGS),
        cases=sorted({case_file_of(c) for c in SENSOR_READING_OF}),
    output:
        pdf=report(
            "results/figures/sensor_fit.pdf",
            caption="../report/sensor_fit_figure.rst",
            category="The experiment's sensor",
            subcategory="The sensor as built",
            labels={"artifact": "A fit of the bond line (figure)", "format": "PDF"},
        ),
        png=report(
            "results/figures/sensor_fit.png",
            caption="../report/sensor_fit_figure.rst",
            category="The experiment's sensor",
            subcategory="The sensor as built",
            labels={"artifact": "A fit of the bond line (figure)", "format": "PNG"},
        ),
        provenance="results/figures/sensor_fit.provenance.json",
    log:
        "logs/figures/sensor_fit.log",
    group:
        GROUP_TABLES
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        code=SRC_SENSOR_TABLES,
        fitted=sensor_band_files([SENSOR_FIT["reading"]] if SENSOR_FIT else []),
        applied=sensor_band_files(SENSOR_FIT.get("apply_to", []) if SENSOR_FIT else []),
        layer=SENSOR_FIT["layer"] if SENSOR_FIT else "",
        descriptions=READING_DESCRIPTIONS,
    script:
        "../scripts/fig_sensor_fit.py"
