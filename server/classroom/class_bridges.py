"""The instructor's Foxglove and rosbridge ports: the class's own ROS domain, every world under its name.

A class server opens no Foxglove server or rosbridge port per world. It opens them once for the
instructor: a bus of its own joins the class's router in the class's domain, where the domain
bridge (node_runtime/transport/domain_bridge.py) declares each world's topics as ``/<world>/<topic>``.
On ``--foxglove-port`` a Foxglove bridge on that bus advertises them (``Bus.known_topics``); on
``--rosbridge-port`` (and at ``/class/rosbridge`` on the app's port, api/websockets/rosbridge.py) rosbridge
clients subscribe, publish and ask rosapi-style questions of the same bus. A topic a client
watches becomes a subscription in the class domain, so the domain bridge carries that world's
samples only while someone watches them; what a client publishes on ``/ada/uav/input/position``
goes into Ada's world only, within the limits the world's own ``/uav/input/position`` keeps. Both
ports admit the instructor's token alone (the Foxglove server checks it itself, rosbridge's port
sits behind the guarded front): a student's token, another site's page or a foreign Host never
reach them.
"""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from node_runtime.bus import Bus, Clock, Executor, ExecutorGroup
from node_runtime.transport.acl import Credentials
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.link import ZenohLink
from server.host.settings import Settings
from server.services.bridges.front import GuardedFront
from server.services.bridges.rosapi import RosapiNode
from server.services.bridges.runner import start_foxglove, start_rosbridge_front

if TYPE_CHECKING:
    from server.services.bridges.foxglove import FoxgloveBridge

log = logging.getLogger("classroom.bridges")
CLASS_ROSBRIDGE_PATH = "/class/rosbridge"


def world_topic(name: str) -> str:
    """``/ada/uav/input/position`` → ``/uav/input/position``: the name in the world, whose limits
    (node_runtime/limits.py: a setpoint inside the arena) a message for it must keep."""
    parts = name.split("/", 2)
    return "/" + parts[2] if len(parts) == 3 and parts[2] else name


@dataclass
class ClassBridges:
    bus: Bus
    link: ZenohLink
    executor: Executor
    foxglove: FoxgloveBridge | None = None
    rosbridge_front: GuardedFront | None = None
    closed: asyncio.Event = field(default_factory=asyncio.Event)  # rosbridge sockets end with it

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
    ) -> ClassBridges:
        """Join the class domain at ``router`` with the class's ``login``; serve Foxglove on
        ``settings.lab.foxglove_port`` and rosbridge on ``settings.lab.rosbridge_port`` (each when set) to
        holders of ``token``. A port that is taken is left out with a warning."""
        lab = settings.lab
        zenoh = ZenohSettings(
            mode="client",
            listen=(),
            connect=(router,),
            domain_id=domain_id,
            login=login,
            config_file=lab.zenoh.config_file if lab.zenoh is not None else None,
        )
        bus = Bus(clock)
        link = await ZenohLink.open(bus, zenoh)
        with bus.activate():
            RosapiNode()  # what rosbridge clients ask the class's graph through
        bridges = cls(bus, link, Executor(bus))
        try:
            if lab.foxglove_port is not None:
                await bridges._start_foxglove(settings, lab.foxglove_port, token)
            if lab.rosbridge_port is not None:
                await bridges._start_rosbridge(settings, lab.rosbridge_port, token)
        except BaseException:  # a port did not open: the class domain's session goes too
            await bridges._stop_ports()
            link.close()
            raise
        executors.add(bridges.executor)
        return bridges

    async def _start_foxglove(self, settings: Settings, port: int, token: str) -> None:
        self.foxglove = await start_foxglove(self.bus, settings, port, token, "teleop-lab class", world_topic)

    async def _start_rosbridge(self, settings: Settings, port: int, token: str) -> None:
        try:
            self.rosbridge_front = await start_rosbridge_front(settings, port, token, CLASS_ROSBRIDGE_PATH)
        except OSError as exc:  # the class runs on without it, as without its Foxglove port
            log.warning("the class's rosbridge port not opened: port %d: %s", port, exc.strerror)

    async def _stop_ports(self) -> None:
        if self.rosbridge_front is not None:
            await self.rosbridge_front.stop()
        if self.foxglove is not None:
            await self.foxglove.stop()
        self.foxglove = self.rosbridge_front = None

    async def close(self, executors: ExecutorGroup) -> None:
        self.closed.set()
        await self._stop_ports()
        executors.remove(self.executor)
        await asyncio.to_thread(self.link.close)
