"""Start and stop the bridges with the app: the Foxglove server behind its guarded front, and
rosbridge on its own port when one is asked for (it is always at /rosbridge on the app's port)."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import AsyncIterator
from contextlib import AsyncExitStack, asynccontextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .front import GuardedFront
from .rosapi import RosapiNode

if TYPE_CHECKING:
    from server.lab import Lab

    from .foxglove import FoxgloveBridge

log = logging.getLogger("bridges")


@dataclass
class Bridges:
    rosapi: RosapiNode | None = None
    foxglove: FoxgloveBridge | None = None
    foxglove_front: GuardedFront | None = None
    rosbridge_front: GuardedFront | None = None

    @property
    def foxglove_port(self) -> int | None:
        return self.foxglove_front.port if self.foxglove_front is not None else None


@asynccontextmanager
async def run_bridges(lab: Lab) -> AsyncIterator[Bridges]:
    """The bridges the settings ask for, running on the app's loop; stopped in reverse order."""
    settings = lab.settings
    bridges = Bridges()
    async with AsyncExitStack() as stack:
        with lab.bus.activate():
            bridges.rosapi = RosapiNode()  # what rosbridge clients ask the graph through
        stack.callback(bridges.rosapi.destroy_node)
        if settings.foxglove_port is not None:
            from .foxglove import FoxgloveBridge  # the SDK loads only when asked for

            foxglove = FoxgloveBridge(lab.bus, asyncio.get_running_loop())
            front = GuardedFront(
                settings.host, settings.foxglove_port, foxglove.port,
                settings.accepted_hosts, settings.allowed_origins, token=settings.token,
            )  # fmt: skip
            try:
                await front.start()
            except OSError as exc:  # another lab (or Foxglove bridge) has the port: run without
                foxglove.stop()
                log.warning("Foxglove server not started: port %d: %s", settings.foxglove_port, exc.strerror)
            else:
                bridges.foxglove, bridges.foxglove_front = foxglove, front
                stack.callback(foxglove.stop)
                stack.push_async_callback(front.stop)
                log.info("Foxglove WebSocket server on ws://%s:%d", settings.host, front.port)
        if settings.rosbridge_port is not None:
            if settings.port == 0:
                log.warning(
                    "rosbridge's own port needs the app's port to be known (not 0); only /rosbridge serves"
                )
            else:
                front = GuardedFront(
                    settings.host, settings.rosbridge_port, settings.port,
                    settings.accepted_hosts, settings.allowed_origins, upstream_path="/rosbridge",
                    token=settings.token,
                )  # fmt: skip
                await front.start()
                bridges.rosbridge_front = front
                stack.push_async_callback(front.stop)
                log.info("rosbridge on ws://%s:%d (and at /rosbridge)", settings.host, front.port)
        yield bridges
