#!/usr/bin/env python3
"""A stand-in for a cluster's submit command (sbatch, qsub), for tests/test_cluster.py.

snakemake's cluster-generic executor calls ``<submit command> <jobscript>``, the submit
command being ``--cluster-generic-submit-cmd`` with the job's ``{resources.mem_mb}``,
``{threads}``, ``{rule}`` etc. filled in. This script appends what it was given to a JSON
lines file (``--record=PATH``): its arguments, and what snakemake wrote into the jobscript's
``# properties = {...}`` line: the type (``single`` or ``group``), the group, the rule and
wildcards (of a single job), the threads, resources and outputs. It then runs
the jobscript to its end (a synchronous "cluster": the jobscript touches the marker file
snakemake polls for, ``<jobid>.jobfinished`` or ``.jobfailed``) and prints a job id, as a
submit command does. It exits 0 even when the job fails: the submission itself succeeded.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

PROPERTIES = re.compile(r"^# properties = (.*)$", re.M)


def main(argv: list[str]) -> int:
    if len(argv) < 2 or not argv[0].startswith("--record="):
        sys.stderr.write("usage: fake_submit.py --record=PATH [option ...] JOBSCRIPT\n")
        return 2
    record, jobscript = Path(argv[0].split("=", 1)[1]), Path(argv[-1])
    match = PROPERTIES.search(jobscript.read_text(encoding="utf-8"))
    properties = json.loads(match.group(1)) if match else {}
    entry = {
        "argv": argv[1:-1],
        "jobscript": jobscript.name,
        **{
            key: properties.get(key)
            for key in ("type", "groupid", "rule", "wildcards", "threads", "resources", "jobid", "output")
        },
    }
    done = subprocess.run(["/bin/sh", str(jobscript)], stdout=sys.stderr, stderr=sys.stderr, check=False)
    entry["returncode"] = done.returncode
    with record.open("a", encoding="utf-8") as out:
        out.write(json.dumps(entry) + "\n")
    sys.stdout.write(f"fake-{properties.get('jobid', 0)}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
