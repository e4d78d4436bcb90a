"""A sandboxed node's control group: its memory counted whole and its processes counted, where the
machine lets this server make groups below its own.

An rlimit counts one process's private memory (``RLIMIT_DATA``): shared mappings and files in a
tmpfs (``/dev/shm``) escape it, and a node that fills them takes the machine's memory. A memory
cgroup charges every page the node's processes touch, shared or not, tmpfs included, and the
kernel ends the group's biggest process when the group is over its limit. Both cgroup versions are
read: version 1's ``memory`` and ``pids`` hierarchies (each a folder of its own) or version 2's one
hierarchy, where this server first moves itself into a leaf of its group (a version 2 group that
holds processes cannot give its children controllers) and enables ``memory`` and ``pids`` below it.

The groups live in ``ros2lab-<server pid>`` below the server's own group, one per node process,
removed as each node ends; a server that finds the folder of a server that is gone ends what is
left in it and removes it. A node joins its group before anything of it runs: its command starts
with a shell that writes its own pid into the group's ``cgroup.procs`` and then becomes bubblewrap.

Where the machine also gives the ``cpu`` controller, all of a server's nodes share one CPU group
(version 1: ``ros2lab-<server pid>`` in the cpu hierarchy, which every node joins too; version 2:
the folder their groups are made in), weighed as ``CPU_SHARES`` against a nice-0 process group's
1024. A niceness is not enough for a class: each sandboxed node leads a session of its own, whose
scheduling group (autogroup) the scheduler weighs apart, so sixty nodes at nice 19 (15 each)
weighed 900 together, nearly a second server beside the worlds', while they started and while
they spun. Together in one group they weigh ``CPU_SHARES`` however many they are, and still take
whatever CPU the worlds leave. Where the kernel offers it (Linux 5.15 and newer, both versions),
the group is also made idle (``cpu.idle``): it then weighs the least a group can, and a world's
loop that wakes takes the core from a node at once. A weight alone does not give that: the loops
are the machine's heaviest threads, run ahead of their fair share, and so waited for a starting
node's slice to end at many of their ticks.
"""

from __future__ import annotations

import contextlib
import functools
import logging
import os
import signal
import time
from dataclasses import dataclass
from pathlib import Path

log = logging.getLogger(__name__)

PREFIX = "ros2lab-"
MIB = 1024 * 1024
REMOVE_TRIES = 10
REMOVE_WAIT_S = 0.05
CPU_SHARES = 64  # version 1's cpu.shares of all of a server's nodes together (a nice-0 group: 1024)
CPU_WEIGHT = 6  # the same for version 2's cpu.weight (its default 100 stands for 1024)
JOIN_SCRIPT = 'while [ "$1" != -- ]; do echo $$ > "$1" || exit 125; shift; done; shift; exec "$@"'


@dataclass(frozen=True)
class NodeCgroup:
    """The groups one node process runs in (one folder for version 2, two for version 1)."""

    folders: tuple[Path, ...]
    version: int
    shared: tuple[Path, ...] = ()  # groups it joins with the server's other nodes (CPU): not its own

    def join_prefix(self) -> list[str]:
        """A command prefix that puts the command into these groups, then runs it (exec)."""
        return [
            "/bin/sh",
            "-c",
            JOIN_SCRIPT,
            "ros2lab-cgroup",
            *(str(f / "cgroup.procs") for f in (*self.folders, *self.shared)),
            "--",
        ]

    def oom_kills(self) -> int:
        """How many of its processes the kernel ended for the group's memory limit."""
        name = "memory.events" if self.version == 2 else "memory.oom_control"
        for folder in self.folders:
            with contextlib.suppress(OSError):
                for line in (folder / name).read_text().splitlines():
                    key, _, value = line.partition(" ")
                    if key == "oom_kill":
                        return int(value)
        return 0

    def remove(self) -> None:
        """End what is left in it and remove it (its node has ended). The kernel may take a moment
        to let the last processes of the sandbox go: a few tries, on the node's own output thread."""
        for folder in self.folders:
            for _ in range(REMOVE_TRIES):
                _empty(folder)
                try:
                    folder.rmdir()
                    break
                except FileNotFoundError:
                    break
                except OSError:  # EBUSY: a process is still leaving
                    time.sleep(REMOVE_WAIT_S)


