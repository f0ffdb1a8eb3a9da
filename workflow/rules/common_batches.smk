# Batches of runs: one method on many runs, cut into parts of about batch.target_s of typical
# solve time (rodimpact.jobs.parts), known when the workflow is parsed. A part is one job and one
# file of runs (a group per run, each with its own provenance; the file written whole or not at
# all), and a run is named by its part's file: part{k}.h5#{name}. Each kind of batch is declared
# once, in BATCHES: the wildcards that name one batch, its runs (a function of their values, in
# order), its file of a part, how its runs are timed and how a message names it. Every rule that
# solves one, and everything that reads its runs, goes through the functions below.
import importlib
from dataclasses import dataclass
from typing import Any, Callable

from rodimpact.config.project import ConfigFile
from rodimpact.jobs.parts import TooManyParts, cut_runs
from rodimpact.jobs.resources import run_cost, timed_cost


@dataclass(frozen=True)
class BatchKind:
    """One kind of batch: ``keys`` the wildcards that name a batch, ``runs(*keys)`` its runs by
    name (each a ``case``, a ``method``, its ``case_file`` and what else the solver rule passes
    on), ``file`` the file of its part ``{part}`` (the solver rule's output), ``timing`` of timed
    runs (None: solved once), ``label(*keys)`` what a message calls the batch, ``case(*keys)``
    the case a refused target names (or None)."""

    keys: tuple
    runs: Callable
    file: str
    label: Callable
    timing: Any = None
    case: Callable = lambda *keys: None


@functools.cache
def group_runs_of(group, method):
    """The runs of one group's batch: ``method`` on every case of the group that lists it, by the
    case's id, each with its case file and, for a law calibrated by a curve, the curve's file;
    refuses an unknown group and a method no case of it runs."""
    cases = GROUPS.get(group)
    if cases is None:
        refuse(f"unknown group of runs {group!r}; known: {', '.join(GROUPS)}")
    runs = {}
    for case in cases:
        if method in case["methods"]:
            runs[case["id"]] = {"case": case, "method": method, "case_file": case_file_of(case["id"])}
            if curve_rule_of(case) is not None:
                runs[case["id"]]["contact_curve"] = curve_file_of(case)
    if not runs:
        refuse(
            f"no case of group {group!r} runs {method!r}; its cases' methods: "
            f"{', '.join(sorted({m for c in cases for m in c['methods']}))}"
        )
    return runs


@functools.cache
def level_runs_of(case_id, method):
    """The levels of ``method`` in the work-precision sweep on ``case_id``, by name (level0,
    level1, ...); refuses a method the study does not sweep there."""
    levels = WORK_PRECISION.get("methods", {}).get(method, {}).get("levels", [])
    runs = {
        f"level{k}": {
            "case": sweep_case(case_id, method, k),
            "method": method,
            "level": k,
            "case_file": case_file_of(case_id),
            "study": {"name": "work_precision", "level": k, "overrides": sweep_level(method, k)},
        }
        for k in range(len(levels))
    }
    return runs or refuse(f"the work-precision study does not sweep {method!r}")


def solver_of(study_method):
    """The solver a batch of the stability study (a stress set, the map) uses: its method, sem for
    the reference."""
    return "sem" if study_method == "reference" else study_method


@functools.cache
def stress_runs_of(set_name, stress_method):
    """One method on every case of a stress set that lists it, or (``reference``) the sem reference
    of every case at the study's tolerance, by the case's id, each with its case file."""
    cases = PROJECT.cases_in(set_name)
    if stress_method == "reference":
        tolerance = config["stability"]["reference_tolerance"]
        return {
            c["id"]: {
                "case": reference_case(c, config["numerics"], tolerance),
                "method": "sem",
                "case_file": case_file_of(c["id"]),
            }
            for c in cases
        }
    runs = {
        c["id"]: {"case": c, "method": stress_method, "case_file": case_file_of(c["id"])}
        for c in cases
        if stress_method in c["methods"]
    }
    if not runs:
        refuse(f"no case of the stress set {set_name!r} runs {stress_method!r}")
    return runs


