# Validation of the configuration (before any job), and the helpers the rules share.
import sys
from pathlib import Path

from snakemake.utils import validate

from rodimpact.config import METHODS, ConfigError, load_project

validate(config, "../schemas/config.schema.yaml")
try:
    PROJECT = load_project(config, root=workflow.basedir)
except ConfigError as error:
    sys.exit(f"rodimpact: invalid configuration: {error}")

# Rules that import rodimpact list its sources as inputs: a code change reruns them.
SRC = sorted(str(p.relative_to(workflow.basedir)) for p in Path(workflow.basedir, "src/rodimpact").rglob("*.py"))
TABLE2_VARIANTS = list(PROJECT.variants.get("table2", {}))


wildcard_constraints:
    case="[A-Za-z0-9][A-Za-z0-9_.\-]*",
    method="|".join(METHODS),
    variant="|".join(TABLE2_VARIANTS) or "no-variant",


def runs_of(cases):
    """HDF5 files of every method of every case in ``cases``."""
    return [f"results/runs/{c['id']}/{m}.h5" for c in cases for m in c["methods"]]


def case_of_run(wildcards):
    """The resolved case of a run; refuses a method the case does not list."""
    case = PROJECT.cases.get(wildcards.case)
    if case is None:
        raise ValueError(f"unknown case {wildcards.case!r}; known: {sorted(PROJECT.cases)}")
    if wildcards.method not in case["methods"]:
        raise ValueError(f"case {wildcards.case!r} does not run {wildcards.method!r} (methods: {case['methods']})")
    return case


def table2_runs(variant):
    return runs_of(PROJECT.cases_in("table2", variant))


def default_targets():
    sets = config["targets"]["sets"]
    targets = []
    if "model" in sets:
        targets += expand("results/figures/fig2_contact_force.{ext}", ext=["pdf", "png"])
    if "table2" in sets:
        targets += expand("results/tables/table2_{variant}.{ext}", variant=TABLE2_VARIANTS,
                          ext=["csv", "md", "tex", "provenance.json"])
        targets += ["results/tables/table2_variants.csv"]
        targets += expand("results/figures/table2_contact_time.{ext}", ext=["pdf", "png"])
    for name in sets:
        targets += runs_of(PROJECT.cases_in(name))
    return targets
