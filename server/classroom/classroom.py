"""The class server's worlds: one lab per student, each with its own graph, sims and 3D view.

A world is a whole ``Lab`` (bus, executor, launched nodes, viser display) named after its
student. Worlds share the process and its event loop and nothing else: a student's topics,
keys, publishers and resets reach only their own world. The instructor's grant reaches all.
"""

from __future__ import annotations

import asyncio
import dataclasses
import hmac
import logging
import re
import secrets
import time
from dataclasses import dataclass, field
from typing import Any

from server.bus import Clock, SystemClock
from server.devices.shared_physics import SharedQuadrotorPhysics
from server.lab import Lab
from server.limits import RateLimit
from server.settings import Settings
from server.transport.config import ZenohSettings, endpoint_host

from .tokens import Grant, TokenSigner

log = logging.getLogger("classroom")
CODE_ALPHABET = "ABCDEFGHJKLMNPQRSTUVWXYZ23456789"  # no 0/O, 1/I: read aloud or off a projector
CODE_CHARS = 6
MAX_NAME_CHARS = 32
MAX_DOMAIN_ID = 232  # ROS 2's highest ROS_DOMAIN_ID
# A world's name is a ROS namespace token: letters, digits and underscores, not starting with a digit.
_NOT_NAME = re.compile(r"[^a-z0-9_]+")


