"""A world worker's worlds: those a class server placed here, in the ROS domains it chose.

A world worker (``ros2lab world-worker``, server/world_worker.py) runs the app as this role: it
answers the class server's hellos on the class's router (worker_control.py), starts the worlds
the class server asks it to host and ends them when asked. Every call comes from the class
server: its own and the instructor's with the worker's API token, a student's forwarded with a
credential for that world alone (workers.py). When the class server has been silent for the
worker's orphan timeout, every world here is freed: nobody can reach them, and its replacement
starts them anew.
"""

from __future__ import annotations

import asyncio
import dataclasses
import hmac
import logging
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from node_runtime.bus import Clock, ExecutorGroup, SystemClock
from node_runtime.transport.acl import ClassAuth, Credentials
from node_runtime.transport.socket_relay import SocketRelay, tcp_target
from server.base.tasks import cancel_and_wait
from server.classroom.admission import new_code
from server.classroom.class_load import PlaceReport
from server.classroom.errors import (
    BadHandoverError,
    ClassFullError,
    JoinThroughClassServerError,
    NameTakenError,
    NotHereError,
    UnknownWorldError,
)
from server.classroom.grants import Grants, world_for
from server.classroom.lateness import late_worlds
from server.classroom.load import CpuMeter, machine_id
from server.classroom.tokens import Grant, TokenSigner
from server.classroom.workers import WATCH_PERIOD_S, worker_api_token, world_of_call_token
from server.classroom.world import World
from server.classroom.worlds import WorldLabs
from server.host.processes.start_pacing import StartPacer
from server.host.settings import Settings, class_section
from server.services.workspace.class_mark import read_mark
from server.services.workspace.location import remove_world_workspace
from server.world.checkpoints.catalog import load as load_checkpoints
from server.world.checkpoints.handover import from_wire
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.saved import SavedProgressError

if TYPE_CHECKING:
    from node_runtime.transport.domain_bridge import DomainBridge
    from server.classroom.class_bridges import ClassBridges
    from server.classroom.local_workers import LocalWorkers
    from server.classroom.workers import WorkerDirectory
    from server.peripherals.viewer.class_view import ClassView

log = logging.getLogger("classroom")
NO_LOAD_HERE = "this is a world worker: its class server has the class's load and queue"


def socket_here(path: str) -> Path | None:
    """``path`` when it is a Unix socket on this machine (the class router's), else None."""
    found = Path(path)
    try:
        return found if found.is_absolute() and found.is_socket() else None
    except (OSError, ValueError):  # a name too long, a NUL: no socket here
        return None