@dataclass(frozen=True)
class CgroupParent:
    """Where this server makes its nodes' groups: version 1's memory and pids folders, or version
    2's one folder (``pids`` is then the same); ``cpu``: version 1's group every node joins as
    well, where there is one (version 2's folder is weighed itself: ``cpu_weighed``)."""

    memory: Path
    pids: Path
    version: int
    cpu: Path | None = None
    cpu_weighed: bool = False  # the nodes' CPU counts as one group's (see the module)
    cpu_idle: bool = False  # and that group is idle: a world's loop that wakes takes a node's core

    def make(self, name: str, memory_mib: int, processes: int) -> NodeCgroup:
        """A new group ``name`` with these limits (OSError if the kernel refuses one)."""
        folders = tuple(dict.fromkeys([self.memory / name, self.pids / name]))
        stale = NodeCgroup(tuple(f for f in folders if f.exists()), self.version)
        stale.remove()  # one of the same name that a node left behind
        group = NodeCgroup(folders, self.version, (self.cpu,) if self.cpu is not None else ())
        try:
            for folder in folders:
                folder.mkdir()
            self._limit(folders, memory_mib, processes)
        except OSError:
            group.remove()  # none left half made
            raise
        return group

    def _limit(self, folders: tuple[Path, ...], memory_mib: int, processes: int) -> None:
        limit = str(memory_mib * MIB)
        if self.version == 2:
            (folders[0] / "memory.max").write_text(limit)
            with contextlib.suppress(OSError):  # no swap accounting: nothing to cap
                (folders[0] / "memory.swap.max").write_text("0")
            (folders[0] / "pids.max").write_text(str(processes))
        else:
            memory, pids = folders
            (memory / "memory.limit_in_bytes").write_text(limit)
            with contextlib.suppress(OSError):  # swap accounting may be off (no memsw files)
                (memory / "memory.memsw.limit_in_bytes").write_text(limit)
            (pids / "pids.max").write_text(str(processes))


def _empty(folder: Path) -> None:
    """SIGKILL every process left in a group (bounded: a group of a node holds a few dozen)."""
    for _ in range(3):
        try:
            pids = [int(p) for p in (folder / "cgroup.procs").read_text().split()]
        except OSError:
            return
        if not pids:
            return
        for pid in pids:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(pid, signal.SIGKILL)


def _mounts() -> list[tuple[str, str, str, str]]:
    """(root in its hierarchy, mount point, file system type, super options) of each cgroup mount."""
    out = []
    with contextlib.suppress(OSError):
        for line in Path("/proc/self/mountinfo").read_text().splitlines():
            fields = line.split()
            dash = fields.index("-")
            kind, options = fields[dash + 1], fields[dash + 3] if len(fields) > dash + 3 else ""
            if kind in ("cgroup", "cgroup2"):
                out.append((fields[3], fields[4], kind, options))
    return out


def _own_groups() -> dict[str, str]:
    """This process's group path per controller (version 2's under the key '')."""
    out: dict[str, str] = {}
    with contextlib.suppress(OSError):
        for line in Path("/proc/self/cgroup").read_text().splitlines():
            _id, controllers, path = line.split(":", 2)
            for name in controllers.split(",") if controllers else [""]:
                out[name] = path
    return out


def _folder(mount_root: str, mount_point: str, path: str) -> Path | None:
    """The folder of group ``path`` through a mount of its hierarchy's ``mount_root``."""
    relative = os.path.relpath(path, mount_root)
    if relative.startswith(".."):
        return None
    return Path(mount_point) / relative if relative != "." else Path(mount_point)


def _version_1(own: dict[str, str], mounts: list[tuple[str, str, str, str]]) -> tuple[Path, Path] | None:
    found: dict[str, Path] = {}
    for root, point, kind, options in mounts:
        for controller in ("memory", "pids"):
            if kind == "cgroup" and controller in options.split(",") and controller in own:
                folder = _folder(root, point, own[controller])
                if folder is not None and os.access(folder, os.W_OK):
                    found.setdefault(controller, folder)
    return (found["memory"], found["pids"]) if len(found) == 2 else None


def _version_1_cpu(own: dict[str, str], mounts: list[tuple[str, str, str, str]]) -> Path | None:
    """This process's group in version 1's cpu hierarchy, if this server may write there."""
    for root, point, kind, options in mounts:
        if kind == "cgroup" and "cpu" in options.split(",") and "cpu" in own:
            folder = _folder(root, point, own["cpu"])
            if folder is not None and os.access(folder, os.W_OK):
                return folder
    return None


