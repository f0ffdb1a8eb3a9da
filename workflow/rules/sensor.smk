# The sensor as built (docs/sensor.md). For each case of the readings config["sensor"]["band"]
# names, the SEM with the law the continuum calibrates on the case's stack, over the stack's
# sourced ranges (results/studies/sensor_band/{variant}/{case}.h5); then the bands' table. The
# same bands with each constant's range by the continuum (sensor_band_axes: the evidence that the
# corners bound the time) are the named target make sensor-axes, not the default build.
rule sensor_band:
    """The calibrated SEM over the sensor stack of each case of one reading: its band (with
    sensor_band_axes, also each constant's range by the continuum); one file per case,
    results/studies/{study}/{variant}/{case}.h5."""
    input:
        case=lambda w: case_file_of(reading_cases(w.variant)[0]["id"]),
        # the nominal stacks' calibrated laws: the curves the cases' own runs take
        curves=lambda w: sorted({os.path.dirname(curve_file_of(c)) for c in reading_cases(w.variant)}),
    output:
        bands=directory("results/studies/{study}/{variant}"),
    log:
        "logs/studies/{study}/{variant}.log",
    wildcard_constraints:
        study="sensor_band|sensor_band_axes",
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
        axes=lambda w: w.study == "sensor_band_axes",
    script:
        "../scripts/sensor_band.py"


rule sensor_band_table:
    """The sensor's band of every case of the band readings."""
    input:
        bands=sensor_band_dirs(SENSOR_READINGS),
        case_files=sorted({case_file_of(case) for case in SENSOR_READING_OF}),
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
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.sensor_tables:make_sensor_band_table"),
        bands=sensor_band_files(SENSOR_READINGS),
    script:
        "../scripts/artifact.py"


rule sensor_band_axes_table:
    """Each constant of the sensor stack along its range by the continuum, per case of the band
    readings, and whether the time is monotone and lengthens at the ends the band takes (make
    sensor-axes)."""
    input:
        bands=sensor_band_dirs(SENSOR_READINGS, "sensor_band_axes"),
        case_files=sorted({case_file_of(case) for case in SENSOR_READING_OF}),
    output:
        csv="results/tables/sensor_band_axes.csv",
        md="results/tables/sensor_band_axes.md",
        html="results/tables/sensor_band_axes.html",
        provenance="results/tables/sensor_band_axes.provenance.json",
    log:
        "logs/tables/sensor_band_axes.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.sensor_tables:make_axes_table"),
        bands=sensor_band_files(SENSOR_READINGS, "sensor_band_axes"),
        kind="sensor",
    script:
        "../scripts/artifact.py"


default_target(sensor_targets)
