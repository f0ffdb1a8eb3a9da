"""A one-node SLURM cluster on this machine, for the workflow's test through a real scheduler.

:class:`LocalSlurm` is a context manager: it writes a ``slurm.conf`` for this machine into a
directory of its own, starts ``munged``, ``slurmctld`` and ``slurmd`` there (no systemd), waits
until the node is idle, and on leaving cancels the jobs left and stops the daemons it started, by
their process ids. Every SLURM command must then see ``SLURM_CONF`` (:meth:`LocalSlurm.env`).

What the configuration is (facts checked with Debian 12's ``slurm-wlm`` 22.05 and ``munge``):

- loopback only: the node's address is 127.0.0.1, the controller listens on free ports of its
  own (``SlurmctldPort``, ``SlurmdPort``), and ``munged`` on a socket in the directory
  (``AuthInfo=socket=...``), so a SLURM or munge already running here is not touched;
- no cgroups (``proctrack/linuxproc``, ``task/none``), no accounting
  (``accounting_storage/none``: ``sacct`` fails, ``squeue`` keeps a finished job for
  ``MinJobAge`` seconds), ``select/cons_tres`` with ``CR_Core_Memory`` so that 1-core jobs
  share the node;
- the node line from ``slurmd -C``, its ``RealMemory`` lowered (:data:`MEMORY_RESERVE_MB`), and
  one partition, the default one.

State, spool, logs, pid files, the munge key and socket: all under the directory. One link
outside it while the cluster runs: ``/run/slurm/conf`` to the directory of ``slurm.conf``, for
the ``srun`` of the jobs, which run without ``SLURM_CONF`` (:meth:`LocalSlurm._link_node_config`).
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import socket
import subprocess
import time
from collections.abc import Callable
from pathlib import Path
from types import TracebackType

#: The Debian packages of SLURM and munge, and the programs they must provide.
PACKAGES = ("slurm-wlm", "munge")
PROGRAMS = ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo", "scontrol", "scancel")
#: Where SLURM's programs look for their configuration without ``SLURM_CONF``: the system's file,
#: then the copy a configless slurmd keeps on its node (a directory).
SYSTEM_CONF = Path("/etc/slurm/slurm.conf")
NODE_CONF_LINK = Path("/run/slurm/conf")
#: What the node leaves to the system (MB): the daemons and the snakemake process that submits.
MEMORY_RESERVE_MB = 2048
#: How long the daemons may take to start and the node to become idle (s).
START_TIMEOUT_S = 60
#: How long a daemon may take to stop on SIGTERM before it is killed (s).
STOP_TIMEOUT_S = 15


class SlurmError(RuntimeError):
    """The local cluster could not be installed, started or used."""


def missing_programs() -> list[str]:
    """The SLURM and munge programs not on the PATH (nor in /usr/sbin, where Debian puts daemons)."""
    path = os.pathsep.join([os.environ.get("PATH", ""), "/usr/sbin", "/sbin"])
    return [name for name in PROGRAMS if shutil.which(name, path=path) is None]


def install() -> bool:
    """Install Debian's ``slurm-wlm`` and ``munge`` when a program of theirs is missing (an
    ``apt-get update`` and a second try when the first install fails); True when it installed."""
    if not missing_programs():
        return False
    command = ["apt-get", "install", "-y", "--no-install-recommends", *PACKAGES]
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    if subprocess.run(command, env=env, capture_output=True, text=True, check=False).returncode != 0:
        subprocess.run(["apt-get", "update"], env=env, capture_output=True, text=True, check=False)
        proc = subprocess.run(command, env=env, capture_output=True, text=True, check=False)
        if proc.returncode != 0:
            raise SlurmError(f"apt-get install {' '.join(PACKAGES)} failed: {proc.stderr.strip()[-500:]}")
    if missing_programs():
        raise SlurmError(f"still missing after installing {' '.join(PACKAGES)}: {', '.join(missing_programs())}")
    return True


def _program(name: str) -> str:
    """The path of a SLURM or munge program."""
    found = shutil.which(name, path=os.pathsep.join([os.environ.get("PATH", ""), "/usr/sbin", "/sbin"]))
    if found is None:
        raise SlurmError(f"{name} not found (install {' '.join(PACKAGES)})")
    return found


def _free_port() -> int:
    """A TCP port of the loopback interface nobody listens on now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def node_line() -> tuple[str, str]:
    """The node's name and its hardware as ``slurmd -C`` prints it (``NodeName=... RealMemory=...``),
    with ``RealMemory`` lowered by :data:`MEMORY_RESERVE_MB` (at least 1000 MB left)."""
    proc = subprocess.run([_program("slurmd"), "-C"], capture_output=True, text=True, check=False)
    line = next((text for text in proc.stdout.splitlines() if text.startswith("NodeName=")), None)
    if proc.returncode != 0 or line is None:
        raise SlurmError(f"slurmd -C printed no node line: {(proc.stdout + proc.stderr).strip()[-300:]}")
    name = re.match(r"NodeName=(\S+)", line).group(1)
    memory = re.search(r"RealMemory=(\d+)", line)
    if memory is None:
        raise SlurmError(f"slurmd -C printed no RealMemory: {line}")
    lowered = max(int(memory.group(1)) - MEMORY_RESERVE_MB, 1000)
    return name, line.replace(memory.group(0), f"RealMemory={lowered}")


