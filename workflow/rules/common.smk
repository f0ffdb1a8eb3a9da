# Two mechanisms of this file, each against what snakemake does on its own:
#
# refuse(): sys.exit from input functions (and from checked_project at parse time).
#   What snakemake does: an Exception raised in an input function is caught by
#   snakemake.rules.Rule.apply_input_function and re-raised as InputFunctionException, printed
#   over several lines (Error, Wildcards, Traceback); an Exception while this file is parsed is
#   printed with its file and line. SystemExit is not an Exception: it passes both and the
#   CLI's `except Exception` (snakemake.cli.main), and Python prints its message as the last
#   line of the run, exit status 1, before any job.
#   Why not enough: a target or wildcard the configuration does not define must stop planning
#   in one line naming the case, method or level (docs/faults.md). An input function may refuse,
#   a resource function may not: Rule.expand_resources catches BaseException and wraps it; the
#   rules' resources call the same per_job functions, after their inputs have been evaluated.
#   If snakemake changes (catches BaseException in input functions or around the parse): the
#   refusals get several lines and a traceback; tests/test_faults.py::
#   test_a_target_the_configuration_does_not_define_is_one_line and tests/test_workflow_errors.py::
#   test_bad_input_stops_before_any_job fail.
#
# RATE: snakemake's job rate limiter, dropped when a local run's jobs start.
#   What snakemake does: its CLI's default --max-jobs-per-timespan, 100/1s, re-arms a
#   threading.Timer of the timespan after every scheduling round
#   (JobScheduler._schedule_reevalutation). Every timer starts a round of its own when it fires
#   and arms the next, so the rounds multiply with the jobs that finish, and each round
#   re-evaluates the ready jobs' params and resources on snakemake's own core; the timers are not
#   daemon threads, so the last one holds the process up to the timespan after the run. No
#   setting turns the limiter off from the command line or a profile (a shorter timespan only
#   fires the rounds faster, a longer one holds the process longer); the API's default, no
#   limiter, arms none.
#   What it pays: the small build of .test/ (79 jobs, snakemake -j2 --directory .test from an
#   empty results/) takes 1.16 times as long without this (133 s against 115 s, medians of three
#   pairs run in turn; docs/studies.md, "Planning and scheduling", gives the command).
#   A run that submits to a cluster keeps the limiter (there it spaces the submissions), and a
#   cluster job's snakemake (--mode remote, no hooks) keeps its default.
#   If snakemake changes (renames the scheduler's attribute): local runs take longer again,
#   never differently; tests/test_plumbing.py::test_no_timer_outlives_a_local_run fails.

# Validation of the configuration (before any job), and the helpers the rules share.
# (SRC_DIR is on the path: preflight.smk, included before the config file is read.)
import functools
import os
import re
import sys
from pathlib import Path

from snakemake.utils import Paramspace

from rodimpact.analysis.studies import level_case, map_point_case, map_point_names, reference_case
from rodimpact.analysis.measured import RECORDS, SIGNAL_RECORDS, measured_cases
from rodimpact.analysis.sweeps import sweep_frame, sweep_point_case, sweep_points
from rodimpact.storage.references import run_reference, split_reference
from rodimpact.config.calibration import applied_cases, calibration_cases, expected_evaluations, with_method
from rodimpact.config.checks import swept_methods
from rodimpact.contact.laws import LAWS, law_of
from rodimpact.contact.tabulated import CURVE_NUMERICS
from rodimpact.solvers.field import FIELD_OUTPUT
from rodimpact.solvers.registry import METHODS as METHOD_REGISTRY
from rodimpact.plumbing.locks import register_run
from rodimpact.plumbing.sources import source_digest


onstart:
    if workflow.local_exec:  # RATE above
        workflow.scheduler.job_rate_limiter = None
    register_run(WORKDIR)  # a live run here: no other snakemake releases its lock


SCHEMA_DIR = os.path.join(workflow.basedir, "workflow", "schemas")

# Job groups, for a cluster: the jobs of a group that a run needs go to the scheduler as one
# submission (profiles/slurm sets how many independent pieces one takes: group-components) and
# run one after another on its node, each still its own rule, outputs and log. A local run
# ignores groups. Every solver rule is in GROUP_SOLVERS. The case files, the tables, the figures
# and the force export are local rules (`localrule: True`): seconds of work each, less than a
# cluster job costs to start, so a cluster run writes them where snakemake runs. The benchmarks
# are alone on their node.
GROUP_SOLVERS = "solvers"


def checked_project():
    """The whole configuration, checked against the schemas and the method registry."""
    from rodimpact.config.load import load_project  # the checker's imports, only when it runs
    from rodimpact.config.project import ConfigError

    try:
        return load_project(config, root=WORKDIR, schema_dir=SCHEMA_DIR)
    except ConfigError as error:
        sys.exit(f"rodimpact: invalid configuration: {error}")


