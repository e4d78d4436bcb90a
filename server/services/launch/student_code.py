"""How a lab runs its students' node processes: in a sandbox where it serves others, refused (and
why) where it serves others but no sandbox can be built, and as its user on a single lab."""

from __future__ import annotations

from pathlib import Path

from node_runtime.process.confinement import Confinement
from server.host.processes.sandbox import Sandbox, StudentCodeRefusedError, probe
from server.host.settings import Settings


def for_lab(settings: Settings, socket: Path | None) -> Sandbox | StudentCodeRefusedError | None:
    """How a lab runs students' nodes: in a sandbox, not at all (why), or as today (None: a single
    lab on loopback, or ``--student-code unsandboxed``)."""
    if not settings.sandboxes_students:
        return None
    why = probe()
    if why is None and socket is None:
        why = "its Zenoh router has no Unix socket on this machine for the sandbox to reach"
    if why is not None or socket is None:
        return StudentCodeRefusedError(why or "")
    limits = settings.sandbox
    return Sandbox(
        socket,
        Confinement(
            memory_mib=limits.memory_mib,
            processes=limits.processes,
            open_files=limits.open_files,
            file_size_mib=limits.file_size_mib,
            cpu_s=limits.cpu_s,
            nice=limits.nice,
        ),
    )
