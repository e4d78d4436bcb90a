"""Start and stop the bridges with the app: the Foxglove server behind its guarded front, and
rosbridge on its own port when one is asked for (it is always at /rosbridge on the app's port)."""

from __future__ import annotations

import logging
from collections.abc import AsyncIterator
from contextlib import AsyncExitStack, asynccontextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from server.lab import Lab

    from .foxglove import FoxgloveBridge
    from .front import GuardedFront

log = logging.getLogger("bridges")


@dataclass
class Bridges:
    foxglove: FoxgloveBridge | None = None
    foxglove_front: GuardedFront | None = None

    @property
    def foxglove_port(self) -> int | None:
        return self.foxglove_front.port if self.foxglove_front is not None else None


@asynccontextmanager
async def run_bridges(lab: Lab) -> AsyncIterator[Bridges]:
    """The bridges the settings ask for, running on the app's loop; stopped in reverse order."""
    settings = lab.settings
    bridges = Bridges()
    async with AsyncExitStack() as stack:
        if settings.foxglove_port is not None:
            import asyncio

            from .foxglove import FoxgloveBridge
            from .front import GuardedFront

            foxglove = FoxgloveBridge(lab.bus, asyncio.get_running_loop())
            front = GuardedFront(
                settings.host, settings.foxglove_port, foxglove.port,
                settings.accepted_hosts, settings.allowed_origins,
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
        yield bridges
