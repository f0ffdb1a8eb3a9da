# Before snakemake reads config/config.yaml: the workflow's own code on the path, the file read
# by rodimpact's YAML reader (a syntax error is one line with its line and column), and the
# lock of a killed run released (rodimpact.plumbing.locks).
import os
import sys
from pathlib import Path

# The workflow runs the code of its own checkout (src/), in this process and in its jobs,
# whatever else is installed: the sources snakemake tracks are the sources that run.
#   What snakemake does: it puts the folder of each file it includes (the project, then
#   workflow/rules; never src/) at the head of its own sys.path (snakemake.workflow.Workflow.
#   include), so an installed rodimpact (or an editable install of another checkout) is what
#   `import rodimpact` finds; it runs a `script:` job as a new process of the same interpreter
#   (snakemake.script.PythonScript) whose preamble appends only snakemake's own location and
#   the script's folder to sys.path, so the job sees site-packages and the PYTHONPATH it
#   inherits. A job in a conda environment loses PYTHONPATH (snakemake.shell drops it unless
#   --conda-not-block-search-path-envvars is given): the workflow runs in the project's .venv,
#   not with --sdm conda.
#   Why not enough: sources() digests the checkout's src/ files for the rules' params, so this
#   process and every job must import exactly those; and before `configfile:` (Snakefile),
#   since reading config.yaml below already imports rodimpact. PYTHONPATH is set, not read
#   from the user, for the jobs; a cluster job's snakemake parses this file again and sets it.
#   If snakemake changes (cleans its jobs' environment, runs scripts another way): the jobs
#   import another copy or none; tests/test_workflow_errors.py::test_jobs_run_the_checkouts_own_code
#   fails (a copy's runner raises on import, an installed one would not).
SRC_DIR = str(Path(workflow.basedir, "src"))
sys.path.insert(0, SRC_DIR)
# Set (not read from the user) for the jobs; every job's snakemake re-parses this file, so
# remote jobs set it too.
os.environ.update(PYTHONPATH=os.pathsep.join(filter(None, [SRC_DIR, os.environ.get("PYTHONPATH")])))

from rodimpact.config.yamlfile import YamlError, read_yaml
from rodimpact.plumbing.locks import OrphanedJobs, release_stale_lock

# The working directory: the project itself, or another directory with its own config/ (and
# results/) given by --directory, such as .test. config.yaml's paths are relative to it.
WORKDIR = os.getcwd()
CONFIG_FILE = "config/config.yaml"


def preflight_config(path):
    """Exit with one line when the config file is missing, not YAML or not a mapping."""
    try:
        document = read_yaml(Path(path))
    except FileNotFoundError:
        sys.exit(f"rodimpact: invalid configuration: {path}: file not found")
    except (YamlError, UnicodeDecodeError, IsADirectoryError) as error:
        sys.exit(f"rodimpact: invalid configuration: {path}: {error}")
    if not isinstance(document, dict):
        sys.exit(
            f"rodimpact: invalid configuration: {path}: must be a mapping of settings, got "
            f"{type(document).__name__}"
        )


preflight_config(CONFIG_FILE)


# A lock left by a killed run (no snakemake process lives in this directory, no run of
# another machine registered here) is released, with a one-line notice. A cluster job's
# snakemake (--mode remote, on a compute node) never releases one: the lock is its run's.
# While a killed run's jobs still run here, the lock is kept and this run stops in one line.
if not workflow.remote_exec:
    try:
        _released = release_stale_lock(WORKDIR)
    except OrphanedJobs as _orphans:
        sys.exit(str(_orphans))
    if _released:
        print(_released, file=sys.stderr)
