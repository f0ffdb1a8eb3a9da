# The sensor's helpers (sensor.smk, tables.smk, figures.smk): its readings and bands, the film's
# tables and figure, the readings' targets. Included after common.smk.

# The sensor as built (sensor.smk): the readings config["sensor"]["band"] names, checked by the
# configuration (rodimpact.config.checks.check_sensor), and their cases' band files.
SENSOR = config.get("sensor", {})
SRC_SENSOR = sources("rodimpact.jobs.sensor_band", "rodimpact.jobs.logs")
SENSOR_READINGS = list(SENSOR.get("band", []))
SENSOR_READING_OF = {c["id"]: v for v in SENSOR_READINGS for c in PROJECT.cases.values() if c.get("variant") == v}


def sensor_variants(set_name):
    """A set's readings with the sensor as built (a stack on the rod) -> whether their law is
    calibrated by the continuum: its figure draws them on their rod's panel."""
    return {
        v: curve_rule_of(reading_cases(v)[0]) == "indentation"
        for v in READING_SETS[set_name]
        if all((c.get("contact") or {}).get("stack") for c in reading_cases(v))
    }


def sensor_band_files(variants, study="sensor_band"):
    """The band files of every case of the given readings (one directory per reading, by the rule
    sensor_band; ``study`` sensor_band_axes: with the constants' ranges by the continuum)."""
    return [
        f"results/studies/{study}/{reading}/{case}.h5"
        for v in variants
        for case, reading in SENSOR_READING_OF.items()
        if reading == v
    ]


def sensor_band_dirs(variants, study="sensor_band"):
    """The directories of the given readings' bands (rule sensor_band's outputs)."""
    return sorted({os.path.dirname(f) for f in sensor_band_files(variants, study)})


def sensor_targets():
    """The sensor's tables, when the configuration asks for them and their readings are built."""
    targets = []
    if not all(v in READING_SET_OF for v in SENSOR_READINGS):
        return targets
    if SENSOR_READINGS:
        targets += expand("results/tables/sensor_band.{ext}", ext=["csv", "md", "provenance.json"])
    return targets


# The sensor film (tables.smk, figures.smk): config["sensor"]'s film_table (one rod's readings by
# role, results/tables/{set}_film.*) and film_force (rows on readings, results/figures/film_force.*),
# when their readings are built; the cases whose law the continuum calibrates (one indentation
# curve each, results/tables/film_indentation.*).
FILM_TABLE = SENSOR.get("film_table") or {}
FILM_TABLE_SETS = (
    sorted({READING_SET_OF[v] for v in FILM_TABLE.values()})
    if all(v in READING_SET_OF for v in FILM_TABLE.values())
    else []
)
FILM_FORCE = SENSOR.get("film_force") or {}
# its runs: each row on each reading, by each of the methods the case runs
FILM_FORCE_RUNS = (
    [
        runs_of([case])[case["methods"].index(method)]
        for case in (
            PROJECT.cases[f"{row}-{variant}"]
            for row in FILM_FORCE.get("rows", [])
            for variant in FILM_FORCE.get("variants", [])
        )
        for method in FILM_FORCE["methods"]
        if method in case["methods"]
    ]
    if all(v in READING_SET_OF for v in FILM_FORCE.get("variants", []))
    else []
)
CALIBRATED_CASES = [
    c["id"] for name in READING_SETS for c in PROJECT.cases_in(name) if curve_rule_of(c) == "indentation"
]


def readings_targets():
    """Every reading set's tables and figure; the film's and the continuum's curves, where built."""
    targets = []
    for name, variants in READING_SETS.items():
        targets += expand(
            "results/tables/{set}_{variant}.{ext}",
            set=name,
            variant=variants,
            ext=["csv", "md", "tex", "provenance.json"],
        )
        targets += expand("results/tables/{set}_variants.{ext}", set=name, ext=["csv", "md", "provenance.json"])
        targets += expand(
            "results/figures/{set}_contact_time{part}.{ext}", set=name, part=["", "_readings"], ext=["pdf", "png"]
        )
    targets += expand("results/studies/film_band_{variant}.h5", variant=FILM_VARIANTS)
    tables = [
        *(f"{name}_film" for name in FILM_TABLE_SETS),
        *(["film_band"] if FILM_VARIANTS else []),
        *(["film_indentation"] if CALIBRATED_CASES else []),
    ]
    targets += expand("results/tables/{name}.{ext}", name=tables, ext=["csv", "md", "provenance.json"])
    if FILM_FORCE_RUNS:
        targets += expand("results/figures/film_force.{ext}", ext=["pdf", "png"])
    return targets
