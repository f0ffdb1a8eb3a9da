"""Copies of the project the workflow tests run snakemake in, so that snakemake never runs in
the repository itself and its config/ is never written: a fresh, shrunk copy of the shipped
configuration (:func:`copy_project`), a copy of a built one (:func:`clone_built`), and the one
end-to-end build of the small configuration ``.test/`` the tests share (:func:`dottest_build`,
:func:`clone_build`).
"""

from __future__ import annotations

import logging
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import h5py
import yaml

from rodimpact.config.load import load_global_config, load_project

from helpers.repo import PROJECT_PARTS, ROOT
from helpers.snakemake_cli import BUILD_TIMEOUT_S, job_stats, snakemake

LOG = logging.getLogger(__name__)

#: The working directory of the small configuration, inside the project.
DOTTEST = ".test"
#: The fem_axi numerics of config.yaml, which a shrunk copy coarsens.
COARSE_FEM_AXI = (
    "steps_per_contact: 300, max_time_factor: 100.0, max_contacts: 50,\n              element: P2, elements_across: 10"
)
#: The studies of a shrunk copy: work precision of the three 1-D methods on 'model' (coarsest
#: three levels, timed once), two stress cases without fem_axi, a 2 x 2 stability map.
SMALL_STRESS = ("short_rod", "rubber_on_steel")
#: Points of the Table 2 ball sweep in a shrunk copy (per rod geometry variant).
SMALL_SWEEP = 3
#: The film readings a shrunk copy drops (it keeps the text's rod: the thin-layer film, and the
#: calibrated law with and without the film).
DROPPED_FILM_VARIANTS = ("r1_l301_film", "r1_l30_film", "r10_l301_film")
_IGNORE = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info", "*.tmp*")


def _copy_parts(dest: Path) -> None:
    dest.mkdir(parents=True, exist_ok=True)
    for part in PROJECT_PARTS:
        source = ROOT / part
        if source.is_dir():
            shutil.copytree(source, dest / part, ignore=_IGNORE)
        else:
            shutil.copy2(source, dest / part)


def copy_project(dest: Path) -> Path:
    """A fresh, unbuilt, shrunk copy of the project at ``dest``.

    For the tests of the workflow's mechanics, not its numerics (tested elsewhere and
    regressed by test_golden.py): the copy runs fem_axi on a coarse mesh with few steps, and
    small studies (comments of the edited YAML files are lost).
    """
    _copy_parts(dest)
    config = dest / "config" / "config.yaml"
    text = config.read_text(encoding="utf-8")
    assert text.count(COARSE_FEM_AXI) == 1, "the fem_axi numerics line of config.yaml moved"
    config.write_text(
        text.replace(
            COARSE_FEM_AXI, COARSE_FEM_AXI.replace("300", "80").replace("elements_across: 10", "elements_across: 4")
        ),
        encoding="utf-8",
    )
    _small_studies(dest)
    git_commit(dest)
    return dest


def git_commit(project: Path) -> None:
    """Make the copy a git repository with everything committed: its runs then record an
    exact code version (``make provenance`` refuses ``+unknown`` and ``.dirty``)."""
    (project / ".gitignore").write_text("__pycache__/\n*.pyc\n.snakemake/\nresults/\nlogs/\n", encoding="utf-8")
    git = ["git", "-C", str(project), "-c", "user.name=rodimpact tests", "-c", "user.email=tests@localhost"]
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-q", "-m", "copy of the project"]):
        subprocess.run([*git, *args], check=True, capture_output=True)