# The configuration is checked here, before any job, from the files as they are now (every
# record a case names read whole); the checked config (every default filled in) replaces
# snakemake's.
PROJECT = checked_project()
config.update(PROJECT.config)


def refuse(message):
    """Stop planning with one line (a target or a wildcard the configuration does not define)."""
    sys.exit(f"rodimpact: {message}")


def sources(*entry_modules):
    """The digest of the package files a script's imports reach (rodimpact.plumbing.sources): a
    rule's ``params: code=``, so that a change to that code reruns the rule (snakemake's params
    trigger) and a change to other code does not."""
    return _digest(tuple(sorted(set(entry_modules))))


@functools.cache
def _digest(entry_modules):
    """source_digest of the checkout's src/ for ``entry_modules``, once per set of modules a run asks for."""
    return source_digest(SRC_DIR, entry_modules)


def per_job(function):
    """``function(wildcards)`` computed once per job (its wildcards): its params, its resources
    and its inputs ask for the same case."""
    results = {}

    @functools.wraps(function)
    def once(wildcards):
        key = tuple(wildcards.items())
        if key not in results:
            results[key] = function(wildcards)
        return results[key]

    return once


# A solver rule runs its part of a batch (scripts/solve_part.py) through the batch module and the solver
# of its method (the registry names it): a change to one method's code reruns that method's batches only.
SRC_BATCH = ("rodimpact.jobs.batch", "rodimpact.jobs.logs")
BATCH_SOURCES = {name: sources(*SRC_BATCH, spec.solver_module) for name, spec in METHOD_REGISTRY.items()}


def sweep_sources(wildcards):
    """Params function: the code digest of a batch of a sweep's points by the method of the
    wildcard and, for a calibrated law, of the code that computes each point's curve in the batch
    (CURVE_CODE)."""
    builder = curve_rule_of(PROJECT.sweeps[wildcards.case])
    extra = CURVE_CODE[builder] if builder else ()
    return sources(*SRC_BATCH, METHOD_REGISTRY[wildcards.method].solver_module, *extra)


def batch_sources(method=None):
    """Params function: the code digest of a batch of runs of the method ``method(wildcards)``
    (default: the wildcard)."""
    return lambda wildcards: BATCH_SOURCES[method(wildcards) if method else wildcards.method]


# The case file's code: its module, and each method's cost model (named by the registry).
SRC_CASES = sources(
    "rodimpact.jobs.cases", "rodimpact.jobs.logs", *(spec.cost.partition(":")[0] for spec in METHOD_REGISTRY.values())
)


def presentation(make):
    """A presentation rule's params: the function its job calls (``module:function``, by
    ../scripts/artifact.py) and the digest of that module's code, so that a change to it reruns
    the rules that present with it, and a change to other code does not."""
    return {"make": make, "code": sources(make.partition(":")[0], "rodimpact.jobs.logs", "rodimpact.present.table")}


SRC_BENCH = sources(
    "rodimpact.tools.bench", "rodimpact.tools.bench_scaling", "rodimpact.storage.atomic", "rodimpact.jobs.logs"
)
# the code that computes each kind of curve (a calibrated sweep's batch runs it too), by its modules
CURVE_CODE = {"indentation": ("rodimpact.jobs.indentation", "rodimpact.jobs.logs")}
SRC_INDENTATION = sources(*CURVE_CODE["indentation"])
SRC_BAND = sources("rodimpact.jobs.band", "rodimpact.jobs.logs")
# The rules that compute a law's curve per case (a law declares its rule: needs.curve_rule) -> the
# curve file of a case; a law that names another rule is refused here, before any job.
# (computed per group: one job writes the curves of a group's cases into its directory)
CURVE_FILES = {"indentation": "results/indentation/{group}/{case}.h5"}
# ... the settings each rule computes a curve with (a sweep point's batch computes its own), and
# its cost model (module:function, imported when a batch needs it: the continuum's modules are heavy)
CURVE_SETTINGS = {rule: config["numerics"][method] for rule, method in CURVE_NUMERICS.items()}
CURVE_COSTS = {"indentation": "rodimpact.solvers.fem_axi.cost:fem_axi_indentation_cost"}
_NO_CURVE_FILE = [law for law in LAWS.values() if law.needs.curve_rule not in (None, *CURVE_FILES)]
if _NO_CURVE_FILE:
    sys.exit(
        f"rodimpact: the {_NO_CURVE_FILE[0].name} contact law needs a curve from the rule "
        f"{_NO_CURVE_FILE[0].needs.curve_rule!r}, which the workflow does not have; rules that compute curves: "
        f"{', '.join(CURVE_FILES)}"
    )


def curve_rule_of(case):
    """Which rule computes the curve of a resolved case's contact law (None when the law needs none)."""
    return law_of(case.get("contact")).needs.curve_rule


def curve_file_of(case):
    """The curve file of a case whose law needs one: in its group's directory of curves."""
    return CURVE_FILES[curve_rule_of(case)].format(group=group_of(case), case=case["id"])


