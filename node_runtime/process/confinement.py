"""The limits a sandboxed node process takes on as it starts, before any of the student's code runs.

The sandbox (server/host/processes/sandbox.py) passes them in ``$ROS2LAB_SANDBOX``; the runner applies
them first thing: rlimits on memory (its data: heap, stacks and private mappings), processes, open
files, file size and CPU time, and a lower CPU priority than the sims (nice, for its session's
scheduling group too: node_runtime/process/priority.py), which it may never raise again: no
real-time priority and no niceness below its own (``RLIMIT_RTPRIO`` and ``RLIMIT_NICE`` 0, whatever
the server's were: a server given ``ulimit -r`` for its worlds' loop would otherwise pass it on).
Hard limits go down with the soft ones, so the node cannot raise them again. Where the machine
gives the server no memory cgroup
(server/host/processes/cgroups.py), which counts shared mappings and tmpfs pages too, the address space
is limited as well (``RLIMIT_AS``, with room for what Zenoh's threads reserve and never touch).

The uid is not changed here: under a root server, ``setpriv`` made the process a uid of its world's
before Python started (the sandbox's command). Processes are counted per user namespace (Linux 5.14
and later), so a non-root server's sandboxes each get their own 64 without the server's own
threads counted in; under a root server, per uid, and each world's nodes have a uid of their own
(``for_domain``).
"""

from __future__ import annotations

import dataclasses
import os
import resource
from dataclasses import dataclass, fields

from node_runtime.process.priority import run_below_sims

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
    address_space_mib: int = 0  # RLIMIT_AS where no cgroup counts the memory (0: not limited)
    reserved_mib: int = 1536  # what the address space may hold beyond memory_mib: unused reservations

    def encode(self) -> str:
        return ",".join(f"{f.name}={int(getattr(self, f.name))}" for f in fields(self))

    @classmethod
    def decode(cls, text: str) -> Confinement:
        pairs = dict(item.split("=", 1) for item in text.split(",") if "=" in item)
        known = {f.name for f in fields(cls)}
        return cls(**{k: int(v) for k, v in pairs.items() if k in known})

    def counting_address_space(self) -> Confinement:
        """These limits with the address space limited too (no cgroup counts shared memory)."""
        return dataclasses.replace(self, address_space_mib=self.memory_mib + self.reserved_mib)

    def apply(self) -> None:
        """Take the limits on, in this process (the runner, before the student's code)."""
        limits = {
            resource.RLIMIT_DATA: self.memory_mib * MIB,
            resource.RLIMIT_NPROC: self.processes,
            resource.RLIMIT_NOFILE: self.open_files,
            resource.RLIMIT_FSIZE: self.file_size_mib * MIB,
            resource.RLIMIT_CPU: self.cpu_s,
            resource.RLIMIT_RTPRIO: 0,  # no real-time class: the worlds' loop goes first
            resource.RLIMIT_NICE: 0,  # no niceness below what it was given
        }
        if self.address_space_mib:
            limits[resource.RLIMIT_AS] = self.address_space_mib * MIB
        for which, value in limits.items():
            resource.setrlimit(which, (value, value))
        run_below_sims(self.nice)  # with its session's group: bubblewrap made it a session leader

    def for_domain(self, domain_id: int) -> Confinement:
        """The limits of a node of the world in ROS domain ``domain_id``: its own uid and gid."""
        return dataclasses.replace(self, uid=self.uid + domain_id, gid=self.gid + domain_id)

    def memory_line(self) -> str:
        return f"node killed: memory limit {self.memory_mib} MiB"


def from_env() -> Confinement | None:
    text = os.environ.get(LIMITS_ENV)
    return Confinement.decode(text) if text else None
