# Tables: read HDF5 runs only.


rule readings_table:
    """One reading of a set with variants against its measurements (for the paper's set: Table 2
    for one reading of the experiment's rod, with the published results its cases declare)."""
    input:
        runs=run_batches(lambda w: reading_runs(w.variant)),
    output:
        csv=report(
            "results/tables/{set}_{variant}.csv",
            caption="../report/table2.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Reading {variant}", "format": "CSV"},
        ),
        md="results/tables/{set}_{variant}.md",
        html="results/tables/{set}_{variant}.html",
        tex="results/tables/{set}_{variant}.tex",
        provenance="results/tables/{set}_{variant}.provenance.json",
    log:
        "logs/tables/{set}_{variant}.log",
    wildcard_constraints:
        set=one_of(READING_SETS),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.readings:make_readings_table"),
        runs=lambda w: reading_runs(w.variant),
        variant="{variant}",
        title=lambda w: set_title(w.set),
        reference=lambda w: PROJECT.compare.get(w.set, {}).get("reference", ""),
        published=lambda w: set_published(w.set),
    script:
        "../scripts/artifact.py"


rule readings_summary:
    """Mean and max error against the measurements per reading and method of a set with variants."""
    input:
        runs=run_batches(lambda w: set_reading_runs(w.set)),
    output:
        csv=report(
            "results/tables/{set}_variants.csv",
            caption="../report/table2_variants.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "Error per reading and method", "format": "CSV"},
        ),
        md="results/tables/{set}_variants.md",
        html="results/tables/{set}_variants.html",
        provenance="results/tables/{set}_variants.provenance.json",
    log:
        "logs/tables/{set}_variants.log",
    wildcard_constraints:
        set=one_of(READING_SETS),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.readings:make_readings_summary"),
        runs=lambda w: set_reading_runs(w.set),
        variants=lambda w: READING_SETS[w.set],
        published=lambda w: set_published(w.set),
    script:
        "../scripts/artifact.py"


# The sensor film: one rod's readings by role (config["sensor"]["film_table"]), side by side.
rule film_table:
    """One rod without and with the film (for the paper's set: Table 2 on the text's rod): every
    method, the calibrated law, the film's prediction band and the model-form error of the
    quasi-static contact."""
    input:
        runs=run_batches([run for v in FILM_TABLE.values() for run in reading_runs(v)] if FILM_TABLE_SETS else []),
        band=f"results/studies/film_band_{FILM_TABLE.get('film')}.h5",
        sensor_bands=sensor_band_dirs([v for v in [FILM_TABLE.get("sensor_calibrated")] if v in SENSOR_READINGS]),
    output:
        csv=report(
            "results/tables/{set}_film.csv",
            caption="../report/table2_film.rst",
            category="Comparison with measurements",
            subcategory="{set}",
            labels={"set": "{set}", "artifact": "With and without the film", "format": "CSV"},
        ),
        md="results/tables/{set}_film.md",
        html="results/tables/{set}_film.html",
        provenance="results/tables/{set}_film.provenance.json",
    log:
        "logs/tables/{set}_film.log",
    wildcard_constraints:
        set=one_of(FILM_TABLE_SETS),
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.film_tables:make_film_table"),
        sensor_bands=sensor_band_files([v for v in [FILM_TABLE.get("sensor_calibrated")] if v in SENSOR_READINGS]),
        runs=[run for v in FILM_TABLE.values() for run in reading_runs(v)] if FILM_TABLE_SETS else [],
        variants=FILM_TABLE,
    script:
        "../scripts/artifact.py"


rule film_band_table:
    """The film's prediction band of every case of every reading with the film."""
    input:
        bands=expand("results/studies/film_band_{variant}.h5", variant=FILM_VARIANTS),
        case_files=sorted({case_file_of(c["id"]) for v in FILM_VARIANTS for c in reading_cases(v)}),
    output:
        csv=report(
            "results/tables/film_band.csv",
            caption="../report/film_band.rst",
            category="The experiment's sensor",
            subcategory="The sensor film",
            labels={"artifact": "The film's prediction bands", "format": "CSV"},
        ),
        md="results/tables/film_band.md",
        html="results/tables/film_band.html",
        provenance="results/tables/film_band.provenance.json",
    log:
        "logs/tables/film_band.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.film_tables:make_film_band_table"),
        variants=FILM_VARIANTS,
    script:
        "../scripts/artifact.py"


rule film_band_axes_table:
    """Each constant of the film along its range, per case of every reading with the film, and
    whether the time is monotone along it (make film-axes)."""
    input:
        bands=expand("results/studies/film_band_axes_{variant}.h5", variant=FILM_VARIANTS),
        case_files=sorted({case_file_of(c["id"]) for v in FILM_VARIANTS for c in reading_cases(v)}),
    output:
        csv="results/tables/film_band_axes.csv",
        md="results/tables/film_band_axes.md",
        html="results/tables/film_band_axes.html",
        provenance="results/tables/film_band_axes.provenance.json",
    log:
        "logs/tables/film_band_axes.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.sensor_tables:make_axes_table"),
        variants=FILM_VARIANTS,
        kind="film",
    script:
        "../scripts/artifact.py"


rule film_indentation_table:
    """The continuum's indentation curves (the calibrated laws) against the analytic laws."""
    input:
        curves=sorted({os.path.dirname(curve_file_of(PROJECT.cases[c])) for c in CALIBRATED_CASES}),
    output:
        csv=report(
            "results/tables/film_indentation.csv",
            caption="../report/film_indentation.rst",
            category="The experiment's sensor",
            subcategory="The sensor film",
            labels={"artifact": "Indentation by the continuum against the analytic laws", "format": "CSV"},
        ),
        md="results/tables/film_indentation.md",
        html="results/tables/film_indentation.html",
        provenance="results/tables/film_indentation.provenance.json",
    log:
        "logs/tables/film_indentation.log",
    localrule: True
    conda:
        "../envs/rodimpact.yaml"
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    params:
        **presentation("rodimpact.present.film_tables:make_film_indentation_table"),
        curves=[curve_file_of(PROJECT.cases[c]) for c in CALIBRATED_CASES],
        cases=CALIBRATED_CASES,
    script:
        "../scripts/artifact.py"


default_target(readings_targets)
