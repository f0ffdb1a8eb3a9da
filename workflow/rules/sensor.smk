# The sensor as built (docs/sensor.md). For each case of the readings config["sensor"] names, the
# SEM with the law the continuum calibrates on the case's stack, over the stack's sourced ranges
# (results/studies/sensor_band/{case}.h5; a reading of the fit only gets its layer's thickness
# grid); then the bands' table and the inverse analysis, labelled as a fit.
SENSOR = config.get("sensor", {})
SENSOR_FIT = SENSOR.get("fit")
SRC_SENSOR = sources("rodimpact.jobs.sensor_band", "rodimpact.jobs.logs")
SRC_SENSOR_TABLES = sources("rodimpact.present.sensor_artifacts", "rodimpact.jobs.logs")


def _sensor_readings():
    """Reading -> whether its cases get the whole band (else the fit's grid only); each checked."""
    named = [(f"sensor.band[{i}]", v, True) for i, v in enumerate(SENSOR.get("band", []))]
    if SENSOR_FIT:
        named.append(("sensor.fit.reading", SENSOR_FIT["reading"], False))
        named += [(f"sensor.fit.apply_to[{i}]", v, False) for i, v in enumerate(SENSOR_FIT.get("apply_to", []))]
    readings = {}
    for field, variant, band in named:
        cases = PROJECT.cases_in("table2", variant) if variant in TABLE2_VARIANTS else []
        if not cases:
            refuse(f"config/config.yaml: field '{field}': {variant!r} is not a Table 2 reading; readings: "
                   f"{', '.join(TABLE2_VARIANTS)}")
        if not all(curve_rule_of(c) == "indentation" and (c.get("contact") or {}).get("stack") for c in cases):
            refuse(f"config/config.yaml: field '{field}': the reading {variant!r} needs a law calibrated by the "
                   "continuum (from: fem_axi_indentation) on a stack (contact.stack)")
        if SENSOR_FIT and not any(layer["name"] == SENSOR_FIT["layer"] for layer in cases[0]["contact"]["stack"]["layers"]):
            refuse(f"config/config.yaml: field 'sensor.fit.layer': the stack of {variant!r} has no layer named "
                   f"{SENSOR_FIT['layer']!r}")
        readings[variant] = readings.get(variant, False) or band
    return readings


SENSOR_READINGS = _sensor_readings()
SENSOR_READING_OF = {c["id"]: v for v in SENSOR_READINGS for c in PROJECT.cases_in("table2", v)}
SENSOR_GRID = {f"{SENSOR_FIT['layer']}: thickness_m": SENSOR_FIT["thickness_grid_m"]} if SENSOR_FIT else {}


# The Table 2 readings with the sensor as built (a stack on the rod) -> whether their law is
# calibrated by the continuum: the Table 2 figure draws them on their rod's panel.
SENSOR_VARIANTS = {v: curve_rule_of(PROJECT.cases_in("table2", v)[0]) == "indentation" for v in TABLE2_VARIANTS
                   if all((c.get("contact") or {}).get("stack") for c in PROJECT.cases_in("table2", v))}


def sensor_band_files(variants):
    return [f"results/studies/sensor_band/{c['id']}.h5" for v in variants for c in PROJECT.cases_in("table2", v)]


def sensor_targets():
    """The sensor's tables, when the configuration asks for them."""
    targets = []
    if any(SENSOR_READINGS.values()):
        targets += expand("results/tables/sensor_band.{ext}", ext=["csv", "md", "provenance.json"])
    if SENSOR_FIT:
        targets += expand("results/tables/sensor_fit.{ext}", ext=["csv", "md", "json", "provenance.json"])
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
        cases=[f"results/cases/{c['id']}.yaml" for v, band in SENSOR_READINGS.items() if band
               for c in PROJECT.cases_in("table2", v)],
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
