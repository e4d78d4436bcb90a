"""The classroom as the API sees it, in either role: ``Classroom``, the one interface the API
calls, which the class server (class_server.py) and a world worker (worker_worlds.py) both have.

Where the roles differ, each answers for itself: a world worker has no world workers, no class
graph, no instructor's view and no bridges of its own (None), nothing to charge a write to (its
class server charged it), no load, queue or saved students of the class (``NotHereError``), and
takes no join (``JoinThroughClassServerError``); a class server hosts no world for another
(``NotHereError``). So the API never asks which role it serves.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from node_runtime.transport.acl import ClassAuth, Credentials
    from node_runtime.transport.domain_bridge import DomainBridge
    from server.classroom.class_bridges import ClassBridges
    from server.classroom.class_load import PlaceReport
    from server.classroom.class_server import ClassServer
    from server.classroom.load import CpuMeter
    from server.classroom.local_workers import LocalWorkers
    from server.classroom.tokens import Grant
    from server.classroom.worker_worlds import WorldWorker
    from server.classroom.workers import WorkerDirectory
    from server.classroom.world import World
    from server.host.processes.start_pacing import StartPacer
    from server.host.settings import ClassroomSettings, Settings
    from server.peripherals.viewer.class_view import ClassView
    from server.world.checkpoints.progress import Progress


class Classroom(Protocol):
    """A class server or a world worker: its worlds, who may act on them, and what the API asks of it."""

    # -- what it is ----------------------------------------------------------------------------
    @property
    def settings(self) -> Settings: ...
    @property
    def class_settings(self) -> ClassroomSettings: ...
    @property
    def code(self) -> str:
        """The class code (a world worker's is never told: joins go to its class server)."""
        ...

    @property
    def cpu(self) -> CpuMeter: ...
    @property
    def worlds(self) -> dict[str, World]: ...
    @property
    def hosted_here(self) -> int:
        """Worlds this process runs itself."""
        ...

    @property
    def local_capacity(self) -> int: ...
    @property
    def start_pacer(self) -> StartPacer:
        """The turns node processes of its worlds take to start."""
        ...

    @property
    def zenoh_auth(self) -> ClassAuth: ...
    def router_endpoint(self) -> str | None: ...

    # -- a class server's own (None on a world worker) -----------------------------------------
    @property
    def workers(self) -> WorkerDirectory | None:
        """The world workers it places worlds on (None: none, or no class router)."""
        ...

    @property
    def local_workers(self) -> LocalWorkers | None:
        """The world workers it started on its machine (``--workers``)."""
        ...

    @property
    def class_graph(self) -> DomainBridge | None:
        """The class's own ROS domain, every world under its name."""
        ...

    @property
    def bridges(self) -> ClassBridges | None:
        """The instructor's rosbridge and Foxglove on the class's domain."""
        ...

    @property
    def view(self) -> ClassView | None:
        """The instructor's 3D view of every world."""
        ...

    # -- start and stop ------------------------------------------------------------------------
    async def open(self) -> None: ...
    async def stop(self) -> None: ...

    # -- who is calling ------------------------------------------------------------------------
    def grant(self, token: str | None) -> Grant | None:
        """The grant of a genuine, current token (None: none)."""
        ...

    def world_for(self, grant: Grant, asked: str | None) -> World:
        """The world a call with ``grant`` acts on, naming ``asked`` (or none)."""
        ...

    def get(self, name: str) -> World: ...
    def charge_write(self, world: World) -> None:
        """A student's write to ``world``: one of its writes a second (RateLimitedError over them)."""
        ...

    def charge_reset(self, name: str) -> None:
        """A student's reset of world ``name``: one of its resets and one of its writes."""
        ...

    # -- worlds --------------------------------------------------------------------------------
    async def join(
        self, student: str, code: str, address: str = "unknown", token: str | None = None
    ) -> tuple[World, str]:
        """A student's own world and its token (``JoinWaits``: it waits in the join queue)."""
        ...

    async def poll_join(self, ticket: str) -> tuple[World, str]:
        """A waiting join, asked again."""
        ...

    async def host(
        self,
        name: str,
        student: str,
        domain_id: int,
        launch: str,
        launch_args: dict[str, str],
        login: Credentials | None = None,
        router_socket: str | None = None,
        progress: Mapping[str, Any] | None = None,
    ) -> World:
        """A world its class server placed here, with its progress handed over in wire form."""
        ...

    async def reset(self, name: str) -> World: ...
    async def kick(self, name: str, *, remove_workspace: bool = False) -> World:
        """Remove world ``name``; its workspace too when ``remove_workspace`` (a class server
        always removes it)."""
        ...

    async def describe_all(self) -> list[dict[str, Any]]: ...
    async def broadcast_on_workers(self, body: dict[str, Any]) -> tuple[list[str], dict[str, str]]:
        """The instructor's broadcast in the worlds its world workers host: those reached, those
        refused and why."""
        ...

    # -- the class's load and join queue -------------------------------------------------------
    async def class_load(self) -> PlaceReport:
        """Each place's load, the capacity verdict, and the join queue as it is now."""
        ...

    def let_through(self, count: int) -> dict[str, Any]:
        """Let ``count`` waiting joins past a full verdict; the queue as it is then."""
        ...

    # -- checkpoints ---------------------------------------------------------------------------
    def not_joined(self) -> list[tuple[str, Progress]]:
        """Saved students not joined since it started, by world, and their progress."""
        ...

    async def not_joined_with_captures(self) -> list[tuple[str, Progress]]:
        """The same, each with its captures (for its report)."""
        ...

    async def worker_checkpoints(self, checkpoints: list[str]) -> tuple[list[dict[str, Any]], dict[str, str]]:
        """The checkpoint table's rows of the worlds on world workers, and the workers that did not answer."""
        ...

    async def worker_reports(self) -> tuple[list[tuple[str, bytes]], dict[str, str]]:
        """The signed reports of the worlds on world workers, and why each world without one has none."""
        ...

    async def release_progress(self, name: str) -> str:
        """Give world ``name``'s saved progress to the next join under its name; whose it was."""
        ...


if TYPE_CHECKING:
    # mypy --strict checks here, member by member, that both roles are a Classroom.
    def _roles(server: ClassServer, worker: WorldWorker) -> tuple[Classroom, Classroom]:
        return server, worker
