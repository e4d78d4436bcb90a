"""The class's Zenoh graph, as the class server holds it: its router and the worlds' logins, the
domain bridge that shows every world under its name in the class's own domain, the instructor's
bridges on that domain, and the directory of world workers on the router's session.

Removing a world retires its login: the router opens again without it (class_router.py), and
everything on the router's session (the domain bridge, the workers' directory) is built again on
the new one. While the router opens again no world starts (router_gate.py) and nobody gets the
domain.
"""

from __future__ import annotations

import asyncio
import dataclasses
import logging
import time
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from node_runtime.bus import Clock, ExecutorGroup
from node_runtime.transport.acl import ClassAuth, Credentials
from node_runtime.transport.config import endpoint_host
from server.classroom.router_gate import RouterGate
from server.classroom.workers import WorkerDirectory
from server.classroom.world import World
from server.host.settings import Settings

if TYPE_CHECKING:
    from node_runtime.transport.domain_bridge import DomainBridge
    from node_runtime.transport.domain_routes import BridgeStats
    from server.classroom.class_bridges import ClassBridges
    from server.classroom.class_router import ClassRouter

log = logging.getLogger("classroom")
WORKERS_BACK_S = 10.0  # how long a reopened router waits for its world workers to answer again


class ClassGraph:
    """What the class server runs on the class's router, from ``open`` to ``close``; ``worlds``
    are the class's (each shown in the class domain under its name)."""

    def __init__(self, settings: Settings, worlds: Mapping[str, World], instructor_token: str) -> None:
        self.settings = settings
        self.worlds = worlds
        self.instructor_token = instructor_token
        self.auth = ClassAuth(instructor_token)  # the class's Zenoh logins
        self.router: ClassRouter | None = None  # the class's Zenoh router and its logins
        self.gate = RouterGate()  # worlds start while the router is open, never while it opens again
        self.revoking: set[int] = set()  # domains whose old login the router may still let in
        self.workers: WorkerDirectory | None = None  # the class's world workers, on the router's session
        self.bridge: DomainBridge | None = None  # every world under /<world> in the class's domain
        self._stats: BridgeStats | None = None  # the bridge's counts, over every reopening
        self.bridges: ClassBridges | None = None  # the instructor's Foxglove and rosbridge ports

    async def open(self, clock: Clock, executors: ExecutorGroup) -> bool:
        """Open the class's router (when Zenoh is on, as a router): whether it is open. Each world
        joins it in a ROS domain of its own."""
        zenoh = self.settings.lab.zenoh
        if zenoh is None or zenoh.mode != "router":
            return False
        from node_runtime.transport.session import TransportError
        from server.classroom.class_router import ClassRouter

        if self.settings.sandboxes_students:  # students' sandboxed nodes reach it on a Unix socket
            from node_runtime.transport.router_socket import new_socket_path, socket_endpoint

            path = new_socket_path()
            zenoh = dataclasses.replace(
                zenoh, listen=(*zenoh.listen, socket_endpoint(path)), process_socket=path
            )
        # The router logs every session in and holds each world's to its own ROS domain.
        router = ClassRouter(zenoh, self.auth.class_credentials())
        try:
            session = await router.open()
        except TransportError as exc:
            log.warning("%s; the worlds run without Zenoh", exc)
            return False
        self.router = router
        self.workers = WorkerDirectory(session, self.instructor_token)
        self._open_bridge(session)
        endpoint = self.endpoint()
        if endpoint is not None:  # the instructor's bridges: /class/rosbridge, and their ports if asked
            from server.classroom.class_bridges import ClassBridges

            try:
                self.bridges = await ClassBridges.open(
                    self.settings,
                    clock,
                    executors,
                    endpoint,
                    zenoh.domain_id,
                    self.auth.class_credentials(),
                    self.instructor_token,
                )
            except TransportError as exc:
                log.warning("the class's Foxglove and rosbridge ports not opened: %s", exc)
        return True

    def endpoint(self) -> str | None:
        """Where worlds and node processes connect: the class's router, or the one it joined."""
        zenoh = self.settings.lab.zenoh
        if zenoh is None or (zenoh.mode == "router" and self.router is None):
            return None
        if zenoh.mode != "router":
            return zenoh.connect[0]
        proto, host, port = endpoint_host(zenoh.listen[0])
        return f"{proto}/{'127.0.0.1' if host in ('0.0.0.0', '[::]', '::') else host}:{port}"

    def process_socket(self) -> Path | None:
        """The router's Unix socket for sandboxed node processes (None: none on this machine)."""
        return self.router.settings.process_socket if self.router is not None else None

    def login(self, domain_id: int) -> Credentials | None:
        """The login of a new world in ``domain_id`` (None without a router)."""
        return self.router.login(domain_id) if self.router is not None else None

    def show(self, world: World) -> None:
        if self.bridge is not None:
            self.bridge.set_world(world.domain_id, world.name)

    def hold(self, world: World) -> None:
        """At once, as ``world`` is removed: a join while it ends must not get its domain, and the
        class domain no longer shows it."""
        if self.router is not None:
            self.revoking.add(world.domain_id)
        if self.bridge is not None:
            self.bridge.drop_world(world.domain_id)

    async def revoke_login(self, domain_id: int) -> None:
        """Retire the login of the world that was in ``domain_id``: the router opens again without
        it (class_router.py), which drops every session of it. Until then nobody gets the domain;
        removals that wait meanwhile are done by the same reopening."""
        if self.router is None:
            return
        self.revoking.add(domain_id)
        try:
            async with self.gate.reopening():
                if domain_id in self.revoking:  # not yet done by a reopening this one waited for
                    batch = set(self.revoking)
                    await self._reopen_router(batch)
                    self.revoking -= batch
        finally:
            self.revoking.discard(domain_id)

    async def _reopen_router(self, domains: set[int]) -> None:
        from node_runtime.transport.session import TransportError

        assert self.router is not None
        if self.workers is not None:
            self.workers.use_session(None)
        if self.bridge is not None:  # it lives on the router's session: built again on the new one
            bridge, self.bridge = self.bridge, None
            try:
                await asyncio.to_thread(bridge.close)
            except Exception:  # the revocation must go on: the router closes with its session anyway
                log.exception("the class's domain bridge did not close cleanly")
        try:
            session = await self.router.revoke(domains)
        except TransportError as exc:
            log.error("the class's Zenoh router did not open again (%s): the worlds are off Zenoh", exc)
            return
        try:
            self._open_bridge(session)
        except Exception:
            log.exception("the class's domain bridge did not open again: worlds are not bridged")
            return
        if self.workers is not None:
            await self._workers_back(session)
        log.info(
            "Zenoh logins of ROS domains %s revoked: the class's router opened again",
            ", ".join(map(str, sorted(domains))),
        )

    async def _workers_back(self, session: Any) -> None:
        """Until the workers found before the router opened again answer on the new one (their
        sessions connect again by themselves), for at most WORKERS_BACK_S: a join meanwhile
        would find no room on them."""
        assert self.workers is not None
        expected = set(self.workers.last_found)
        self.workers.use_session(session)
        deadline = time.monotonic() + WORKERS_BACK_S
        while expected and time.monotonic() < deadline:
            found = {ref.id for ref in await asyncio.to_thread(self.workers.discover)}
            if expected <= found:
                return
            await asyncio.sleep(0.1)
        if expected:
            log.warning(
                "world workers %s did not answer within %g s of the router opening again",
                ", ".join(sorted(expected - self.workers.last_found)),
                WORKERS_BACK_S,
            )

    def _open_bridge(self, session: Any) -> None:
        from node_runtime.transport.domain_bridge import DomainBridge

        assert self.settings.lab.zenoh is not None
        self.bridge = DomainBridge(session, self.settings.lab.zenoh.domain_id, self._stats)
        self._stats = self.bridge.stats
        for world in self.worlds.values():
            self.bridge.set_world(world.domain_id, world.name)

    async def close_bridges(self, executors: ExecutorGroup) -> None:
        """The instructor's ports, first: they are on the class's executors."""
        if self.bridges is not None:
            await self.bridges.close(executors)
            self.bridges = None

    async def close(self) -> None:
        """The workers' directory, the domain bridge, then the router (not while it opens again)."""
        if self.workers is not None:
            await self.workers.close()
            self.workers = None
        if self.bridge is not None:
            await asyncio.to_thread(self.bridge.close)
            self.bridge = None
        if self.router is not None:
            async with self.gate.reopening():
                self.router.close()
            socket, self.router = self.router.settings.process_socket, None
            if socket is not None:
                from node_runtime.transport.router_socket import remove

                remove(socket)