@functools.cache
def map_runs_of(map_method):
    """Every point of the stability map (each impactor mass at every rod impedance) by one method
    or its sem reference, by the point's name (m{i}_z{j})."""
    base, method = PROJECT.cases[MAP["base_case"]], solver_of(map_method)
    return {
        name: {
            "case": map_point_case(base, MAP, name, map_method, config["numerics"]),
            "method": method,
            "case_file": case_file_of(base["id"]),
        }
        for name in MAP_POINTS
    }


@functools.cache
def sweep_runs_of(case_id, method):
    """Every point of the sweep ``case_id`` by ``method``, by its name (in the grid's order): its
    run (the point's case, the method, the study, and the curve its batch computes when its law
    needs one); refuses a sweep or method the configuration does not define."""
    if case_id not in PROJECT.sweeps:
        refuse(f"unknown sweep {case_id!r}; known: {', '.join(PROJECT.sweeps)}")
    case = PROJECT.sweeps[case_id]
    if method not in case["sweep"]["methods"]:
        refuse(f"sweep {case_id!r} does not run {method!r}; its methods: {', '.join(case['sweep']['methods'])}")
    runs = {}
    for name, values in SWEEP_POINTS[case_id].items():
        point = sweep_point_case(case, values, name)
        study = {"name": "sweep", "sweep": case_id, "point": name}
        runs[name] = {"case": point, "method": method, "case_file": case_file_of(case_id), "study": study}
        builder = curve_rule_of(point)
        if builder is not None:  # no rule computes a point's curve, its batch does
            runs[name]["curve"] = {"rule": builder, "settings": CURVE_SETTINGS[builder]}
    return runs


#: Every kind of batch, by the rule that solves its parts.
BATCHES = {
    "solve": BatchKind(
        keys=("group", "method"),
        runs=group_runs_of,
        file="results/runs/{group}/{method}/part{part}.h5",
        label=lambda group, method: f"group {group!r} by {method}",
    ),
    "solve_levels": BatchKind(
        keys=("case", "method"),
        runs=level_runs_of,
        file="results/convergence/{case}/{method}/part{part}.h5",
        label=lambda case, method: f"the work-precision levels of {method} on {case!r}",
        timing=WORK_PRECISION.get("timing", {}),
        case=lambda case, method: case,
    ),
    "solve_stress": BatchKind(
        keys=("set", "stress_method"),
        runs=stress_runs_of,
        file="results/stress/{set}/{stress_method}/part{part}.h5",
        label=lambda set_name, method: f"stress set {set_name!r} by {method}",
    ),
    "solve_map": BatchKind(
        keys=("map_method",),
        runs=map_runs_of,
        file="results/stability_map/{map_method}/part{part}.h5",
        label=lambda method: f"the stability map by {method}",
        case=lambda method: MAP.get("base_case"),
    ),
    "solve_sweep": BatchKind(
        keys=("case", "method"),
        runs=sweep_runs_of,
        file="results/sweeps/{case}/{method}/part{part}.h5",
        label=lambda case, method: f"sweep {case!r} by {method}",
        case=lambda case, method: case,
    ),
}


def curve_cost(run):
    """The cost of the curve a run's batch computes for its law (CURVE_COSTS; its module imported
    only when a batch needs it)."""
    dotted, _, function = CURVE_COSTS[run["curve"]["rule"]].partition(":")
    return getattr(importlib.import_module(dotted), function)(run["case"], run["curve"]["settings"])


def run_costs(run, timing=None):
    """What a batch's job computes for one run: its solve (timed by ``timing``) and the curve of
    its law when the batch computes it."""
    solve = timed_cost(run_cost(run["case"], run["method"]), timing)
    return [solve, *([curve_cost(run)] if "curve" in run else [])]