def _small_studies(project: Path) -> None:
    """Shrink config.yaml's studies, the stress cases and the Table 2 sweep."""
    config = project / "config" / "config.yaml"
    document = yaml.safe_load(config.read_text(encoding="utf-8"))
    study = document["work_precision"]
    study["cases"] = ["model"]
    study["timing"] = {"min_repeats": 1, "min_total_s": 0.0, "max_total_s": 0.0}
    study["methods"] = {
        m: {**spec, "levels": spec["levels"][:3]} for m, spec in study["methods"].items() if m != "fem_axi"
    }
    study.pop("separate", None)  # fem_axi on the slowest Table 2 row: not swept here
    study.pop("per_case", None)  # the smooth and elastic-plastic cases are not among the cases here
    document["stability"]["map"].update(mass_kg=[1.0e-3, 1.0e-2], impedance_kg_s=[3.0, 1000.0])
    config.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    stress = project / "config" / "cases" / "stress.yaml"
    document = yaml.safe_load(stress.read_text(encoding="utf-8"))
    document["cases"] = [c for c in document["cases"] if c["id"] in SMALL_STRESS]
    for case in document["cases"]:
        case["methods"] = ["sem", "sem_paper", "fem1d"]
    stress.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    table2 = project / "config" / "cases" / "table2.yaml"  # edited as text: tests add rows to it
    text = table2.read_text(encoding="utf-8")
    sweep = "ball_diameter_m: {start: 1.0e-3, stop: 20.0e-3, num: 25, spacing: log}"
    assert text.count(sweep) == 1, "the ball sweep's line of table2.yaml moved"
    text = text.replace(sweep, sweep.replace("num: 25", f"num: {SMALL_SWEEP}"))
    film_sweep = "ball_diameter_m: {start: 1.0e-3, stop: 20.0e-3, num: 13, spacing: log}"
    assert text.count(film_sweep) == 1, "the film sweep's line of table2.yaml moved"
    text = text.replace(film_sweep, film_sweep.replace("num: 13", "num: 2"))
    for variant in DROPPED_FILM_VARIANTS:  # a variant's block runs to the next one's name
        block = re.search(rf"\n  {variant}:\n(?:    .*\n|\s*\n)*?(?=  \w+:\n|  # )", text)
        assert block, f"the variant {variant} of table2.yaml moved"
        text = text.replace(block.group(0), "\n")
    table2.write_text(text, encoding="utf-8")


def clone_built(built: Path, dest: Path) -> Path:
    """A copy of a built project: results, logs and .snakemake metadata, mtimes preserved."""
    shutil.copytree(built, dest, symlinks=True)
    return dest


def project_cases(workdir: Path):
    """The resolved project of a working directory (a copy, or its ``.test``), as the workflow
    sees it."""
    config = load_global_config(workdir / "config" / "config.yaml")
    project = next(d for d in (workdir, *workdir.parents) if (d / "Snakefile").is_file())
    return load_project(config, root=workdir, schema_dir=project / "workflow" / "schemas")


def group_of(case_id: str) -> str:
    """The group a case's runs are batched in, from its id: the reading of a ``{row}-{variant}``
    case, else the case itself (a set named like its one case, such as ``model``)."""
    return case_id.rpartition("-")[2] if "-" in case_id else case_id


def run_batch(case_id: str, method: str, group: str | None = None) -> str:
    """The folder of the batch (rule solve's parts, ``part{k}.h5``) holding the run of ``case_id``
    by ``method``: ``results/runs/{group}/{method}``."""
    return f"results/runs/{group or group_of(case_id)}/{method}"


def batch_part(case_id: str, method: str, group: str | None = None, part: int = 0) -> str:
    """The file of one part of that batch (a target): ``results/runs/{group}/{method}/part{k}.h5``."""
    return f"{run_batch(case_id, method, group)}/part{part}.h5"


def batches(files) -> set[str]:
    """The batches' folders of part files (a set of rule solve's outputs)."""
    return {Path(f).parent.as_posix() for f in files}


def case_run(workdir: Path, case: dict, method: str) -> str:
    """The run of a resolved ``case`` by ``method`` in ``workdir``'s results: in the batch of its
    group (its reading, else its set)."""
    return run_path(workdir, case["id"], method, group=case.get("variant") or case["set"])


def run_path(workdir: Path, case_id: str, method: str, group: str | None = None) -> str:
    """The run of ``case_id`` by ``method`` as ``workdir``'s results hold it, relative to
    ``workdir``: ``results/runs/{group}/{method}/part{k}.h5#{case}``, the part found by
    reading the batch's files (the cut is the workflow's)."""
    folder = run_batch(case_id, method, group)
    for file in sorted((workdir / folder).glob("part*.h5")):
        with h5py.File(file, "r") as h5:
            if case_id in h5:
                return f"{folder}/{file.name}#{case_id}"
    raise FileNotFoundError(f"no part of {workdir / folder} holds the run {case_id!r}")


