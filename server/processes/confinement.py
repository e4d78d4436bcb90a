"""The limits a sandboxed node process takes on as it starts, before any of the student's code runs.

The sandbox (server/processes/sandbox.py) passes them in ``$ROS2LAB_SANDBOX``; the runner applies
them first thing: rlimits on memory (its data: heap, stacks and private mappings; not the address
space, which Zenoh's threads reserve by the hundred MiB unused), processes, open files, file size
and CPU time; a lower CPU priority than the sims (nice, for its session's scheduling group too:
server/processes/priority.py); and, when the sandbox was started by root, a uid and gid of its
own with no supplementary groups (which also drops every capability). Hard limits go down with the
soft ones, so the node cannot raise them again.

Processes are counted per user namespace (Linux 5.14 and later), so a non-root server's sandboxes
each get their own 64 without the server's own threads counted in; under a root server, per uid,
and each world's nodes have a uid of their own (``for_domain``).
"""

from __future__ import annotations

import dataclasses
import os
import resource
from dataclasses import dataclass, fields
from pathlib import Path

from .priority import run_below_sims

LIMITS_ENV = "ROS2LAB_SANDBOX"
MIB = 1024 * 1024
EXIT_MEMORY = 137  # as a shell reports a process killed by SIGKILL: the node was ended for its memory


@dataclass(frozen=True)
class Confinement:
    """What one sandboxed node process may use."""

    memory_mib: int = 512  # its private writable memory: heap, stacks, mappings (RLIMIT_DATA)
    processes: int = 64  # processes and threads in its sandbox (RLIMIT_NPROC)
    open_files: int = 256  # RLIMIT_NOFILE
    file_size_mib: int = 64  # the largest file it may write (RLIMIT_FSIZE)
    cpu_s: int = 3600  # CPU seconds of one run (RLIMIT_CPU)
    nice: int = 19  # added to its niceness (19 at most): the sims' loop goes first
    uid: int = 61000  # a server running as root starts the node as this user (plus its ROS domain)
    gid: int = 61000
    drop_root: bool = False  # started by root: become ``uid``/``gid``

    def encode(self, *, drop_root: bool) -> str:
        values = {f.name: getattr(self, f.name) for f in fields(self)} | {"drop_root": int(drop_root)}
        return ",".join(f"{k}={int(v)}" for k, v in values.items())

    @classmethod
    def decode(cls, text: str) -> Confinement:
        pairs = dict(item.split("=", 1) for item in text.split(",") if "=" in item)
        known = {f.name for f in fields(cls)}
        values = {k: int(v) for k, v in pairs.items() if k in known and k != "drop_root"}
        return cls(**values, drop_root=pairs.get("drop_root") == "1")

    def apply(self) -> None:
        """Take the limits on, in this process (the runner, before the student's code)."""
        limits = {
            resource.RLIMIT_DATA: self.memory_mib * MIB,
            resource.RLIMIT_NPROC: self.processes,
            resource.RLIMIT_NOFILE: self.open_files,
            resource.RLIMIT_FSIZE: self.file_size_mib * MIB,
            resource.RLIMIT_CPU: self.cpu_s,
        }
        for which, value in limits.items():
            resource.setrlimit(which, (value, value))
        run_below_sims(self.nice)  # with its session's group: bubblewrap made it a session leader
        if self.drop_root and os.getuid() == 0:
            os.setgroups([])
            os.setgid(self.gid)
            os.setuid(self.uid)

    def give(self, workspace: Path) -> None:
        """Make ``workspace`` the node's own (a root server's node runs as ``uid``, not as root)."""
        for path in [workspace, *workspace.rglob("*")]:
            info = path.lstat()
            if (info.st_uid, info.st_gid) != (self.uid, self.gid):
                os.lchown(path, self.uid, self.gid)

    def for_domain(self, domain_id: int) -> Confinement:
        """The limits of a node of the world in ROS domain ``domain_id``: its own uid and gid."""
        return dataclasses.replace(self, uid=self.uid + domain_id, gid=self.gid + domain_id)

    def memory_line(self) -> str:
        return f"node killed: memory limit {self.memory_mib} MiB"


def from_env() -> Confinement | None:
    text = os.environ.get(LIMITS_ENV)
    return Confinement.decode(text) if text else None