@functools.cache
def batch_parts(kind, keys):
    """The parts of the batch ``keys`` (the values of its kind's wildcards) of the kind ``kind``
    (BATCHES): rodimpact.jobs.parts.cut_runs of its runs' costs at batch.target_s, each run
    costed once. Refuses a target that cuts the batch into too many jobs, in one line."""
    spec = BATCHES[kind]
    costs = {name: run_costs(run, spec.timing) for name, run in spec.runs(*keys).items()}
    try:
        return cut_runs(costs, config["batch"]["target_s"])
    except TooManyParts as error:
        where = ConfigFile.under(CONFIG_FILE, Path(WORKDIR))
        message = where.error(f"{spec.label(*keys)}: {error}", case=spec.case(*keys), field="batch.target_s")
        refuse(f"invalid configuration: {message}")


@functools.cache
def _part_of_run(kind, keys):
    """Each run's part in the batch: its name -> the part's index."""
    return {name: k for k, part in enumerate(batch_parts(kind, keys)) for name in part.names}


def part_files(kind, keys):
    """The files of every part of one batch (one job each: the rule ``kind``)."""
    spec = BATCHES[kind]
    return [spec.file.format(**dict(zip(spec.keys, keys)), part=k) for k in range(len(batch_parts(kind, keys)))]


def run_in_batch(kind, keys, name):
    """The run ``name`` of one batch: ``{its part's file}#{name}``."""
    spec = BATCHES[kind]
    file = spec.file.format(**dict(zip(spec.keys, keys)), part=_part_of_run(kind, keys)[name])
    return run_reference(file, name)


def runs_in_batch(kind, keys):
    """Every run of one batch, in its order: ``{its part's file}#{name}`` each."""
    return [run_in_batch(kind, keys, name) for name in BATCHES[kind].runs(*keys)]


def _batch_keys(kind, wildcards):
    return tuple(getattr(wildcards, key) for key in BATCHES[kind].keys)


def batch_part(kind, wildcards):
    """The part of the job's wildcards (a batch's keys and ``part``); refuses a part the batch
    does not have."""
    keys = _batch_keys(kind, wildcards)
    parts, index = batch_parts(kind, keys), int(wildcards.part)
    if index >= len(parts):
        held = "one part: part0" if len(parts) == 1 else f"{len(parts)} parts: part0 to part{len(parts) - 1}"
        refuse(f"{BATCHES[kind].label(*keys)} has {held} (batch.target_s = {config['batch']['target_s']:g} s)")
    return parts[index]


def part_runs(kind):
    """Params function of the solver rule ``kind``, the runs of its job's part, by name."""

    def runs(wildcards):
        every = BATCHES[kind].runs(*_batch_keys(kind, wildcards))
        return {name: every[name] for name in batch_part(kind, wildcards).names}

    return runs


def part_input(kind, files):
    """Input function of the solver rule ``kind``, ``files(runs)`` of its job's part's runs, once the
    part is known to exist (an input function may refuse; its resources and group may not)."""
    return lambda wildcards: files(part_runs(kind)(wildcards))


def case_files(runs):
    """The case files of ``runs`` (each run names its own): a part's input."""
    return sorted({run["case_file"] for run in runs.values()})


def part_group(kind):
    """The job group of the solver rule ``kind``, GROUP_SOLVERS for a batch in one part (below the
    target, so its submission is shared with other small jobs), none for a part of a batch that
    was cut (each is worth a submission of its own; a group would run them one after another)."""
    return lambda wildcards: GROUP_SOLVERS if len(batch_parts(kind, _batch_keys(kind, wildcards))) == 1 else None


def part_resources(kind):
    """The resources of the solver rule ``kind``, its part's (rodimpact.jobs.parts.cut_runs), scaled by
    the attempt."""
    return {
        "mem_mb": lambda wildcards, attempt: batch_part(kind, wildcards).resources.for_attempt(attempt).mem_mb,
        "runtime": lambda wildcards, attempt: batch_part(kind, wildcards).resources.for_attempt(attempt).runtime_min,
    }
