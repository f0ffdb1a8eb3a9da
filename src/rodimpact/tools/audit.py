"""Provenance audit of ``results/``: every artifact resolves to the config and code that made it.

``make provenance`` (``python -m rodimpact.tools.audit``) checks every file under ``results/``:

* an HDF5 run (a run file, or each run of a file of runs: a sweep's part): its config hash
  matches its config, its content digest (``data_sha256``, over config, series and summary)
  matches its content, it was made by the libraries installed now, and the case file it
  records still holds its case;
* a case file (``results/cases/*.yaml``): its case has the hash it was written with;
* a contact-law curve (``results/indentation/*.h5``), a band (``results/studies/film_band_*.h5``,
  ``results/studies/sensor_band/*/*.h5``; with their axes, ``make film-axes``' and ``make
  sensor-axes``', ``film_band_axes_*.h5`` and ``sensor_band_axes/*/*.h5``) or a calibration
  (``results/calibration/*.h5``): its data match their hash;
* a table or figure: a provenance sidecar (``*.provenance.json``) lists it with the SHA-256
  of its bytes as written, and every input run the sidecar names still has the config and
  content hashes the artifact was made from;
* every file's code version names a commit of this repository, made from committed code
  (not ``.dirty``, not ``+unknown``);
* snakemake's own record (``snakemake --summary``) has the file as an output of the current
  workflow and configuration, up to date (not "params changed", "updated input files",
  "rule implementation changed"...). A file it does not know is left from an old config.

The audit only reads; it fails (exit status 1) when any file does not resolve.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import logging
import subprocess
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import h5py

from rodimpact.storage.bands import read_band
from rodimpact.storage.calibrations import read_calibration
from rodimpact.storage.casefile import read_case_file
from rodimpact.storage.curves import read_contact_curve
from rodimpact.storage.faults import DIRECTORY_TIMESTAMP, REBUILD_HINT, StoredFileError
from rodimpact.storage.provenance import commit_exists, file_sha256, find_repo_root, library_versions
from rodimpact.storage.references import split_reference
from rodimpact.storage.runs import CorruptRun, StoreError, read_run, read_summary, run_references

logger = logging.getLogger(__name__)

__all__ = [
    "EXEMPT",
    "TOOL_FOLDERS",
    "AuditResult",
    "Finding",
    "audit",
    "audit_one_run",
    "audit_run",
    "audit_sidecar",
    "code_problems",
    "main",
    "workflow_status",
]

#: Files under results/ the audit does not check, and why.
EXEMPT: dict[str, str] = {
    "report.html": "the snakemake report: a view of the audited artifacts, rebuilt by `make report`",
    "report_screenshot.png": "the report's first screen in headless Chromium (`make report-check`)",
    "benchmarks/build.csv": "the last build's own timing, from snakemake's job records (`make bench`)",
    "benchmarks/planning.csv": "how long snakemake takes to plan, timed on this machine (`make bench`)",
    "benchmarks/cost_share.csv": "the stored runs' solver times over their cost models' (`make bench`)",
    "benchmarks/sweep_scaling.csv": "sweeps built in scratch copies with -j1 and -j2, timed (`make bench`)",
    "benchmarks/sweep_point.csv": "where a sweep point's time goes, timed in a scratch copy (`make bench`)",
    "benchmarks/cluster.csv": "the small configuration built locally and through SLURM, timed (`make test-cluster`)",
}
#: Folders under results/ that a named target writes outside snakemake (the Makefile's): their
#: files are audited by their provenance records, and not asked of snakemake's up-to-date check.
TOOL_FOLDERS: dict[str, str] = {
    "sensor_plastic/": "make sensor-plastic (rodimpact.tools.sensor_plastic)",
    "verification/": "make sphere-flat (rodimpact.tools.sphere_flat)",
}
_SIDECAR = ".provenance.json"
#: Where under ``results/studies/`` the band files are: the film's (``film_band_{variant}.h5``, and
#: ``film_band_axes_{variant}.h5``) and the sensor's (``sensor_band/`` and ``sensor_band_axes/``).
BAND_PREFIXES = ("film_band_", "sensor_band/", "sensor_band_axes/")
_BENCHMARKS = ("results/benchmarks/sem.csv", "results/benchmarks/fem.csv")


@dataclass(frozen=True)
class Finding:
    """What the audit found for one file: ``problems`` is empty when it resolves."""

    path: str
    kind: str
    problems: tuple[str, ...] = ()
    code_versions: tuple[str, ...] = ()
    config_sha256: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        return not self.problems


@dataclass(frozen=True)
class AuditResult:
    """The audit of one results directory, a finding per file (sorted by path)."""

    findings: tuple[Finding, ...]

    @property
    def success(self) -> bool:
        return all(f.ok for f in self.findings)

    @property
    def message(self) -> str:
        failed = sum(not f.ok for f in self.findings)
        return (
            f"{len(self.findings)} files audited: {len(self.findings) - failed} resolve to their "
            f"config and code, {failed} do not"
        )


def code_problems(version: str, repo_root: Path | None) -> list[str]:
    """Why a recorded code version does not name exact code ([] if it does)."""
    if not version or version.endswith("+unknown"):
        return [f"code version {version!r} is unknown (made outside a git checkout)"]
    if version.endswith(".dirty"):
        return [f"made from uncommitted code ({version})"]
    commit = version.rsplit("+g", 1)[-1]
    if repo_root is None:
        return [f"cannot check commit {commit}: no git repository here"]
    if not commit_exists(repo_root, commit):
        return [f"commit {commit} of code version {version} is not in this repository"]
    return []


def audit_run(path: str | Path, libraries: Mapping[str, str], repo_root: Path | None) -> Finding:
    """Check one HDF5 run file, or every run of a file of runs (a sweep's part), each as
    :func:`audit_one_run`; a problem of one run of a file names the run."""
    try:
        references = run_references(path)
    except CorruptRun as error:
        return Finding(str(path), "run", (f"{error.reason} ({REBUILD_HINT})" if error.marked else error.reason,))
    except (StoreError, OSError, ValueError) as error:
        return Finding(str(path), "run", (f"not a readable run file: {error}",))
    if references == [str(path)]:
        return audit_one_run(path, libraries, repo_root)
    if not references:
        return Finding(str(path), "run", ("a file of runs that holds no run",))
    each = [audit_one_run(reference, libraries, repo_root) for reference in references]
    return Finding(
        str(path),
        "run",
        tuple(f"run {split_reference(f.path)[1]}: {problem}" for f in each for problem in f.problems),
        tuple(sorted({version for f in each for version in f.code_versions})),
        tuple(digest for f in each for digest in f.config_sha256),
    )


def audit_one_run(path: str | Path, libraries: Mapping[str, str], repo_root: Path | None) -> Finding:
    """Check one run (a file, or ``file#name`` in a file of runs): config hash, content digest,
    code version and libraries."""
    try:
        record = read_run(path)  # checks the content digest; a damaged or edited file is marked out of date
    except CorruptRun as error:
        return Finding(str(path), "run", (f"{error.reason} ({REBUILD_HINT})" if error.marked else error.reason,))
    except (StoreError, OSError, ValueError) as error:
        return Finding(str(path), "run", (f"not a readable run file: {error}",))
    problems = code_problems(record.code_version, repo_root)
    if not record.data_sha256:
        problems.append("no content digest (written by an older version of the code)")
    problems += case_file_problems(record.config.get("run", {}).get("case_file"))
    changed = sorted(
        name for name, version in record.library_versions.items() if libraries.get(name, version) != version
    )
    if changed:
        problems.append(
            "made with other library versions: "
            + ", ".join(f"{name} {record.library_versions[name]} (now {libraries[name]})" for name in changed)
        )
    return Finding(str(path), "run", tuple(problems), (record.code_version,), (record.config_sha256,))


def audit_derived(path: str | Path, kind: str, repo_root: Path | None) -> Finding:
    """Check a contact-law curve (``results/indentation/``), a band (``results/studies/``) or a
    calibration (``results/calibration/``): readable, its data match their hash, its code
    version exists."""
    reader = {"curve": read_contact_curve, "band": read_band, "calibration": read_calibration}[kind]
    try:
        reader(path)
        with h5py.File(path, "r") as h5:
            version = str(h5.attrs["code_version"])
    except (StoredFileError, OSError, KeyError) as error:
        return Finding(str(path), kind, (str(error),))
    return Finding(str(path), kind, tuple(code_problems(version, repo_root)), (version,))


def case_file_problems(reference: Mapping[str, Any] | None) -> list[str]:
    """Whether the case file a run records still holds the case the run was made from."""
    if not reference:
        return []
    try:
        document = read_case_file(reference["path"])
    except (OSError, ValueError) as error:
        return [f"its case file {reference['path']} is not readable: {error}"]
    if reference["config_sha256"] not in {record["config_sha256"] for record in document["cases"]}:
        return [f"its case file {reference['path']} holds another case now (the case was edited)"]
    return []


def audit_case_file(path: str | Path) -> Finding:
    """Check one case file: it is one, and each of its cases has the hash it was written with."""
    try:
        document = read_case_file(path)
    except (OSError, ValueError) as error:
        return Finding(str(path), "case", (str(error),))
    return Finding(str(path), "case", (), (), tuple(record["config_sha256"] for record in document["cases"]))


def _input_problems(entry: Mapping[str, Any], runs: dict[str, Any]) -> list[str]:
    """Does the input run a sidecar names still hold what the artifact was made from?"""
    path = entry.get("path", "")
    if path not in runs:
        try:
            runs[path] = read_summary(path)
        except (StoreError, OSError, ValueError) as error:
            runs[path] = error
    record = runs[path]
    if isinstance(record, Exception):
        return [f"input {path} is gone or unreadable ({record})"]
    if record.config_sha256 != entry.get("config_sha256"):
        return [f"input {path} now has another config (the artifact is older than the run)"]
    if record.data_sha256 != entry.get("data_sha256", ""):
        return [f"input {path} now has other content (the artifact is older than the run)"]
    return []


def audit_sidecar(path: str | Path, runs: dict[str, Any], repo_root: Path | None) -> list[Finding]:
    """Check a provenance sidecar and every artifact it lists: a finding for each."""
    path = str(path)
    try:
        record = json.loads(Path(path).read_text(encoding="utf-8"))
        artifacts, digests, inputs = record["artifacts"], record.get("sha256", {}), record["inputs"]
    except (OSError, ValueError, KeyError, TypeError) as error:
        return [Finding(path, "provenance", (f"not a readable provenance record: {error}",))]
    shared = code_problems(record.get("code_version", ""), repo_root)
    for entry in inputs:
        shared += _input_problems(entry, runs)
    versions = tuple(sorted({record.get("code_version", "")} | {e.get("code_version", "") for e in inputs}))
    hashes = tuple(e.get("config_sha256", "") for e in inputs)
    findings = [Finding(path, "provenance", tuple(shared), versions, hashes)]
    for artifact in artifacts:
        problems = list(shared)
        if artifact not in digests:
            problems.append(f"{Path(path).name} records no SHA-256 for it (written by an older version)")
        elif not Path(artifact).is_file():
            problems.append("listed by its provenance record but missing")
        elif file_sha256(artifact) != digests[artifact]:
            problems.append("bytes differ from those recorded when it was written (edited by hand?)")
        findings.append(Finding(artifact, "artifact", tuple(problems), versions, hashes))
    return findings


def workflow_status(root: Path, targets: Sequence[str] = ()) -> dict[str, str]:
    """Output file -> why snakemake would remake it ("" when up to date), from ``--summary``.

    The reason is the file's status (``params changed``, ``updated input files``, ``rule
    implementation changed``, ``missing``...), or, for a file whose own status is ``ok`` but
    whose job is planned because an input is remade first, ``an input is out of date``.

    Raises
    ------
    RuntimeError
        snakemake failed (its message is included).
    """
    command = [sys.executable, "-m", "snakemake", "--summary", "--nocolor", *targets]
    # a working directory of its own (such as .test) is run with the project's Snakefile above it
    above = next((d / "Snakefile" for d in Path(root).resolve().parents if (d / "Snakefile").is_file()), None)
    if not (Path(root) / "Snakefile").is_file() and above is not None:
        command += ["--snakefile", str(above)]
    proc = subprocess.run(command, cwd=root, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{proc.stderr[-3000:]}")
    status = {}
    for line in proc.stdout.splitlines()[1:]:
        parts = line.split("\t")
        if len(parts) >= 6:
            own, plan = parts[4], parts[5]
            status[parts[0]] = own if own != "ok" else ("an input is out of date" if plan == "update pending" else "")
    return status


def audit(root: str | Path = ".", *, results: str = "results", workflow: bool = True) -> AuditResult:
    """Audit every file under ``root/results``; paths in the findings are relative to ``root``.

    Parameters
    ----------
    root : str or Path
        The project (the directory with the Snakefile).
    results : str
        The results directory, relative to ``root``.
    workflow : bool
        Also ask snakemake whether each file is an up-to-date output of the current
        workflow and config (``--summary``; needs the project's Snakefile).
    """
    root = Path(root).resolve()
    repo_root = find_repo_root(root)
    base = root / results
    files = sorted(str(p.relative_to(root)) for p in base.rglob("*") if p.is_file()) if base.is_dir() else []
    exempt = {f"{results}/{name}" for name in EXEMPT}
    libraries, runs = library_versions(), {}
    found: dict[str, Finding] = {}
    with contextlib.chdir(root):
        for path in files:
            if path.startswith(f"{results}/indentation/") and path.endswith(".h5"):
                found[path] = audit_derived(path, "curve", repo_root)
            elif path.startswith(tuple(f"{results}/studies/{band}" for band in BAND_PREFIXES)) and path.endswith(".h5"):
                found[path] = audit_derived(path, "band", repo_root)
            elif path.startswith(f"{results}/calibration/") and path.endswith(".h5"):
                found[path] = audit_derived(path, "calibration", repo_root)
            elif path.endswith(".h5"):
                found[path] = audit_run(path, libraries, repo_root)
            elif path.startswith(f"{results}/cases/") and path.endswith(".yaml"):
                found[path] = audit_case_file(path)
            elif path.endswith(_SIDECAR):
                for finding in audit_sidecar(path, runs, repo_root):
                    if finding.path in found and finding.path != path:  # listed twice: keep both verdicts
                        finding = _merged(found[finding.path], finding.problems)
                    found[finding.path] = finding
        status = {}
        if workflow:
            targets = ["all", *(b for b in _BENCHMARKS if Path(b).is_file())]
            status = workflow_status(root, targets)
    findings = []
    for path in files:
        if path in exempt or Path(path).name == DIRECTORY_TIMESTAMP:  # snakemake's, in a batch's directory
            continue
        finding = found.get(path) or Finding(path, "unknown", ("no provenance record lists it",))
        if workflow and path not in status:  # a run of a batch: its directory is the rule's output
            holder = next((str(parent) for parent in Path(path).parents if str(parent) in status), None)
            if holder is not None:
                status[path] = status[holder]
        if ".tmp." in Path(path).name or ".tmp-" in Path(path).name:
            finding = _merged(finding, ("a temporary file left by an interrupted write",))
        if path.startswith(tuple(f"{results}/{folder}" for folder in TOOL_FOLDERS)):
            pass  # a named target's, outside snakemake: its record is what is audited
        elif workflow and path not in status:
            finding = _merged(finding, ("not an output of the current workflow and config (left from an old one?)",))
        elif workflow and status[path]:
            finding = _merged(finding, (f"snakemake: {status[path]} (stale against the current config or code)",))
        findings.append(finding)
    result = AuditResult(tuple(findings))
    logger.info("%s", result.message)
    return result


def _merged(finding: Finding, problems: Sequence[str]) -> Finding:
    return Finding(
        finding.path, finding.kind, (*finding.problems, *problems), finding.code_versions, finding.config_sha256
    )


def add_arguments(parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """The audit's options, on ``parser`` (this module's command and ``rodimpact audit``)."""
    parser.add_argument("--root", default=".", help="project directory (default: .)")
    parser.add_argument("--no-workflow", action="store_true", help="skip snakemake's up-to-date check")
    parser.add_argument("--json", help="also write every finding to this JSON file")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m rodimpact.tools.audit [--root DIR] [--no-workflow] [--json FILE]``; exit 1 on failure."""
    parser = argparse.ArgumentParser(prog="python -m rodimpact.tools.audit", description=__doc__.split("\n")[0])
    return run(add_arguments(parser).parse_args(argv))


def run(args: argparse.Namespace) -> int:
    """The audit with parsed options (:func:`add_arguments`): prints its findings; exit status 1 on failure."""
    result = audit(args.root, workflow=not args.no_workflow)
    for finding in result.findings:
        for problem in finding.problems:
            sys.stdout.write(f"FAIL {finding.path}: {problem}\n")
    versions = sorted({v for f in result.findings for v in f.code_versions})
    sys.stdout.write(f"{result.message}; code versions: {', '.join(versions) or 'none'}\n")
    if args.json:
        rows = [
            {
                "path": f.path,
                "kind": f.kind,
                "ok": f.ok,
                "problems": list(f.problems),
                "code_versions": list(f.code_versions),
                "config_sha256": list(f.config_sha256),
            }
            for f in result.findings
        ]
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps({"success": result.success, "findings": rows}, indent=1) + "\n")
    return 0 if result.success else 1


if __name__ == "__main__":
    raise SystemExit(main())