# --------------------------------------------------------------------------------------------
# the small configuration .test/, built once
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class DotTestBuild:
    """The project (the directory of the Snakefile) whose ``.test/`` holds a complete, up-to-date
    build of the small configuration; ``reused``: the checkout's own, built by ``make test``."""

    project: Path
    reused: bool

    @property
    def workdir(self) -> Path:
        """``.test/``: its config/, results/, logs/ and .snakemake/."""
        return self.project / DOTTEST


def reuse_refusal(project: Path = ROOT) -> str | None:
    """Why the checkout's ``.test/results`` cannot stand for a fresh build (None: it can).

    It can when it exists, snakemake plans nothing for it (every output present and up to date
    with the checkout's code and configuration), and every run it holds names a commit of the
    checkout as its code version (a build of uncommitted code fails the provenance audit).
    """
    workdir = project / DOTTEST
    if not (workdir / "results").is_dir():
        return f"{workdir / 'results'} does not exist"
    run = snakemake(project, "-n", "-j2", workdir=DOTTEST)
    if run.returncode != 0 or job_stats(run.output) or "Nothing to be done" not in run.output:
        return f"snakemake -n --directory {DOTTEST} plans jobs:\n{run.output[-2000:]}"
    versions = set()
    for path in sorted((workdir / "results").rglob("*.h5")):
        with h5py.File(path, "r") as h5:
            version = h5.attrs.get("code_version")
        versions.add(version.decode() if isinstance(version, bytes) else version)
    for version in sorted(versions - {None}):
        commit = version.rpartition("+g")[2]
        if (
            version.endswith((".dirty", "+unknown"))
            or "+g" not in version
            or subprocess.run(
                ["git", "-C", str(project), "cat-file", "-e", f"{commit}^{{commit}}"], capture_output=True
            ).returncode
        ):
            return f"{DOTTEST}/results holds runs of code version {version}, not a commit of this checkout"
    return None


def copy_dottest(dest: Path) -> Path:
    """A fresh, unbuilt copy of the project with its small configuration ``.test/config``, every
    file committed to a git repository of its own."""
    _copy_parts(dest)
    shutil.copytree(ROOT / DOTTEST / "config", dest / DOTTEST / "config", ignore=_IGNORE)
    git_commit(dest)
    return dest


def dottest_build(scratch: Path) -> DotTestBuild:
    """The checkout's ``.test/`` build when :func:`reuse_refusal` finds none, else a build
    (``snakemake -j2 --directory .test``) in a copy of the project under ``scratch``.

    Building in a copy, not in the checkout: pytest alone then never writes into the checkout
    (``make test`` builds ``.test/`` itself before pytest), a stale or half-built ``.test/``
    of a developer is left as it is, and two test sessions at once do not share a directory.
    """
    why = reuse_refusal()
    if why is None:
        LOG.info("reusing the checkout's build of %s", ROOT / DOTTEST)
        return DotTestBuild(ROOT, reused=True)
    LOG.info("building %s in a copy: %s", DOTTEST, why)
    project = copy_dottest(scratch / "project")
    run = snakemake(project, "-j2", timeout=BUILD_TIMEOUT_S, workdir=DOTTEST)
    assert run.returncode == 0, run.describe()
    return DotTestBuild(project, reused=False)


def clone_build(build: DotTestBuild, dest: Path) -> DotTestBuild:
    """A copy of ``build`` a test may change: the project with ``.test/`` and its results, logs
    and .snakemake metadata, mtimes kept, in a git repository that holds the commits its runs
    name (the checkout's, shared read-only, when the build is the checkout's)."""
    if not build.reused:
        return DotTestBuild(clone_built(build.project, dest), reused=False)
    subprocess.run(
        ["git", "clone", "-q", "--shared", "--no-checkout", str(build.project), str(dest)],
        check=True,
        capture_output=True,
    )
    _copy_parts(dest)
    shutil.copytree(build.workdir, dest / DOTTEST, symlinks=True)
    return DotTestBuild(dest, reused=False)
