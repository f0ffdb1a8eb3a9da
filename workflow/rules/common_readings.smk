# The case sets compared with their measurements and their readings: which sets, which readings,
# and what the tables, figures and bands of a reading read. Included right after common.smk (its
# PROJECT, runs_of and law_of); the files after it use these at parse time.

# The case sets compared with their measurements (compare.smk): every target set that has cases
# with something measured, whatever its name.
COMPARE_SETS = [name for name in config["targets"]["sets"] if measured_cases(PROJECT.cases_in(name))]
# Those with variants (readings of one experiment) -> their readings: each set gets its readings'
# tables and figure (tables.smk, figures.smk: results/tables/{set}_{variant}.*, {set}_variants.*,
# results/figures/{set}_contact_time.*); the columns a case declares (published results, a film's
# law) are the ones these show. A reading's name is unique over all sets (the loader checks).
READING_SETS = {name: list(PROJECT.variants[name]) for name in COMPARE_SETS if PROJECT.variants.get(name)}
READING_SET_OF = {v: name for name, variants in READING_SETS.items() for v in variants}
# the names that end the other files of a set ({set}_variants, {set}_film, {set}_contact_time)
_TAKEN = sorted(set(READING_SET_OF) & {"variants", "film", "contact_time"})
if _TAKEN:
    sys.exit(
        f"rodimpact: case set {READING_SET_OF[_TAKEN[0]]!r}: a variant may not be named {_TAKEN[0]!r} "
        "(the name of another of its set's files)"
    )


def reading_cases(variant):
    """The cases of one reading (a variant of a set of READING_SETS)."""
    return PROJECT.cases_in(READING_SET_OF[variant], variant)


def reading_runs(variant):
    return runs_of(reading_cases(variant))


def set_reading_runs(set_name):
    """The runs of every reading of a set, reading by reading."""
    return [run for v in READING_SETS[set_name] for run in reading_runs(v)]


def set_title(set_name):
    """A set as captions name it: its compare.title, else "case set <name>"."""
    return PROJECT.compare.get(set_name, {}).get("title", f"case set {set_name}")


def set_published(set_name):
    """Whether a set's cases declare published results (the paper's: its captions say so)."""
    return any(c.get("published") for c in PROJECT.cases_in(set_name))


# each reading in words (its case file's description): the panels' titles
READING_DESCRIPTIONS = {
    v: spec.get("description", "") for name in READING_SETS for v, spec in PROJECT.variants[name].items()
}
# The readings whose cases' law needs a film (the law declares it: needs.film): each gets its
# prediction band over the film's ranges.
FILM_VARIANTS = [v for v in READING_SET_OF if all(law_of(c.get("contact")).needs.film for c in reading_cases(v))]


wildcard_constraints:
    variant=one_of(READING_SET_OF),