class LocalSlurm:
    """A one-node SLURM cluster whose files all live under ``root`` (see the module docstring).

    Parameters
    ----------
    root : path
        An empty directory of its own (a temporary directory).
    min_job_age : int
        ``MinJobAge`` (s): how long ``squeue`` still shows a finished job.
    partition : str
        The name of the node's only partition (the default one).
    """

    def __init__(self, root: Path, *, min_job_age: int = 300, partition: str = "debug") -> None:
        self.root = Path(root).resolve()
        self.min_job_age, self.partition = min_job_age, partition
        self.conf = self.root / "etc" / "slurm.conf"
        self.node = ""
        self.ctld_port = 0
        self._daemons: list[tuple[str, subprocess.Popen]] = []
        self._linked = self._made_run_dir = False

    # ---------------------------------------------------------------- configuration

    def env(self) -> dict[str, str]:
        """This process's environment with ``SLURM_CONF`` pointing at the cluster's configuration."""
        return {**os.environ, "SLURM_CONF": str(self.conf)}

    def _paths(self) -> dict[str, Path]:
        """The cluster's directories under ``root``, by role."""
        names = {"etc": "etc", "state": "state", "spool": "spool", "log": "log", "run": "run", "munge": "munge"}
        return {key: self.root / name for key, name in names.items()}

    def write_config(self) -> Path:
        """Write ``slurm.conf`` (and make its directories); returns its path."""
        paths = self._paths()
        for path in paths.values():
            path.mkdir(mode=0o700, parents=True, exist_ok=True)
        self.node, node = node_line()
        host = socket.gethostname().split(".")[0]
        self.ctld_port = _free_port()
        settings: dict[str, object] = {
            "ClusterName": "rodimpact",
            "SlurmctldHost": f"{host}(127.0.0.1)",
            "SlurmctldPort": self.ctld_port,
            "SlurmdPort": _free_port(),
            "SlurmUser": "root",
            "SlurmdUser": "root",
            "AuthType": "auth/munge",
            "CredType": "cred/munge",
            "AuthInfo": f"socket={paths['munge'] / 'munge.socket'}",
            "StateSaveLocation": paths["state"],
            "SlurmdSpoolDir": paths["spool"],
            "SlurmctldPidFile": paths["run"] / "slurmctld.pid",
            "SlurmdPidFile": paths["run"] / "slurmd.pid",
            "SlurmctldLogFile": paths["log"] / "slurmctld.log",
            "SlurmdLogFile": paths["log"] / "slurmd.log",
            "ProctrackType": "proctrack/linuxproc",
            "TaskPlugin": "task/none",
            "JobAcctGatherType": "jobacct_gather/none",
            "AccountingStorageType": "accounting_storage/none",
            "JobCompType": "jobcomp/none",
            "SelectType": "select/cons_tres",
            "SelectTypeParameters": "CR_Core_Memory",
            "DefMemPerCPU": 1000,
            "SchedulerType": "sched/backfill",
            "MpiDefault": "none",
            "SwitchType": "switch/none",
            "ReturnToService": 2,
            "MinJobAge": self.min_job_age,
            "SlurmdTimeout": 300,
            "InactiveLimit": 0,
            "KillWait": 5,
        }
        lines = [f"{key}={value}" for key, value in settings.items()]
        lines.append(f"{node} NodeAddr=127.0.0.1 State=UNKNOWN")
        lines.append(f"PartitionName={self.partition} Nodes={self.node} Default=YES MaxTime=INFINITE State=UP")
        self.conf.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return self.conf

    def _link_node_config(self) -> None:
        """Make ``/run/slurm/conf`` a link to the directory of ``slurm.conf``.

        A job's snakemake starts its rule with ``srun`` in an environment without ``SLURM_CONF``
        (snakemake-executor-plugin-slurm-jobstep drops every ``SLURM_*`` variable but the job's
        ids), so ``srun`` looks for ``/etc/slurm/slurm.conf`` and then for the configuration a
        configless slurmd keeps on its node, ``/run/slurm/conf/slurm.conf``: this link is that
        second place. Refused when either is there already (this machine has a SLURM of its own).
        """
        if SYSTEM_CONF.exists():
            raise SlurmError(f"{SYSTEM_CONF} exists: jobs would run srun against that cluster, not this one")
        if NODE_CONF_LINK.is_symlink() and not NODE_CONF_LINK.exists():
            NODE_CONF_LINK.unlink()  # left by a run that was killed: its directory is gone
        if NODE_CONF_LINK.exists() or NODE_CONF_LINK.is_symlink():
            raise SlurmError(f"{NODE_CONF_LINK} exists: another slurmd (or another test) uses it")
        self._made_run_dir = not NODE_CONF_LINK.parent.exists()
        NODE_CONF_LINK.parent.mkdir(mode=0o755, parents=True, exist_ok=True)
        NODE_CONF_LINK.symlink_to(self.conf.parent, target_is_directory=True)
        self._linked = True

    def _unlink_node_config(self) -> None:
        """Remove the link :meth:`_link_node_config` made (and ``/run/slurm`` if it made that)."""
        if self._linked and NODE_CONF_LINK.is_symlink() and Path(os.readlink(NODE_CONF_LINK)) == self.conf.parent:
            NODE_CONF_LINK.unlink()
            if self._made_run_dir and not any(NODE_CONF_LINK.parent.iterdir()):
                NODE_CONF_LINK.parent.rmdir()
        self._linked = False

    # ---------------------------------------------------------------- daemons

    def _start(self, name: str, command: list[str]) -> None:
        """Start a daemon in the foreground of its own session (a terminal's Ctrl-C reaches this
        process only, which then stops it); its output goes to ``log/<name>.out``."""
        out = open(self._paths()["log"] / f"{name}.out", "wb")
        try:
            proc = subprocess.Popen(
                command, stdout=out, stderr=subprocess.STDOUT, env=self.env(), start_new_session=True
            )
        finally:
            out.close()
        self._daemons.append((name, proc))

    def _check_alive(self) -> None:
        """Raise when a daemon this object started has exited."""
        for name, proc in self._daemons:
            if proc.poll() is not None:
                raise SlurmError(f"{name} exited with status {proc.returncode}: {self.log_tail(name)}")

    def log_tail(self, name: str, chars: int = 800) -> str:
        """The end of a daemon's log (``munged``, ``slurmctld``, ``slurmd``), on one line."""
        texts = []
        for path in (
            self._paths()["log"] / f"{name}.log",
            self._paths()["log"] / f"{name}.out",
            self._paths()["munge"] / f"{name}.log",
        ):
            if path.is_file():
                texts.append(path.read_text(encoding="utf-8", errors="replace")[-chars:])
        return " | ".join(" ".join(t.split()) for t in texts) or "(no log)"

    def _start_munged(self) -> None:
        """munged with a fresh key of its own, its socket, pid, seed and log files in ``munge/``."""
        munge = self._paths()["munge"]
        key = munge / "munge.key"
        descriptor = os.open(key, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(descriptor, "wb") as handle:
            handle.write(os.urandom(1024))
        self._start(
            "munged",
            [
                _program("munged"),
                "--foreground",
                "--force",
                f"--key-file={key}",
                f"--socket={munge / 'munge.socket'}",
                f"--pid-file={munge / 'munged.pid'}",
                f"--seed-file={munge / 'munged.seed'}",
                f"--log-file={munge / 'munged.log'}",
            ],
        )
        self._wait(lambda: (munge / "munge.socket").exists(), "munged's socket")

    def _wait(self, ready: Callable[[], bool], what: str, timeout: float = START_TIMEOUT_S) -> None:
        """Poll ``ready()`` until it is true; raise when a daemon exits or ``timeout`` passes."""
        deadline = time.monotonic() + timeout
        while not ready():
            self._check_alive()
            if time.monotonic() > deadline:
                raise SlurmError(
                    f"timed out after {timeout:.0f} s waiting for {what}: "
                    f"{self.log_tail('slurmctld')} {self.log_tail('slurmd')}"
                )
            time.sleep(0.5)

    def command(self, *args: str, check: bool = True, timeout: float = 30) -> subprocess.CompletedProcess:
        """A SLURM client command (``sinfo``, ``squeue``...) against this cluster."""
        proc = subprocess.run(
            [_program(args[0]), *args[1:]], env=self.env(), capture_output=True, text=True, check=False, timeout=timeout
        )
        if check and proc.returncode != 0:
            raise SlurmError(f"{' '.join(args)} failed: {proc.stderr.strip()}")
        return proc

    def node_state(self) -> str:
        """The node's state as ``sinfo`` prints it (``idle``, ``mixed``, ``down*``...; "" when unknown)."""
        proc = self.command("sinfo", "--noheader", "--format=%T", f"--nodes={self.node}", check=False, timeout=10)
        return proc.stdout.strip() if proc.returncode == 0 else ""

    def start(self) -> None:
        """Write the configuration, start the daemons and wait until the node is idle."""
        self.write_config()
        self._link_node_config()
        self._start_munged()
        self._start("slurmctld", [_program("slurmctld"), "-D", "-i", "-f", str(self.conf)])
        self._wait(
            lambda: self.command("scontrol", "ping", check=False, timeout=10).returncode == 0, "slurmctld to answer"
        )
        self._start("slurmd", [_program("slurmd"), "-D", "-N", self.node, "-f", str(self.conf)])
        self._wait(lambda: self.node_state() == "idle", f"node {self.node} to be idle")

    def cancel_jobs(self, timeout: float = STOP_TIMEOUT_S) -> None:
        """Cancel every job of this cluster and wait (up to ``timeout``) until none runs."""
        listed = self.command("squeue", "--noheader", "--format=%A", check=False, timeout=10)
        jobs = listed.stdout.split() if listed.returncode == 0 else []
        if not jobs:
            return
        self.command("scancel", *jobs, check=False, timeout=10)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            running = self.command(
                "squeue", "--noheader", "--format=%A", "--states=RUNNING,COMPLETING", check=False, timeout=10
            )
            if running.returncode != 0 or not running.stdout.split():
                return
            time.sleep(0.5)

    def stop(self) -> None:
        """Cancel the jobs left, then stop the daemons this object started (slurmd, slurmctld,
        munged: the reverse order), each by its process id: SIGTERM, then SIGKILL after
        :data:`STOP_TIMEOUT_S`."""
        if any(name == "slurmctld" and proc.poll() is None for name, proc in self._daemons):
            try:
                self.cancel_jobs()
            except (SlurmError, subprocess.TimeoutExpired, OSError):
                pass  # the daemons are stopped below whatever the jobs do
        for _name, proc in reversed(self._daemons):
            if proc.poll() is None:
                proc.send_signal(signal.SIGTERM)
                try:
                    proc.wait(timeout=STOP_TIMEOUT_S)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
        self._daemons.clear()
        self._unlink_node_config()

    def __enter__(self) -> LocalSlurm:
        try:
            self.start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, traceback: TracebackType | None
    ) -> None:
        self.stop()
