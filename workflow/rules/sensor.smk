# The sensor as built (docs/sensor.md). For each case of the readings config["sensor"]["band"]
# names, the SEM with the law the continuum calibrates on the case's stack, over the stack's
# sourced ranges (results/studies/sensor_band/{variant}/{case}.h5); then the bands' table.
rule sensor_band:
    """The calibrated SEM over the sensor stack of each case of one reading: its band; one file
    per case, results/studies/sensor_band/{variant}/{case}.h5."""
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
        numerics=lambda w: config["numerics"]["fem_axi"],
    script:
        "../scripts/sensor_band.py"


rule sensor_band_table:
    """The sensor's band of every case of the band readings."""
    input:
        bands=sensor_band_dirs(SENSOR_READINGS),
        cases=sorted({case_file_of(case) for case in SENSOR_READING_OF}),
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
        bands=sensor_band_files(SENSOR_READINGS),
    script:
        "../scripts/sensor_band_table.py"
