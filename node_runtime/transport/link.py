"""The app's link to Zenoh: the session and the bridge, opened and closed together."""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass
from typing import Any

from node_runtime.bus import Bus
from node_runtime.transport.bridge import ZenohBridge
from node_runtime.transport.config import ZenohSettings, endpoint_host
from node_runtime.transport.session import TransportError, open_session

log = logging.getLogger("transport")


@dataclass
class ZenohLink:
    settings: ZenohSettings
    session: Any  # zenoh.Session (its stubs leave close() untyped)
    bridge: ZenohBridge

    @classmethod
    async def open(cls, bus: Bus, settings: ZenohSettings) -> ZenohLink:
        """Open the session off the loop (it takes a moment), then join the bus on it."""
        session = await asyncio.to_thread(open_session, settings)
        bridge = ZenohBridge(bus, session, settings.domain_id, samples_hz=settings.samples_hz)
        return cls(settings, session, bridge)

    def router_endpoint(self) -> str:
        """Where this app's node processes connect: its own router, or the one it joined."""
        if self.settings.mode == "router":
            proto, host, port = endpoint_host(self.settings.listen[0])
            if host in ("0.0.0.0", "[::]", "::"):
                host = "127.0.0.1"
            return f"{proto}/{host}:{port}"
        return self.settings.connect[0]

    def close(self) -> None:
        self.bridge.close()
        self.session.close()

    def status(self) -> dict[str, Any]:
        return {
            "mode": self.settings.mode,
            "router": self.router_endpoint(),
            "listen": list(self.settings.listen) if self.settings.mode == "router" else [],
            "connect": list(self.settings.connect),
            "domain_id": self.settings.domain_id,
            "login": self.settings.login is not None,
            "zid": self.bridge.zid,
            "processes": len(self.bridge.remote.sessions()),
            "sent": self.bridge.stats.sent,
            "received": self.bridge.stats.received,
            "dropped_without_attachment": self.bridge.stats.no_attachment,
            "dropped_over_rate": self.bridge.stats.over_rate,
        }


async def open_link(bus: Bus, settings: ZenohSettings) -> tuple[ZenohLink | None, str | None]:
    """The link, or None and one line saying why not (the app then runs in-process only)."""
    try:
        return await ZenohLink.open(bus, settings), None
    except TransportError as exc:
        log.warning("%s", exc)
        return None, str(exc)
