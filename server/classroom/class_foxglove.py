"""The instructor's Foxglove connection: the class's own ROS domain, every world under its name.

A class server opens no Foxglove server per world. It opens one on ``--foxglove-port`` for the
instructor: a bus of its own joins the class's router in the class's domain, where the domain
bridge (server/transport/domain_bridge.py) declares each world's topics as ``/<world>/<topic>``,
and a Foxglove bridge on that bus advertises them (``Bus.known_topics``). A channel a client
subscribes to becomes a subscription in the class domain, so the domain bridge carries that
world's samples only while someone watches them; what a client publishes on
``/ada/uav/input/position`` goes into Ada's world only, within the limits the world's own
``/uav/input/position`` keeps. The port sits behind the guarded front
with the instructor's token: a student's token, another site's page or a foreign Host never
reach the SDK's server.
"""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass

from server.bridges.foxglove import FoxgloveBridge
from server.bridges.front import GuardedFront
from server.bus import Bus, Clock, Executor, ExecutorGroup
from server.settings import Settings
from server.transport.acl import Credentials
from server.transport.config import ZenohSettings
from server.transport.link import ZenohLink

log = logging.getLogger("classroom.foxglove")


def world_topic(name: str) -> str:
    """``/ada/uav/input/position`` → ``/uav/input/position``: the name in the world, whose limits
    (server/limits.py: a setpoint inside the arena) a message for it must keep."""
    parts = name.split("/", 2)
    return "/" + parts[2] if len(parts) == 3 and parts[2] else name


@dataclass
class ClassFoxglove:
    link: ZenohLink
    executor: Executor
    foxglove: FoxgloveBridge
    front: GuardedFront

    @property
    def port(self) -> int:
        return self.front.port

    @classmethod
    async def open(
        cls,
        settings: Settings,
        clock: Clock,
        executors: ExecutorGroup,
        router: str,
        domain_id: int,
        login: Credentials,
        token: str,
    ) -> ClassFoxglove | None:
        """Join the class domain at ``router`` with the class's ``login`` and serve Foxglove on
        ``settings.foxglove_port`` to holders of ``token``; None (and a warning) if the port is taken."""
        assert settings.foxglove_port is not None
        zenoh = ZenohSettings(
            mode="client", listen=(), connect=(router,), domain_id=domain_id, login=login,
            config_file=settings.zenoh.config_file if settings.zenoh is not None else None,
        )  # fmt: skip
        bus = Bus(clock)
        link = await ZenohLink.open(bus, zenoh)
        try:
            foxglove = FoxgloveBridge(bus, asyncio.get_running_loop(), "teleop-lab class", world_topic)
        except BaseException:  # the SDK's server did not start: the class domain's session goes too
            link.close()
            raise
        front = GuardedFront(
            settings.host, settings.foxglove_port, foxglove.port,
            settings.accepted_hosts, settings.allowed_origins, token=token,
        )  # fmt: skip
        try:
            await front.start()
        except OSError as exc:
            foxglove.stop()
            link.close()
            log.warning(
                "the class's Foxglove server not started: port %d: %s", settings.foxglove_port, exc.strerror
            )
            return None
        executor = Executor(bus)
        executors.add(executor)
        log.info("Foxglove WebSocket server for the class on ws://%s:%d", settings.host, front.port)
        return cls(link, executor, foxglove, front)

    async def close(self, executors: ExecutorGroup) -> None:
        await self.front.stop()
        executors.remove(self.executor)
        self.foxglove.stop()
        await asyncio.to_thread(self.link.close)