class WorldWorker:
    """The worlds hosted for one class server; ``settings.worker`` says which and how (a
    ``Classroom``, roles.py: what only a class server has or does, it has not or refuses)."""

    def __init__(
        self,
        settings: Settings,
        clock: Clock | None = None,
        *,
        code: str | None = None,
        signer: TokenSigner | None = None,
    ) -> None:
        if settings.worker is None:
            raise ValueError("a world worker needs its worker settings (settings.worker)")
        self.settings = settings
        self.class_settings = class_section(settings)
        self.role = settings.worker
        self.clock: Clock = clock or SystemClock()
        self.code = code or new_code()  # joins go to the class server: nobody is told this one
        self.grants = Grants(signer)
        # The class router's Unix socket when it is on this machine (the class server says where),
        # else this worker's relay to the router's TCP endpoint (socket_relay.py).
        self._router_socket: Path | None = None
        self._relay: SocketRelay | None = None
        self.labs = WorldLabs(settings, self.clock, self.router_endpoint, self.router_socket)
        # This process's and machine's CPU: each hello (every WATCH_PERIOD_S) reads it, so a
        # load covers the last seconds.
        self.cpu = CpuMeter(machine=machine_id())
        self._worker_token = worker_api_token(self.role.class_token, self.role.id)
        self._class_heard_at = self.clock.now()  # the class server's last hello or call
        self._control: Any = None  # the hello queryable (WorkerControl) and its session
        self._control_session: Any = None
        self._watch: asyncio.Task[None] | None = None

    @property
    def worlds(self) -> dict[str, World]:
        return self.labs.worlds

    @property
    def executors(self) -> ExecutorGroup:
        return self.labs.executors

    @property
    def instructor_token(self) -> str:
        return self.grants.instructor_token

    @property
    def hosted_here(self) -> int:
        return self.labs.hosted_here

    @property
    def local_capacity(self) -> int:
        return self.labs.local_capacity

    @property
    def start_pacer(self) -> StartPacer:
        return self.labs.start_pacer

    @property
    def zenoh_auth(self) -> ClassAuth:
        """The class's Zenoh logins, from the instructor's token (held here as the class token)."""
        return ClassAuth(self.role.class_token)

    def router_endpoint(self) -> str | None:
        """Where worlds and node processes connect: the class's router this worker joined."""
        zenoh = self.settings.lab.zenoh
        return zenoh.connect[0] if zenoh is not None and zenoh.mode != "router" else None

    def router_socket(self) -> Path | None:
        """Where its worlds' sandboxed nodes reach the class's router: its Unix socket on this
        machine, or this worker's relay to it (None: neither, so far)."""
        return self._router_socket

    # -- a class server's own: a world worker has none of them ---------------------------------
    @property
    def workers(self) -> WorkerDirectory | None:
        return None

    @property
    def local_workers(self) -> LocalWorkers | None:
        return None

    @property
    def class_graph(self) -> DomainBridge | None:
        return None  # its class server's is the class's

    @property
    def bridges(self) -> ClassBridges | None:
        return None

    @property
    def view(self) -> ClassView | None:
        return None

    # -- who is calling ------------------------------------------------------------------------
    def grant(self, token: str | None) -> Grant | None:
        """The class server's own calls (and the instructor's) with the worker's API token; a
        student's, forwarded by the class server, for their world alone; else a signed token's."""
        if not token:
            return None
        if hmac.compare_digest(token.encode(), self._worker_token.encode()):
            self.heard_from_class()
            return self.grants.instructor  # the class server, calling its worker
        forwarded = world_of_call_token(self.role.class_token, self.role.id, token)
        if forwarded is not None:
            self.heard_from_class()
            world = self.worlds.get(forwarded)
            # A student's call, forwarded by the class server: that world's student, nothing more.
            return Grant("student", world.name, world.student, world.token_id) if world is not None else None
        return self.grants.check(token, self.worlds)

    def world_for(self, grant: Grant, asked: str | None) -> World:
        return world_for(grant, asked, self.worlds)

    def get(self, name: str) -> World:
        return self.labs.get(name)

    def charge_write(self, world: World) -> None:
        """Nothing: a student's calls come through the class server, which charged the write."""

    def charge_reset(self, name: str) -> None:
        self.labs.charge_reset(name)

    # -- start and stop ------------------------------------------------------------------------
    async def open(self) -> None:
        """Join the class's router (if Zenoh is on) and answer the class server's hellos."""
        zenoh = self.settings.lab.zenoh
        if zenoh is None:
            return
        from node_runtime.transport.session import open_session
        from server.classroom.worker_control import WorkerControl

        zenoh = dataclasses.replace(zenoh, login=self.zenoh_auth.class_credentials())
        self._control_session = await asyncio.to_thread(open_session, zenoh)
        self._control = WorkerControl(self._control_session, self.role, self._load, self.heard_from_class)
        self._watch = asyncio.create_task(self._watch_class(self.role.orphan_timeout_s))

    async def stop(self) -> None:
        if self._watch is not None:
            await cancel_and_wait(self._watch)
            self._watch = None
        for name in list(self.worlds):
            await self._end(self.worlds.pop(name))
        await self.executors.close()
        await self.labs.close_progress()
        if self._control is not None:
            self._control.close()
            self._control = None
        if self._control_session is not None:
            self._control_session.close()
            self._control_session = None
        if self._relay is not None:
            await self._relay.close()
            self._relay = None

    async def _relayed_socket(self) -> Path | None:
        """On another machine than the class server: a Unix socket of this worker's own that
        carries each sandboxed node's link on to the router's TCP endpoint (None: not TCP)."""
        if self._relay is None:
            target = tcp_target(self.router_endpoint())
            if target is None:
                return None
            try:
                self._relay = await SocketRelay.open(*target)
            except OSError as exc:
                log.warning("no relay to the class's router for students' nodes: %s", exc)
                return None
        return self._relay.path

    # -- worlds --------------------------------------------------------------------------------
    async def join(
        self, student: str, code: str, address: str = "unknown", token: str | None = None
    ) -> tuple[World, str]:
        raise JoinThroughClassServerError("this is a world worker: students join through the class server")

    async def poll_join(self, ticket: str) -> tuple[World, str]:
        raise NotHereError(NO_LOAD_HERE)

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
        """Start the world a class server placed here, in the domain it chose. ``router_socket``:
        the class router's Unix socket, which its students' sandboxed nodes reach when it is on
        this machine (else through this worker's relay to the router's TCP endpoint).
        ``progress``: the class server's copy of the world's progress
        (server/classroom/progress_copies.py), in the form server/world/checkpoints/handover.py
        sends it, which it starts with."""
        snapshot = None
        if progress is not None:
            try:
                snapshot = from_wire(progress, load_checkpoints(self.settings.lab.checkpoints))
            except SavedProgressError as exc:
                raise BadHandoverError(
                    f"the progress handed over with world {name!r} is not one: {exc}"
                ) from None
        self.heard_from_class()
        if router_socket is not None:  # the class sandboxes students' nodes: they need a way in
            self._router_socket = socket_here(router_socket) or await self._relayed_socket()
        if self.labs.taken(name):
            raise NameTakenError(f"world {name!r} is already here")
        if self.labs.full():
            raise ClassFullError(f"this worker is full ({self.class_settings.max_worlds} worlds)")
        self.labs.starting[name] = domain_id
        try:
            if snapshot is not None:
                await asyncio.to_thread(self.labs.progress.put, name, snapshot)
            lab = await self.labs.start(name, domain_id, (launch, launch_args), login)
        finally:
            del self.labs.starting[name]
        _token, grant = self.grants.issue(name, student)  # never handed out: the class server proxies
        world = self.worlds[name] = World(
            name, student, grant.token_id, lab, self.labs.write_limit(), domain_id, login=login
        )
        log.info("hosting world %s (%s), ROS domain %d", name, student, domain_id)
        return world

    async def reset(self, name: str) -> World:
        """A fresh world under the same name: every node starts over, the 3D view too."""
        world = self.get(name)
        await self.labs.restart(world)
        world.resets += 1
        log.info("world %s reset", name)
        return world

    async def kick(self, name: str, *, remove_workspace: bool = False) -> World:
        """End a world the class server removed (with its workspace here) or moved elsewhere."""
        world = self.worlds.pop(name, None)
        if world is None:
            raise UnknownWorldError(f"no world named {name!r}")
        self.grants.revoke(world)
        await self._end(world)
        if remove_workspace:  # the student was removed: their progress goes too
            remove_world_workspace(self.class_settings.workspaces_dir, name)
            await self.labs.remove_progress(name)
        log.info("%s kicked: world %s removed", world.student, name)
        return world

    async def _end(self, world: World) -> None:
        if world.lab is not None:
            await world.lab.stop()

    async def describe_all(self) -> list[dict[str, Any]]:
        """Every world here, as the class server asks for it."""
        return [world.describe() for world in self.worlds.values()]

    async def broadcast_on_workers(self, body: dict[str, Any]) -> tuple[list[str], dict[str, str]]:
        return [], {}  # no world workers: the worlds here are its own

    # -- what only its class server keeps ------------------------------------------------------
    async def class_load(self) -> PlaceReport:
        raise NotHereError(NO_LOAD_HERE)

    def let_through(self, count: int) -> dict[str, Any]:
        raise NotHereError(NO_LOAD_HERE)

    def not_joined(self) -> list[tuple[str, Progress]]:
        return []  # its class server lists the saved students

    async def not_joined_with_captures(self) -> list[tuple[str, Progress]]:
        return []

    async def worker_checkpoints(self, checkpoints: list[str]) -> tuple[list[dict[str, Any]], dict[str, str]]:
        return [], {}

    async def worker_reports(self) -> tuple[list[tuple[str, bytes]], dict[str, str]]:
        return [], {}

    async def release_progress(self, name: str) -> str:
        raise NotHereError("only a class server keeps whose progress is whose")

    # -- a class server that goes --------------------------------------------------------------
    def heard_from_class(self) -> None:
        """The class server said hello or called (Zenoh's thread or the loop)."""
        self._class_heard_at = self.clock.now()

    async def _watch_class(self, timeout_s: float) -> None:
        """Free every world when the class server has been silent for ``timeout_s`` (it stopped or
        lost the network): nobody can reach them, and its replacement starts them anew."""
        while True:
            await asyncio.sleep(min(WATCH_PERIOD_S, timeout_s / 2))
            try:
                await self.free_if_orphaned(timeout_s)
            except Exception:
                log.exception("checking on the class server failed; trying again")

    async def free_if_orphaned(self, timeout_s: float) -> list[str]:
        """The worlds freed because the class server has said nothing for ``timeout_s``."""
        silent_s = self.clock.now() - self._class_heard_at
        if not self.worlds or silent_s < timeout_s:
            return []
        names = list(self.worlds)
        log.warning(
            "no hello from the class server for %.0f s: freeing worlds %s", silent_s, ", ".join(names)
        )
        for name in names:
            await self._end(self.worlds.pop(name))
        return names

    def _load(self) -> dict[str, Any]:
        """A worker's hello: how full it is, and which worlds it hosts (Zenoh's thread: a copy)."""
        hosted = sorted(self.worlds)
        return {"worlds": len(hosted) + len(self.labs.starting), "max_worlds": self.class_settings.max_worlds,
                "hosted": hosted, "cpu": self.cpu.read().describe(), "late": self._late(),
                "workspaces": read_mark(self.class_settings.workspaces_dir),
                "progress": read_mark(self.labs.progress.folder)}  # fmt: skip

    def _late(self) -> int | None:
        """Its late worlds, read on Zenoh's thread while the loop runs them: a world or node added
        mid-read makes this round say nothing rather than guess."""
        try:
            return late_worlds(w.lab for w in list(self.worlds.values()))
        except RuntimeError:
            return None
