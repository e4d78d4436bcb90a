"""Who published a message: a node of the app's own process, or one of another process, told by the
GID its sample carried; and whether that process runs the student's own code."""

from __future__ import annotations

from collections.abc import Callable

from node_runtime.ament.index import PackageIndex
from node_runtime.bus import Publisher
from node_runtime.transport.remote_graph import RemoteGraph
from server.services.launch.launcher import Launcher
from server.world.checkpoints.events import UNKNOWN, Source

MAX_KNOWN = 256


class Sources:
    def __init__(
        self, launcher: Launcher, packages: PackageIndex, remote: Callable[[], RemoteGraph | None]
    ) -> None:
        self._launcher = launcher
        self._packages = packages
        self._remote = remote
        self._known: dict[bytes, Source] = {}

    def of(self, source: object) -> Source:
        if isinstance(source, Publisher):
            # Nodes inside the app are the lab's: a student's file always runs as its own process.
            return Source(source.node.fully_qualified_name)
        if not isinstance(source, bytes):
            return UNKNOWN
        known = self._known.get(source)
        if known is not None:
            return known
        remote = self._remote()
        found = remote.publisher(source) if remote is not None else None
        if found is None:
            return UNKNOWN  # not kept: its token may arrive later
        node, zid = found
        assert remote is not None
        student, label = self._process(zid, remote)
        if len(self._known) >= MAX_KNOWN:
            self._known.clear()
        known = self._known[source] = Source(node, label, student)
        return known

    def _process(self, zid: str, remote: RemoteGraph) -> tuple[bool, str]:
        """Whether session ``zid`` runs the student's code, and where it runs. A process the lab
        started is the student's when it runs a file of their workspace; one the lab did not start
        (``ros2lab run``, another machine) is the student's too: every node of the lab's own
        packages is started by the lab."""
        for entry in self._launcher.launched:
            process = entry.process
            if process is None or process.command.zid != zid:
                continue
            return self.student_executable(entry.action.pkg, entry.action.exec), remote.location(zid)
        return True, remote.location(zid)

    def student_executable(self, pkg: str, exe: str) -> bool:
        try:
            found = self._packages.resolve(pkg, exe)
        except (LookupError, ValueError):
            return False
        return found.file is not None or found.entry_point is not None