def _cpu_group_version_1(base: Path) -> Path | None:
    """All this server's nodes' CPU group below ``base``, weighed ``CPU_SHARES`` (None, and none
    left, where the kernel refuses it: the nodes then count by their niceness alone)."""
    folder = base / f"{PREFIX}{os.getpid()}"
    try:
        _sweep(base)
        folder.mkdir(exist_ok=True)
        (folder / "cpu.shares").write_text(str(CPU_SHARES))
    except OSError as exc:
        log.warning("students' nodes not weighed as one CPU group: %s", exc)
        with contextlib.suppress(OSError):
            folder.rmdir()
        return None
    return folder


def _idle(folder: Path) -> bool:
    """Make the nodes' CPU group idle; False where the kernel has no ``cpu.idle`` (older than 5.15)
    or refuses it: the group then counts by its weight alone."""
    try:
        (folder / "cpu.idle").write_text("1")
    except OSError as exc:
        log.info("students' nodes' CPU group not made idle (%s): it counts by its weight", exc)
        return False
    return True


def _version_2(own: dict[str, str], mounts: list[tuple[str, str, str, str]]) -> Path | None:
    for root, point, kind, _options in mounts:
        if kind != "cgroup2" or "" not in own:
            continue
        folder = _folder(root, point, own[""])
        if folder is None:
            continue
        with contextlib.suppress(OSError):
            if {"memory", "pids"} <= set((folder / "cgroup.controllers").read_text().split()):
                return folder
    return None


def _delegate_version_2(folder: Path) -> tuple[Path, bool]:
    """Move this server into a leaf of its group and give the group's children memory and pids
    (OSError where the kernel or another process in the group forbids it), and cpu where it may:
    the nodes' folder, and whether its CPU is weighed as ``CPU_WEIGHT``."""
    leaf = folder / f"{PREFIX}{os.getpid()}-server"
    leaf.mkdir(exist_ok=True)
    (leaf / "cgroup.procs").write_text(str(os.getpid()))
    (folder / "cgroup.subtree_control").write_text("+memory +pids")
    nodes = folder / f"{PREFIX}{os.getpid()}"
    nodes.mkdir(exist_ok=True)
    (nodes / "cgroup.subtree_control").write_text("+memory +pids")
    try:
        (folder / "cgroup.subtree_control").write_text("+cpu")
        (nodes / "cpu.weight").write_text(str(CPU_WEIGHT))
    except OSError as exc:
        log.warning("students' nodes not weighed as one CPU group: %s", exc)
        return nodes, False
    return nodes, True


def _sweep(parent: Path) -> None:
    """End and remove the node groups of servers that are gone (killed before they could)."""
    for folder in parent.glob(f"{PREFIX}*"):
        pid = folder.name[len(PREFIX) :].split("-")[0]
        if not pid.isdigit() or int(pid) == os.getpid() or Path(f"/proc/{pid}").exists():
            continue
        for node in [p for p in folder.iterdir() if p.is_dir()]:
            NodeCgroup((node,), 1).remove()
        _empty(folder)
        with contextlib.suppress(OSError):
            folder.rmdir()


@functools.cache
def parent() -> CgroupParent | str:
    """Where this server's nodes' groups go, or why there are none (in one line)."""
    own, mounts = _own_groups(), _mounts()
    found_1 = _version_1(own, mounts)
    if found_1 is not None:
        memory, pids = found_1
        try:
            for base in (memory, pids):
                _sweep(base)
            made = [base / f"{PREFIX}{os.getpid()}" for base in (memory, pids)]
            for folder in made:
                folder.mkdir(exist_ok=True)
        except OSError as exc:
            return f"cgroup v1 memory and pids folders refuse a group ({exc.strerror})"
        cpu_base = _version_1_cpu(own, mounts)
        cpu = _cpu_group_version_1(cpu_base) if cpu_base is not None else None
        return CgroupParent(made[0], made[1], 1, cpu, cpu is not None, cpu is not None and _idle(cpu))
    found_2 = _version_2(own, mounts)
    if found_2 is None:
        return "no cgroup with memory and pids controllers that this server may write"
    try:
        _sweep(found_2)
        nodes, weighed = _delegate_version_2(found_2)
    except OSError as exc:
        return f"its cgroup v2 group cannot give memory and pids to groups below it ({exc.strerror})"
    return CgroupParent(nodes, nodes, 2, None, weighed, weighed and _idle(nodes))
