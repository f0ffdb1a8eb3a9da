# The comparisons' helpers (compare.smk): the compared sets' runs and measured records, and
# their targets. Included after common.smk.


def compare_runs(set_name):
    """The runs of a set's cases that carry measurements."""
    return runs_of(measured_cases(PROJECT.cases_in(set_name)))


# record figure's ending (force, strain, velocity) -> the compared sets with such a record (compare.smk)
SIGNAL_SETS = {
    ending: [
        name for name in COMPARE_SETS if any(c["measured"].get(key) for c in measured_cases(PROJECT.cases_in(name)))
    ]
    for ending, key in SIGNAL_RECORDS.items()
}


def compare_histories(set_name):
    """The measured records of a set's cases (inputs: a changed record reruns the comparison)."""
    return sorted(
        {
            c["measured"][key]["path"]
            for c in measured_cases(PROJECT.cases_in(set_name))
            for key in RECORDS
            if c["measured"].get(key)
        }
    )


def signal_runs(set_name, ending):
    """The runs of a set's cases with a measured record of the kind ``ending`` names."""
    key = SIGNAL_RECORDS[ending]
    if set_name not in SIGNAL_SETS[ending]:
        refuse(
            f"set {set_name!r} has no measured {key}; sets that have one: "
            f"{', '.join(SIGNAL_SETS[ending]) or 'none'}"
        )
    return runs_of([c for c in measured_cases(PROJECT.cases_in(set_name)) if c["measured"].get(key)])


def compare_targets():
    """The comparison of every compared set: its table, its figure, a figure per kind of record it measures."""
    targets = expand(
        "results/tables/compare_{set}.{ext}", set=COMPARE_SETS, ext=["csv", "md", "html", "tex", "provenance.json"]
    )
    targets += expand("results/figures/compare_{set}.{ext}", set=COMPARE_SETS, ext=["pdf", "png"])
    targets += [
        f"results/figures/compare_{s}_{ending}.{ext}"
        for ending, sets in SIGNAL_SETS.items()
        for s in sets
        for ext in ("pdf", "png")
    ]
    return targets


# The calibrated sets (calibrate.smk): the compared sets whose case file declares `calibrate:`.
CALIBRATED_SETS = [name for name in COMPARE_SETS if name in PROJECT.calibrate]
SRC_CALIBRATE = ("rodimpact.jobs.calibrate", "rodimpact.jobs.logs")


def calibration_sources(wildcards):
    """Params function: the code digest of a set's calibration: its job, its method's solver and,
    where a rule computes its cases' law's curve (again at every trial), that code (CURVE_CODE)."""
    rules = sorted({curve_rule_of(c) for c in calibration_cases_of(wildcards.set)} - {None})
    method = PROJECT.calibrate[wildcards.set]["method"]
    return sources(
        *SRC_CALIBRATE, METHOD_REGISTRY[method].solver_module, *(module for r in rules for module in CURVE_CODE[r])
    )


def calibration_cases_of(set_name):
    """The cases a set's calibration runs: those it fits (giving one of its quantities), then
    those it predicts at the fitted constants (its apply_to)."""
    cases, block = PROJECT.cases_in(set_name), PROJECT.calibrate[set_name]
    return [*calibration_cases(cases, block), *applied_cases(cases, block)]


def calibration_curves(set_name):
    """Case id -> the curve file its runs take, for the cases of a set's calibration whose law a
    rule's curve calibrates (read by the calibration at the cases' own constants)."""
    return {c["id"]: curve_file_of(c) for c in calibration_cases_of(set_name) if curve_rule_of(c)}


def calibration_resources():
    """A calibration job's resources: its method's runs of every case, each repeated once per
    value of a grid, or as often as a fit and its leave-one-out are expected to evaluate it
    (expected_evaluations); with its law's curve computed as often, where a rule computes one."""

    def estimate(set_name):
        block = PROJECT.calibrate[set_name]
        cases = calibration_cases_of(set_name)
        fitted = calibration_cases(PROJECT.cases_in(set_name), block)
        grid = next((p["grid"] for p in block["parameters"] if p.get("grid")), None)
        repeats = len(grid) if grid else expected_evaluations(len(block["parameters"]), len(fitted))
        runs = [(with_method(c, block["method"], config["numerics"]), block["method"], repeats) for c in cases]
        curves = [
            curve_cost({"case": c, "curve": {"rule": curve_rule_of(c), "settings": CURVE_SETTINGS[curve_rule_of(c)]}})
            for c in cases
            if curve_rule_of(c) is not None
        ]
        return estimate_sequence(runs, extra=curves * repeats)

    return _resources(lambda w: estimate(w.set))


def calibration_targets():
    """Each calibrated set's tables and figure."""
    return [
        f"results/{kind}/calibration_{name}{ending}"
        for name in CALIBRATED_SETS
        for kind, ending in (
            ("tables", ".csv"),
            ("tables", "_parameters.csv"),
            ("tables", ".md"),
            ("tables", ".html"),
            ("tables", ".provenance.json"),
            ("figures", ".pdf"),
            ("figures", ".png"),
        )
    ]
