# Before snakemake reads config/config.yaml: the workflow's own code on the path, the file read
# by rodimpact's YAML reader (a syntax error is one line with its line and column), and the
# lock of a killed run released (rodimpact.plumbing.locks).
import os
import sys
from pathlib import Path

# The workflow runs the code of its own checkout (src/), in this process and in its jobs,
# whatever else is installed: the sources snakemake tracks are the sources that run.
SRC_DIR = str(Path(workflow.basedir, "src"))
sys.path.insert(0, SRC_DIR)
# Set (not read from the user) for the jobs; every job's snakemake re-parses this file, so
# remote jobs set it too.
os.environ.update(PYTHONPATH=os.pathsep.join(filter(None, [SRC_DIR, os.environ.get("PYTHONPATH")])))

from rodimpact.config.yamlfile import YamlError, read_yaml
from rodimpact.plumbing.locks import release_stale_lock

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
        sys.exit(f"rodimpact: invalid configuration: {path}: must be a mapping of settings, got "
                 f"{type(document).__name__}")


preflight_config(CONFIG_FILE)


# A lock left by a killed run (no snakemake process lives in this directory, no run of
# another machine registered here) is released, with a one-line notice.
_released = release_stale_lock(WORKDIR)
if _released:
    print(_released, file=sys.stderr)
