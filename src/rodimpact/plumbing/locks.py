"""Snakemake's lock of the project directory after a killed run: released when no run holds it.

Snakemake locks a directory while it runs in it (``.snakemake/locks``). A run killed by
SIGKILL, an out-of-memory kill or a power cut leaves the lock behind, and the next run stops
on it until ``snakemake --unlock``. The workflow calls :func:`release_stale_lock` when it is
parsed: the lock is released, with a one-line notice, only when

* no snakemake process other than the caller runs in this directory on this machine (read
  from ``/proc``; without ``/proc`` nothing is released), and
* no run on another machine registered itself here (:func:`register_run`, called when a run
  starts: ``.snakemake/rodimpact/runs/<host>-<pid>``, removed when it ends; a shared file
  system may hold a live run of another node, which this machine cannot see).
"""

from __future__ import annotations

import atexit
import contextlib
import os
import socket
from pathlib import Path

__all__ = ["live_snakemake_pids", "register_run", "release_stale_lock"]

LOCK_DIR = Path(".snakemake") / "locks"
RUNS_DIR = Path(".snakemake") / "rodimpact" / "runs"
_PROC = Path("/proc")


def live_snakemake_pids(root: str | Path, proc: Path = _PROC) -> list[int] | None:
    """Other processes running snakemake in ``root`` on this machine; None without ``/proc``."""
    if not proc.is_dir():
        return None
    here, me = Path(root).resolve(), os.getpid()
    found = []
    for entry in proc.iterdir():
        if not entry.name.isdigit() or int(entry.name) == me:
            continue
        try:
            command = (entry / "cmdline").read_bytes().split(b"\0")
            if not any(b"snakemake" in part for part in command[:3]):
                continue
            if Path(os.readlink(entry / "cwd")).resolve() == here:
                found.append(int(entry.name))
        except OSError:  # gone, or not ours to read
            continue
    return found


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def register_run(root: str | Path) -> Path:
    """Record this run (host and pid) until it ends; the record's path."""
    runs = Path(root) / RUNS_DIR
    runs.mkdir(parents=True, exist_ok=True)
    record = runs / f"{socket.gethostname()}-{os.getpid()}"
    record.write_text(f"{socket.gethostname()} {os.getpid()}\n", encoding="utf-8")

    def remove() -> None:
        with contextlib.suppress(OSError):
            record.unlink()

    atexit.register(remove)
    return record


def _other_hosts(root: Path) -> list[str]:
    """Registered runs on other machines, and on this one whose process still lives."""
    runs, host, held = root / RUNS_DIR, socket.gethostname(), []
    for record in sorted(runs.glob("*")) if runs.is_dir() else []:
        name, _, pid = record.name.rpartition("-")
        if name != host:
            held.append(f"{name} (pid {pid})")
        elif pid.isdigit() and int(pid) != os.getpid() and _alive(int(pid)):
            held.append(f"{name} (pid {pid})")
        elif pid.isdigit() and int(pid) != os.getpid():
            with contextlib.suppress(OSError):
                record.unlink()  # a dead run's record
    return held


def release_stale_lock(root: str | Path, proc: Path = _PROC) -> str | None:
    """Release a lock no live run holds; the notice to show (None when nothing was done)."""
    root = Path(root)
    locks = sorted((root / LOCK_DIR).glob("*.lock")) if (root / LOCK_DIR).is_dir() else []
    if not locks:
        return None
    live = live_snakemake_pids(root, proc)
    if live is None or live:
        return None
    if _other_hosts(root):
        return None
    for lock in locks:
        with contextlib.suppress(FileNotFoundError):
            lock.unlink()
    return (f"rodimpact: released snakemake's lock of {root.resolve()}: no run holds it (one was killed); "
            "its unfinished outputs are remade")
