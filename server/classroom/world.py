"""A world: one student's lab, its name, its ROS domain and its limits, wherever it runs.

A world is a whole ``Lab`` (bus, executor, launched nodes, viser display) named after its
student. Worlds share the process and its event loop and nothing else: a student's topics,
keys, publishers and resets reach only their own world. A world on a world worker has no lab
here; its worker reports it.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from node_runtime.limits import RateLimit
from node_runtime.transport.acl import Credentials
from server.classroom.workers import WorkerRef
from server.world.lab import Lab

MAX_NAME_CHARS = 32
# A world's name is a ROS namespace token: letters, digits and underscores, not starting with a digit.
_NOT_NAME = re.compile(r"[^a-z0-9_]+")


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
    lab: Lab | None  # None when the world runs on a world worker
    writes: RateLimit
    domain_id: int = 0  # its ROS_DOMAIN_ID on the class's Zenoh graph
    joined_at: float = field(default_factory=time.time)
    resets: int = 0
    worker: WorkerRef | None = None  # the world worker that hosts it, if one does
    moves: int = 0  # times it started again elsewhere because its world worker was gone
    placed_at: float = -math.inf  # when it was last started where it is (the class's clock)
    lost: str | None = None  # why it cannot be reached now (its worker is gone and it waits for room)
    login: Credentials | None = field(default=None, repr=False)  # its Zenoh login (class_router.py)
    address: str | None = None  # the client address it was joined from (a class server's)
    reset_limit: RateLimit | None = None  # a student's resets, besides their writes
    sockets: int = 0  # a student's WebSockets open on it now (api/middleware/socket_cap.py)

    def __post_init__(self) -> None:
        if self.lab is not None:  # its checkpoint report names the student
            self.lab.checkpoints.progress.student = self.student

    def describe(self) -> dict[str, Any]:
        """What the class server knows itself; a worker's world adds what its worker reports."""
        out: dict[str, Any] = {
            "world": self.name,
            "student": self.student,
            "domain_id": self.domain_id,
            "joined_at": self.joined_at,
            "resets": self.resets,
            "writes_refused": self.writes.refused,
            "worker": self.worker.id if self.worker is not None else None,
            "moves": self.moves,
            "lost": self.lost,
        }
        lab = self.lab
        if lab is None:
            return out
        rocket = lab.rocket.view.tracker if lab.rocket.view is not None else None
        return {
            **out,
            "domain_id": self.domain_id if lab.zenoh is not None else None,
            "keys_held": sorted(lab.keyboard.held()),
            "rocket": None
            if rocket is None
            else {"phase": rocket.phase, "altitude_m": round(rocket.altitude_m, 2)},
            "drone": drone_position(lab),
            "crashed_nodes": sorted(n.fully_qualified_name for n in lab.bus.nodes if n.state == "crashed"),
            "nodes": len(lab.bus.nodes),
        }


def drone_position(lab: Lab) -> list[float] | None:
    """Where the world's drone is (its GPS topic's latest pose), or None before the first fix."""
    topic = lab.bus.topics.get("/uav/sensors/gps")
    latest: Any = topic.latest if topic is not None else None
    if latest is None:
        return None
    p = latest.pose.position
    return [round(p.x, 3), round(p.y, 3), round(p.z, 3)]


def drones(
    worlds: Iterable[World], remote: Mapping[str, list[float] | None]
) -> dict[str, tuple[str, list[float] | None]]:
    """Each world's student and drone position (None: not known now); a worker's world's from
    ``remote``, the latest its worker reported."""
    out: dict[str, tuple[str, list[float] | None]] = {}
    for world in worlds:
        if world.lab is not None:
            position = drone_position(world.lab)
        else:
            position = None if world.lost is not None else remote.get(world.name)
        out[world.name] = (world.student, position)
    return out
