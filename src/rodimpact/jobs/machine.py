"""The machine a timing ran on: one description for the timed runs and the benchmarks."""

from __future__ import annotations

import contextlib
import os
import platform
from pathlib import Path
from typing import Any

__all__ = ["machine_description", "machine_info"]


def _processor() -> str:
    model = platform.processor() or platform.machine()
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return model


def machine_info() -> dict[str, Any]:
    """Host name, processor model, logical CPUs, CPUs this process may use, system and Python."""
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return {
        "machine": platform.node(),
        "processor": _processor(),
        "cpu_count": os.cpu_count(),
        "usable_cpus": usable,
        "system": f"{platform.system()} {platform.release()}",
        "python": platform.python_version(),
    }


def machine_description() -> str:
    """The machine in one line: processor; logical CPUs, usable; system."""
    info = machine_info()
    return f"{info['processor']}; {info['cpu_count']} logical CPUs, {info['usable_cpus']} usable; {info['system']}"
