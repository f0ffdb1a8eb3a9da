# The studies' helpers (studies.smk, sweeps.smk): the error-against-run-time levels, the stress
# runs and the stability map, the sweeps' points. Included after common.smk, whose names it uses.

WORK_PRECISION = config.get("work_precision", {})
STABILITY = config.get("stability", {})
MAP = STABILITY.get("map", {})


def work_precision_study(methods=None):
    """What the error-against-run-time tables and figures read of the study (config.yaml
    work_precision): its methods' settings (of ``methods``, default all), the levels fitted, the
    arrival window and the expectations per case."""
    names = list(WORK_PRECISION.get("methods", {})) if methods is None else list(methods)
    return {
        "methods": {m: WORK_PRECISION["methods"][m] for m in names},
        "fit_levels": WORK_PRECISION.get("fit_levels", 4),
        "arrival_window": WORK_PRECISION.get("arrival_window"),
        "per_case": WORK_PRECISION.get("per_case", {}),
    }


MAP_POINTS = map_point_names(MAP) if MAP else []


def stress_batches():
    """Every batch of the stress study, by its keys (the solve_stress rule), each set by each method
    some case of it lists, and by ``reference``."""
    return [
        (name, m)
        for name in STABILITY.get("sets", [])
        for m in [*METHOD_REGISTRY, "reference"]
        if m == "reference" or any(m in c["methods"] for c in PROJECT.cases_in(name))
    ]


def stress_runs(reference):
    """The stress study's runs: every method on every case of each set (``reference`` False),
    or each case's sem reference (True), in the order of the sets' cases and methods."""
    return [
        run_in_batch("solve_stress", (name, m), c["id"])
        for name in STABILITY.get("sets", [])
        for c in PROJECT.cases_in(name)
        for m in (["reference"] if reference else c["methods"])
    ]


def map_runs(methods):
    """The stability map's runs of every point by each of ``methods`` (or ``reference``), point by point."""
    return [run_in_batch("solve_map", (m,), p) for p in MAP_POINTS for m in methods]


def map_files():
    """The files of the stability map's parts, of every method and the reference."""
    return [f for m in [*MAP.get("methods", []), "reference"] for f in part_files("solve_map", (m,))] if MAP else []


# The cases that ask for the strain over the rod (output strain_field): each gets its wave map
# (waves.smk), and only they.
WAVE_CASES = [case_id for case_id, case in PROJECT.cases.items() if FIELD_OUTPUT in case["outputs"]]


def sweep_level(method, level):
    """Numerics overrides of one level of the method's work-precision sweep."""
    levels = WORK_PRECISION.get("methods", {}).get(method, {}).get("levels", [])
    if not 0 <= level < len(levels):
        refuse(f"no level {level} in the work-precision sweep of {method!r}; its levels: 0 to {len(levels) - 1}")
    return dict(levels[level])


def swept_on(case_id):
    """The methods the work-precision study sweeps on a case (rodimpact.config.checks.swept_methods)."""
    if case_id not in PROJECT.cases:
        refuse(f"unknown case {case_id!r}; known: {', '.join(PROJECT.cases)}")
    return swept_methods(WORK_PRECISION, case_id, PROJECT.cases[case_id])


def sweep_case(case_id, method, level):
    """The case of one sweep level (the method need not be among the case's own, but the study
    must sweep it on the case)."""
    if method not in swept_on(case_id):
        refuse(
            f"the work-precision study does not sweep {method!r} on case {case_id!r}; it sweeps "
            f"{', '.join(swept_on(case_id))}"
        )
    return level_case(PROJECT.cases[case_id], method, config["numerics"], sweep_level(method, level))


def _swept(cases=None, methods=None):
    """(case, method, levels) of every method the study sweeps on each of ``cases`` (default: the
    default build's), of ``methods`` only when given."""
    cases = WORK_PRECISION.get("cases", []) if cases is None else cases
    swept = WORK_PRECISION.get("methods", {})
    return [(c, m, len(swept[m]["levels"])) for c in cases for m in swept_on(c) if methods is None or m in methods]


def level_files(cases=None, methods=None):
    """The files of the work-precision levels (the solve_levels rule) of :func:`_swept`'s cases and methods."""
    return [f for c, m, _ in _swept(cases, methods) for f in part_files("solve_levels", (c, m))]


def level_runs(cases=None, methods=None):
    """Every level of :func:`_swept`'s cases and methods, each ``part{k}.h5#level{i}``."""
    return [run for c, m, _ in _swept(cases, methods) for run in runs_in_batch("solve_levels", (c, m))]


# The sweep's cases too slow for the default build (a level over a minute): their own target.
WORK_PRECISION_SEPARATE = WORK_PRECISION.get("separate") or {}


# One Paramspace per sweep case: its grid, and the names of its points (a group each in its part's
# file); and each point's values by its name (the Paramspace's rows are the grid's points, in order).
SWEEPS = {
    case_id: Paramspace(sweep_frame(case["sweep"]), filename_params="*", single_wildcard="sweep_point")
    for case_id, case in PROJECT.sweeps.items()
}
SWEEP_POINTS = {
    case_id: dict(zip(space.instance_patterns, sweep_points(PROJECT.sweeps[case_id]["sweep"])))
    for case_id, space in SWEEPS.items()
}


def sweep_part_files(sweep_cases):
    """The files of the given sweep cases' parts, of every method (one job each: rule solve_sweep)."""
    return [f for c in sweep_cases for m in c["sweep"]["methods"] for f in part_files("solve_sweep", (c["id"], m))]


def sweep_point_runs(sweep_cases):
    """The runs of every point and method of the given sweep cases, in the grid's order: each
    ``part{k}.h5#{point}`` in its part's file."""
    return [
        run for c in sweep_cases for m in c["sweep"]["methods"] for run in runs_in_batch("solve_sweep", (c["id"], m))
    ]


def study_targets():
    """The error-against-run-time study (its table, orders and figures), the stress cases' table and
    the stability map, each when config.yaml asks for it."""
    targets = []
    if WORK_PRECISION:
        targets += ["results/tables/work_precision.csv", "results/tables/work_precision_orders.md"]
        targets += expand(
            "results/figures/work_precision_{case}.{ext}", case=WORK_PRECISION["cases"], ext=["pdf", "png"]
        )
    if STABILITY:
        targets += ["results/tables/stability.csv"]
    if MAP:
        targets += expand("results/figures/stability_map.{ext}", ext=["pdf", "png"])
    return targets