def one_of(names):
    return "|".join(map(re.escape, names)) or "(?!)"


wildcard_constraints:
    case="[A-Za-z0-9][A-Za-z0-9_.\-]*",
    method=one_of(METHOD_REGISTRY),
    row="[0-9]+",
    part="[0-9]+",
    map_method=one_of(["sem", "sem_paper", "reference"]),


def case_file_of(case_id):
    """The case file holding a case: its group's (results/cases/{group}.yaml), or a sweep case's own."""
    if case_id in PROJECT.sweeps:
        return f"results/cases/{case_id}.yaml"
    case = PROJECT.cases.get(case_id)
    if case is None:
        refuse(f"unknown case {case_id!r}; known: {', '.join([*PROJECT.cases, *PROJECT.sweeps])}")
    return f"results/cases/{group_of(case)}.yaml"


def case_file(case_id):
    """The case file a solver rule takes as input, of the case ``case_id(wildcards)`` (or a fixed id)."""
    return lambda w: case_file_of(case_id(w) if callable(case_id) else case_id)


@per_job
def case_file_cases(wildcards):
    """The cases of the case file of the wildcard ``name``: a group's, or a sweep case."""
    if wildcards.name in GROUPS:
        return GROUPS[wildcards.name]
    if wildcards.name in PROJECT.sweeps:
        return [PROJECT.sweeps[wildcards.name]]
    refuse(
        f"no case file {wildcards.name!r}: neither a group of runs ({', '.join(GROUPS)}) nor a sweep case "
        f"({', '.join(PROJECT.sweeps) or 'none'})"
    )


@per_job
def indentation_cases_of(wildcards):
    """The cases of a group whose law the indentation calibrates; refuses a group that has none."""
    cases = [c for c in GROUPS.get(wildcards.group, []) if curve_rule_of(c) == "indentation"]
    if not cases:
        refuse(
            f"group {wildcards.group!r} has no case whose contact law the indentation calibrates; groups that "
            f"have: {', '.join(g for g, cs in GROUPS.items() if any(curve_rule_of(c) == 'indentation' for c in cs))}"
        )
    return cases


def group_of(case):
    """The group a case's runs are batched in: its reading (variant) in a set with variants, else its set."""
    return case.get("variant") or case["set"]


# group -> its cases: one batch runs one method on every case of a group that lists it (rule solve)
GROUPS = {}
for _case in PROJECT.cases.values():
    GROUPS.setdefault(group_of(_case), []).append(_case)
_CLASH = sorted(
    {c["variant"] for c in PROJECT.cases.values() if c.get("variant")} & {c["set"] for c in PROJECT.cases.values()}
)
if _CLASH:
    sys.exit(
        f"rodimpact: a variant may not be named like a case set ({_CLASH[0]!r}): both name a group of runs, "
        f"results/runs/{_CLASH[0]}/"
    )
_CLASH = sorted(set(GROUPS) & set(PROJECT.sweeps))
if _CLASH:
    sys.exit(
        f"rodimpact: a sweep case may not be named like a group of runs ({_CLASH[0]!r}): both name a case file, "
        f"results/cases/{_CLASH[0]}.yaml"
    )


def runs_of(cases):
    """The runs of every method of every case in ``cases``, each in its group's batch (the solve rule),
    results/runs/{group}/{method}/part{k}.h5#{case}."""
    return [run_in_batch("solve", (group_of(c), m), c["id"]) for c in cases for m in c["methods"]]


def run_batches(runs):
    """Input: the files of runs (a part of a batch each) that hold the runs ``runs`` (a list, or a
    function of the wildcards returning one). A rule that reads runs takes their files as inputs
    and the runs as its ``runs`` param."""
    if callable(runs):
        return lambda wildcards: run_batches(runs(wildcards))
    return sorted({str(split_reference(run)[0]) for run in runs})


def force_files(cases, ext):
    """The exported contact forces (forces.smk) of every run of ``cases``: ext csv or json."""
    return [f"results/forces/{c['set']}/{c['id']}/{m}.{ext}" for c in cases for m in c["methods"]]


#: What the default target builds, gathered from the files of rules: each registers, beside its
#: rules, a function of no arguments that lists their outputs the default target builds
#: (default_target), in the order the files are included. A new artifact's file of rules adds
#: its own; nothing here names it.
DEFAULT_TARGETS = []


def default_target(function):
    """Register ``function`` (no arguments -> a list of targets) with the default target."""
    DEFAULT_TARGETS.append(function)
    return function


def default_targets():
    """Every registered rule file's default targets (rule all)."""
    return [target for function in DEFAULT_TARGETS for target in function()]


def field_runs(case):
    """The runs of a case's methods that record the strain field (the wave map's inputs)."""
    return [run for run, m in zip(runs_of([case]), case["methods"]) if METHOD_REGISTRY[m].records_field]
