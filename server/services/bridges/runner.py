"""Start and stop the bridges with the app: the Foxglove server (guarded itself), and rosbridge
on its own port behind the guarded front when one is asked for (it is always at /rosbridge on the
app's port)."""

from __future__ import annotations

import logging
from collections.abc import AsyncIterator, Callable
from contextlib import AsyncExitStack, asynccontextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

from server.services.bridges.front import GuardedFront
from server.services.bridges.rosapi import RosapiNode

if TYPE_CHECKING:
    from node_runtime.bus import Bus
    from server.host.settings import Settings
    from server.services.bridges.foxglove import FoxgloveBridge

log = logging.getLogger("bridges")


@dataclass
class Bridges:
    rosapi: RosapiNode | None = None
    foxglove: FoxgloveBridge | None = None
    rosbridge_front: GuardedFront | None = None

    @property
    def foxglove_port(self) -> int | None:
        return self.foxglove.port if self.foxglove is not None else None


class BridgedLab(Protocol):
    """What the bridges need of a lab (server/world/lab.py's ``Lab``): its bus and its settings."""

    @property
    def bus(self) -> Bus: ...

    @property
    def settings(self) -> Settings: ...


@asynccontextmanager
async def run_bridges(lab: BridgedLab) -> AsyncIterator[Bridges]:
    """The bridges the settings ask for, running on the app's loop; stopped in reverse order."""
    settings = lab.settings
    bridges = Bridges()
    async with AsyncExitStack() as stack:
        with lab.bus.activate():
            bridges.rosapi = RosapiNode()  # what rosbridge clients ask the graph through
        stack.callback(bridges.rosapi.destroy_node)
        if settings.lab.foxglove_port is not None:
            started = await start_foxglove(
                lab.bus, settings, settings.lab.foxglove_port, settings.listen.token
            )
            if started is not None:
                bridges.foxglove = started
                stack.push_async_callback(started.stop)
        if settings.lab.rosbridge_port is not None:
            front = await start_rosbridge_front(settings, settings.lab.rosbridge_port, settings.listen.token)
            if front is not None:
                bridges.rosbridge_front = front
                stack.push_async_callback(front.stop)
        yield bridges


async def start_foxglove(
    bus: Bus,
    settings: Settings,
    port: int,
    token: str | None,
    name: str = "teleop-lab",
    limits_name: Callable[[str], str] | None = None,
) -> FoxgloveBridge | None:
    """A Foxglove server for ``bus`` on ``port``, admitting what the app's port admits (its Host
    and Origin rules) and only holders of ``token``; None, with a warning, if the port is taken."""
    from server.services.bridges.foxglove import FoxgloveBridge
    from server.services.bridges.foxglove_server import Guard

    listen = settings.listen
    guard = Guard(listen.accepted_hosts, frozenset(listen.allowed_origins), token)
    foxglove = FoxgloveBridge(bus, guard, name, limits_name)
    try:
        await foxglove.start(listen.host, port)
    except OSError as exc:  # another lab (or Foxglove bridge) has the port: run without
        log.warning("Foxglove server (%s) not started: port %d: %s", name, port, exc.strerror)
        return None
    log.info("Foxglove WebSocket server (%s) on ws://%s:%d", name, listen.host, foxglove.port)
    return foxglove


async def start_rosbridge_front(
    settings: Settings, port: int, token: str | None, upstream_path: str = "/rosbridge"
) -> GuardedFront | None:
    """rosbridge on a port of its own: the guarded front onto ``upstream_path`` on the app's port;
    None, with a warning, if the app's port is not known. OSError if ``port`` is taken."""
    listen = settings.listen
    if listen.port == 0:
        log.warning(
            "rosbridge's own port needs the app's port to be known (not 0); only %s serves", upstream_path
        )
        return None
    front = GuardedFront(
        listen.host,
        port,
        listen.port,
        listen.accepted_hosts,
        listen.allowed_origins,
        upstream_path=upstream_path,
        token=token,
    )
    await front.start()
    log.info("rosbridge on ws://%s:%d (and at %s)", listen.host, front.port, upstream_path)
    return front
