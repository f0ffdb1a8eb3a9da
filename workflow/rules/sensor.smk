# The sensor as built (docs/sensor.md). For each case of the readings config["sensor"] names, the
# SEM with the law the continuum calibrates on the case's stack, over the stack's sourced ranges
# (results/studies/sensor_band/{case}.h5; a reading of the fit only gets its layer's thickness
# grid); then the bands' table and the inverse analysis, labelled as a fit.
SENSOR = config.get("sensor", {})
SENSOR_FIT = SENSOR.get("fit")
SRC_SENSOR = sources("rodimpact.jobs.sensor_band", "rodimpact.jobs.logs")
SRC_SENSOR_TABLES = sources("rodimpact.present.sensor_artifacts", "rodimpact.jobs.logs")


def _sensor_readings():
    """Reading -> whether its cases get the whole band (else the fit's grid only); the
    configuration checked them (rodimpact.config.checks.check_sensor)."""
    readings = {v: True for v in SENSOR.get("band", [])}
    for v in [SENSOR_FIT["reading"], *SENSOR_FIT.get("apply_to", [])] if SENSOR_FIT else []:
        readings.setdefault(v, False)
    return readings


SENSOR_READINGS = _sensor_readings()
SENSOR_READING_OF = {c["id"]: v for v in SENSOR_READINGS for c in PROJECT.cases.values() if c.get("variant") == v}
SENSOR_GRID = {f"{SENSOR_FIT['layer']}: thickness_m": SENSOR_FIT["thickness_grid_m"]} if SENSOR_FIT else {}


# The Table 2 readings with the sensor as built (a stack on the rod) -> whether their law is
# calibrated by the continuum: the Table 2 figure draws them on their rod's panel.
SENSOR_VARIANTS = {v: curve_rule_of(PROJECT.cases_in("table2", v)[0]) == "indentation" for v in TABLE2_VARIANTS
                   if all((c.get("contact") or {}).get("stack") for c in PROJECT.cases_in("table2", v))}


def sensor_band_files(variants):
    return [f"results/studies/sensor_band/{case}.h5" for v in variants for case, reading in SENSOR_READING_OF.items()
            if reading == v]


def sensor_targets():
    """The sensor's tables, when the configuration asks for them."""
    targets = []
    if any(SENSOR_READINGS.values()):
        targets += expand("results/tables/sensor_band.{ext}", ext=["csv", "md", "provenance.json"])
    if SENSOR_FIT:
        targets += expand("results/tables/sensor_fit.{ext}", ext=["csv", "md", "json", "provenance.json"])
        targets += expand("results/figures/sensor_fit.{ext}", ext=["pdf", "png", "provenance.json"])
    return targets


rule sensor_band:
    """The calibrated SEM over one case's sensor stack: its band, and the fit's thickness grid."""
    input:
        case=case_file(lambda w: w.case),
        code=SRC_SENSOR,
    output:
        h5="results/studies/sensor_band/{case}.h5",
    params:
        case=lambda w: PROJECT.cases[w.case],
        variant=lambda w: SENSOR_READING_OF[w.case],
        band=lambda w: SENSOR_READINGS[SENSOR_READING_OF[w.case]],
        grid=SENSOR_GRID,
        numerics=lambda w: config["numerics"]["fem_axi"],
    wildcard_constraints:
        case=one_of(SENSOR_READING_OF),
    log:
        "logs/studies/sensor_band/{case}.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/sensor_band.py"


rule sensor_band_table:
    """The sensor's band of every case of the band readings."""
    input:
        bands=sensor_band_files([v for v, band in SENSOR_READINGS.items() if band]),
        cases=[f"results/cases/{case}.yaml" for case, v in SENSOR_READING_OF.items() if SENSOR_READINGS[v]],
        code=SRC_SENSOR_TABLES,
    output:
        csv=report(
            "results/tables/sensor_band.csv",
            caption="../report/sensor_band.rst",
            category="Paper, Table 2",
            subcategory="The sensor as built",
            labels={"artifact": "The sensor's prediction band", "format": "CSV"},
        ),
        md="results/tables/sensor_band.md",
        html="results/tables/sensor_band.html",
        provenance="results/tables/sensor_band.provenance.json",
    log:
        "logs/tables/sensor_band.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/sensor_band_table.py"


rule sensor_fit:
    """The inverse analysis: one layer's thickness fitted to the measurements, with leave-one-out."""
    input:
        fitted=sensor_band_files([SENSOR_FIT["reading"]] if SENSOR_FIT else []),
        applied=sensor_band_files(SENSOR_FIT.get("apply_to", []) if SENSOR_FIT else []),
        cases=[f"results/cases/{c}.yaml" for c in SENSOR_READING_OF],
        code=SRC_SENSOR_TABLES,
    output:
        csv=report(
            "results/tables/sensor_fit.csv",
            caption="../report/sensor_fit.rst",
            category="Paper, Table 2",
            subcategory="The sensor as built",
            labels={"artifact": "A fit of the bond line", "format": "CSV"},
        ),
        md="results/tables/sensor_fit.md",
        html="results/tables/sensor_fit.html",
        summary="results/tables/sensor_fit.json",
        provenance="results/tables/sensor_fit.provenance.json",
    params:
        layer=SENSOR_FIT["layer"] if SENSOR_FIT else "",
    log:
        "logs/tables/sensor_fit.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/sensor_fit.py"


rule fig_sensor_fit:
    """The inverse analysis as a figure: measured, the sourced stack, the fitted one, the rows held out."""
    input:
        fitted=sensor_band_files([SENSOR_FIT["reading"]] if SENSOR_FIT else []),
        applied=sensor_band_files(SENSOR_FIT.get("apply_to", []) if SENSOR_FIT else []),
        cases=[f"results/cases/{c}.yaml" for c in SENSOR_READING_OF],
        code=SRC_SENSOR_TABLES,
    output:
        pdf=report(
            "results/figures/sensor_fit.pdf",
            caption="../report/sensor_fit_figure.rst",
            category="Paper, Table 2",
            subcategory="The sensor as built",
            labels={"artifact": "A fit of the bond line (figure)", "format": "PDF"},
        ),
        png=report(
            "results/figures/sensor_fit.png",
            caption="../report/sensor_fit_figure.rst",
            category="Paper, Table 2",
            subcategory="The sensor as built",
            labels={"artifact": "A fit of the bond line (figure)", "format": "PNG"},
        ),
        provenance="results/figures/sensor_fit.provenance.json",
    params:
        layer=SENSOR_FIT["layer"] if SENSOR_FIT else "",
        descriptions={v: spec.get("description", "") for v, spec in PROJECT.variants.get("table2", {}).items()},
    log:
        "logs/figures/sensor_fit.log",
    threads: 1
    resources:
        **PRESENTATION_RESOURCES,
    conda:
        "../envs/rodimpact.yaml"
    script:
        "../scripts/fig_sensor_fit.py"
