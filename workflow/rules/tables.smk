# Tables: read HDF5 runs only.


rule table2:
    """Table 2 of the paper for one reading of the experiment's rod geometry."""
    input:
        runs=lambda w: table2_runs(w.variant),
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/table2_{variant}.csv",
            caption="../report/table2.rst",
            category="Paper, Table 2",
            subcategory="{variant}",
            labels={"artifact": "Table 2, rod reading {variant}", "format": "CSV"},
        ),
        md="results/tables/table2_{variant}.md",
        html="results/tables/table2_{variant}.html",
        tex="results/tables/table2_{variant}.tex",
        provenance="results/tables/table2_{variant}.provenance.json",
    params:
        variant="{variant}",
    log:
        "logs/tables/table2_{variant}.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/table2.py"


rule table2_variants:
    """Mean and max error against the measurements per geometry variant and method."""
    input:
        runs=[run for v in TABLE2_VARIANTS for run in table2_runs(v)],
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/table2_variants.csv",
            caption="../report/table2_variants.rst",
            category="Paper, Table 2",
            subcategory="All readings",
            labels={"artifact": "Error per reading and method", "format": "CSV"},
        ),
        md="results/tables/table2_variants.md",
        html="results/tables/table2_variants.html",
        provenance="results/tables/table2_variants.provenance.json",
    params:
        variants=TABLE2_VARIANTS,
    log:
        "logs/tables/table2_variants.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/table2_variants.py"


rule fig2_comparison:
    """Fig. 2's numbers: contact time and maxima per method against the SEM and the paper's."""
    input:
        runs=lambda w: runs_of([PROJECT.cases["model"]]),
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/fig2_comparison.csv",
            caption="../report/fig2_comparison.rst",
            category="Paper, Fig. 2 and Fig. 4",
            subcategory="Fig. 2",
            labels={"artifact": "Fig. 2 in numbers", "format": "CSV"},
        ),
        md="results/tables/fig2_comparison.md",
        html="results/tables/fig2_comparison.html",
        provenance="results/tables/fig2_comparison.provenance.json",
    log:
        "logs/tables/fig2_comparison.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig2_comparison.py"


# The sensor film. The text's rod by role: without the film (Hertz), with it (the thin-layer law;
# fem_axi's bonded film), with the law calibrated by the continuum, with and without the film,
# and with the sensor as built (fem_axi's bonded layers; the law calibrated on them).
TEXT_ROD_READINGS = {role: variant for role, variant in (
    ("no_film", "r10_l30"), ("film", "r10_l30_film"), ("film_calibrated", "r10_l30_film_cal"),
    ("no_film_calibrated", "r10_l30_cal"), ("sensor", "r10_l30_sensor"),
    ("sensor_calibrated", "r10_l30_sensor_cal")) if variant in TABLE2_VARIANTS}
# The Table 2 cases whose law the continuum calibrates: one indentation curve each.
CALIBRATED_CASES = [c["id"] for c in PROJECT.cases_in("table2") if curve_rule_of(c) == "indentation"]


rule table2_film:
    """Table 2 on the text's rod without and with the film: every method, the calibrated law,
    the film's prediction band and the model-form error of the quasi-static contact."""
    input:
        runs=[run for v in TEXT_ROD_READINGS.values() for run in table2_runs(v)],
        band=f"results/studies/film_band_{TEXT_ROD_READINGS.get('film')}.h5",
        sensor_bands=sensor_band_files([v for v in [TEXT_ROD_READINGS.get("sensor_calibrated")]
                                        if SENSOR_READINGS.get(v)]),
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/table2_film.csv",
            caption="../report/table2_film.rst",
            category="Paper, Table 2",
            subcategory="The sensor film",
            labels={"artifact": "Table 2 with and without the film", "format": "CSV"},
        ),
        md="results/tables/table2_film.md",
        html="results/tables/table2_film.html",
        provenance="results/tables/table2_film.provenance.json",
    params:
        variants=TEXT_ROD_READINGS,
    log:
        "logs/tables/table2_film.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/table2_film.py"


rule film_band_table:
    """The film's prediction band of every case of every reading with the film."""
    input:
        bands=expand("results/studies/film_band_{variant}.h5", variant=FILM_VARIANTS),
        cases=[f"results/cases/{c['id']}.yaml" for v in FILM_VARIANTS for c in PROJECT.cases_in("table2", v)],
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/film_band.csv",
            caption="../report/film_band.rst",
            category="Paper, Table 2",
            subcategory="The sensor film",
            labels={"artifact": "The film's prediction bands", "format": "CSV"},
        ),
        md="results/tables/film_band.md",
        html="results/tables/film_band.html",
        provenance="results/tables/film_band.provenance.json",
    params:
        variants=FILM_VARIANTS,
    log:
        "logs/tables/film_band.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/film_band_table.py"


rule film_indentation_table:
    """The continuum's indentation curves (the calibrated laws) against the analytic laws."""
    input:
        curves=expand("results/indentation/{case}.h5", case=CALIBRATED_CASES),
        code=SRC_PRESENT,
    output:
        csv=report(
            "results/tables/film_indentation.csv",
            caption="../report/film_indentation.rst",
            category="Paper, Table 2",
            subcategory="The sensor film",
            labels={"artifact": "Indentation by the continuum against the analytic laws", "format": "CSV"},
        ),
        md="results/tables/film_indentation.md",
        html="results/tables/film_indentation.html",
        provenance="results/tables/film_indentation.provenance.json",
    params:
        cases=CALIBRATED_CASES,
    log:
        "logs/tables/film_indentation.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/film_indentation_table.py"
