# The comparisons' helpers (compare.smk): the compared sets' runs and measured force histories,
# and their targets. Included after common.smk.

# The cases of the compared sets (COMPARE_SETS) with a measured force history (compare.smk).
SRC_COMPARE = sources("rodimpact.present.compare_artifacts", "rodimpact.jobs.logs")
HISTORY_CASES = {
    c["id"]: name
    for name in COMPARE_SETS
    for c in measured_cases(PROJECT.cases_in(name))
    if c["measured"].get("force_history")
}


def compare_runs(set_name):
    """The runs of a set's cases that carry measurements."""
    return runs_of(measured_cases(PROJECT.cases_in(set_name)))


def compare_histories(set_name):
    """The measured force histories of a set's cases (inputs: a changed record reruns the comparison)."""
    return sorted(
        {
            c["measured"]["force_history"]["path"]
            for c in measured_cases(PROJECT.cases_in(set_name))
            if c["measured"].get("force_history")
        }
    )


def compare_case_runs(set_name, case_id):
    """The runs of one case with a measured force history, of the set that holds it."""
    if HISTORY_CASES.get(case_id) != set_name:
        refuse(
            f"case {case_id!r} has no measured force history in set {set_name!r}; cases that have one: "
            f"{', '.join(f'{c} ({s})' for c, s in HISTORY_CASES.items()) or 'none'}"
        )
    return runs_of([PROJECT.cases[case_id]])


def compare_targets():
    """The comparison of every compared set: its table, its figure, a figure per measured history."""
    targets = expand(
        "results/tables/compare_{set}.{ext}", set=COMPARE_SETS, ext=["csv", "md", "html", "tex", "provenance.json"]
    )
    targets += expand("results/figures/compare_{set}.{ext}", set=COMPARE_SETS, ext=["pdf", "png"])
    targets += [f"results/figures/compare_{s}_{c}.{ext}" for c, s in HISTORY_CASES.items() for ext in ("pdf", "png")]
    return targets