class ClassroomError(Exception):
    """A refused classroom request: ``status`` is the HTTP status that says why."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


def new_code() -> str:
    return "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_CHARS))


def world_name(student: str) -> str:
    """``"Ada Lovelace"`` → ``ada_lovelace``; ValueError when nothing usable is left."""
    name = _NOT_NAME.sub("_", student.strip().lower()).strip("_")[:MAX_NAME_CHARS].rstrip("_")
    if not name:
        raise ValueError("a name needs at least one letter or digit")
    return name if not name[0].isdigit() else f"s_{name}"[:MAX_NAME_CHARS]


@dataclass
class World:
    name: str
    student: str
    token_id: str
    lab: Lab
    writes: RateLimit
    domain_id: int = 0  # its ROS_DOMAIN_ID on the class's Zenoh graph
    joined_at: float = field(default_factory=time.time)
    resets: int = 0

    def describe(self) -> dict[str, Any]:
        lab = self.lab
        rocket = lab.rocket_view.tracker if lab.rocket_view is not None else None
        return {
            "world": self.name,
            "student": self.student,
            "domain_id": self.domain_id if lab.zenoh is not None else None,
            "joined_at": self.joined_at,
            "resets": self.resets,
            "keys_held": sorted(lab.keyboard.held()),
            "rocket": None
            if rocket is None
            else {"phase": rocket.phase, "altitude_m": round(rocket.altitude_m, 2)},
            "drone": drone_position(lab),
            "crashed_nodes": sorted(n.fully_qualified_name for n in lab.bus.nodes if n.state == "crashed"),
            "nodes": len(lab.bus.nodes),
            "writes_refused": self.writes.refused,
        }


def drone_position(lab: Lab) -> list[float] | None:
    """Where the world's drone is (its GPS topic's latest pose), or None before the first fix."""
    topic = lab.bus.topics.get("/uav/sensors/gps")
    latest: Any = topic.latest if topic is not None else None
    if latest is None:
        return None
    p = latest.pose.position
    return [round(p.x, 3), round(p.y, 3), round(p.z, 3)]


class Classroom:
    """The worlds of one class server, and who may do what in them."""

    def __init__(
        self,
        settings: Settings,
        clock: Clock | None = None,
        *,
        code: str | None = None,
        signer: TokenSigner | None = None,
    ) -> None:
        self.settings = settings
        self.clock: Clock = clock or SystemClock()  # every world's, the physics' and the limits'
        self.code = code or new_code()
        self.signer = signer or TokenSigner()
        self.instructor_token, self.instructor = self.signer.issue("instructor", None, "instructor")
        self.worlds: dict[str, World] = {}
        self.physics = SharedQuadrotorPhysics(self.clock)
        self._revoked: set[str] = set()
        self._starting: dict[str, int] = {}  # world → its ROS domain, while it starts
        self._router: Any = None  # the class's Zenoh router session (zenoh.Session)

    # -- who is calling ------------------------------------------------------
    def grant(self, token: str | None) -> Grant | None:
        """The grant of a genuine, current token: a student's world must still be theirs."""
        if not token:
            return None
        grant = self.signer.verify(token)
        if grant is None or grant.token_id in self._revoked:
            return None
        if grant.is_instructor:
            return grant
        world = self.worlds.get(grant.world or "")
        return grant if world is not None and world.token_id == grant.token_id else None

    def world_for(self, grant: Grant, asked: str | None) -> World:
        """The world a call acts on: a student's own (naming another is 403); the instructor's
        must be named."""
        if grant.is_instructor:
            if asked is None:
                raise ClassroomError(400, "name a world (the X-Lab-World header or ?world=)")
            return self.get(asked)
        if asked is not None and asked != grant.world:
            raise ClassroomError(403, f"your token is for world {grant.world!r}, not {asked!r}")
        return self.get(grant.world or "")

    def get(self, name: str) -> World:
        world = self.worlds.get(name)
        if world is None:
            raise ClassroomError(404, f"no world named {name!r}")
        return world

    # -- worlds ----------------------------------------------------------------
    # -- the class's Zenoh graph ---------------------------------------------------------------
    async def open(self) -> None:
        """Open the class's Zenoh router (if Zenoh is on): each world joins it in a ROS domain of
        its own, so students' node processes join their world with its ROS_DOMAIN_ID."""
        zenoh = self.settings.zenoh
        if zenoh is None or zenoh.mode != "router":
            return
        from server.transport.session import TransportError, open_session

        try:
            self._router = await asyncio.to_thread(open_session, zenoh)
        except TransportError as exc:
            log.warning("%s; the worlds run without Zenoh", exc)

    def router_endpoint(self) -> str | None:
        """Where worlds and node processes connect: the class's router, or the one it joined."""
        zenoh = self.settings.zenoh
        if zenoh is None or (zenoh.mode == "router" and self._router is None):
            return None
        if zenoh.mode != "router":
            return zenoh.connect[0]
        proto, host, port = endpoint_host(zenoh.listen[0])
        return f"{proto}/{'127.0.0.1' if host in ('0.0.0.0', '[::]', '::') else host}:{port}"

    def _free_domain(self) -> int:
        taken = {w.domain_id for w in self.worlds.values()} | set(self._starting.values())
        if self.settings.zenoh is not None:
            taken.add(self.settings.zenoh.domain_id)  # the class's own domain stays empty
        return next(d for d in range(1, MAX_DOMAIN_ID + 1) if d not in taken)

    def _world_settings(self, name: str, domain_id: int) -> Settings:
        # A world's graph joins the class's router in a ROS domain of its own; the class server's
        # other ports (Foxglove, rosbridge) are not opened per world; bags go in a folder per world.
        endpoint = self.router_endpoint()
        zenoh = None
        if endpoint is not None:
            config_file = self.settings.zenoh.config_file if self.settings.zenoh is not None else None
            zenoh = ZenohSettings(
                mode="client", listen=(), connect=(endpoint,), domain_id=domain_id, config_file=config_file
            )
        return dataclasses.replace(
            self.settings,
            zenoh=zenoh,
            foxglove_port=None,
            rosbridge_port=None,
            bag_dir=self.settings.bag_dir / name,
        )

    async def _start_lab(self, name: str, domain_id: int) -> Lab:
        lab = Lab(self._world_settings(name, domain_id), self.clock)
        lab.bus.devices["quadrotor_physics"] = self.physics  # every world's drone in one batch
        await lab.start()
        return lab

    async def join(self, student: str, code: str) -> tuple[World, str]:
        if not hmac.compare_digest(code.strip().upper().encode(), self.code.encode()):
            raise ClassroomError(403, "wrong class code")
        try:
            name = world_name(student)
        except ValueError as exc:
            raise ClassroomError(422, str(exc)) from None
        if name in self.worlds or name in self._starting:
            raise ClassroomError(409, f"the name {student!r} is taken in this class (world {name!r})")
        if len(self.worlds) + len(self._starting) >= self.settings.max_worlds:
            raise ClassroomError(429, f"the class is full ({self.settings.max_worlds} worlds)")
        domain_id = self._free_domain()
        self._starting[name] = domain_id  # held while the world starts: no two joins take one name
        try:
            lab = await self._start_lab(name, domain_id)
        finally:
            del self._starting[name]
        student = student.strip()[:64]
        token, grant = self.signer.issue("student", name, student)
        world = self.worlds[name] = World(name, student, grant.token_id, lab, self._limit(), domain_id)
        log.info("%s joined: world %s", student, name)
        return world, token

    def _limit(self) -> RateLimit:
        return RateLimit(self.clock, self.settings.world_writes_hz, self.settings.world_writes_burst)

    async def reset(self, name: str) -> World:
        """A fresh world under the same name and token: every node starts over, the 3D view too."""
        world = self.get(name)
        old = world.lab
        await old.stop()  # first: the new world takes the same ROS domain on the graph
        world.lab = await self._start_lab(name, world.domain_id)
        world.resets += 1
        log.info("world %s reset", name)
        return world

    async def kick(self, name: str) -> World:
        world = self.worlds.pop(name, None)
        if world is None:
            raise ClassroomError(404, f"no world named {name!r}")
        self._revoked.add(world.token_id)
        await world.lab.stop()
        log.info("%s kicked: world %s removed", world.student, name)
        return world

    async def stop(self) -> None:
        for name in list(self.worlds):
            world = self.worlds.pop(name)
            await world.lab.stop()
        if self._router is not None:
            self._router.close()
            self._router = None
