"""The sections of a class server and a world worker: the class (``classroom``, with what one
world may hold, the joins and the join queue) and the worker's identity (``worker``)."""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import Field, field_validator

from server.host.settings.base import (
    LOCAL_WORLDS_RULE,
    MAX_LOCAL_WORKERS,
    ORPHAN_TIMEOUT_S,
    SPREAD_AT_WORLDS,
    WORKER_TIMEOUT_S,
    WORKERS_RULE,
    WORLDS_PER_CORE,
    Section,
    log_level,
)

# ``ros2lab world-worker``'s own defaults, where a worker differs from a class server: the worlds
# it hosts at most (--max-worlds; a class server's is ``ClassroomSettings.max_worlds``), and its
# HTTP API's port (--port; 0: a free one, which it tells the class server in its hello).
WORKER_MAX_WORLDS = 30
WORKER_PORT = 0


class WorldLimits(Section):
    """What one student's world may hold on a class server, so its load stays its own."""

    writes_hz: float = Field(
        default=20.0, gt=0
    )  # a student's REST writes per second in their world, bursts of:
    writes_burst: int = Field(default=40, ge=1)
    # Launches and runs started through the API (and nodes in each), resets (also writes), and
    # WebSockets of every kind.
    launches: int = Field(default=4, ge=1)
    launch_nodes: int = Field(default=16, ge=1)
    resets_hz: float = Field(
        default=1 / 30, gt=0
    )  # a reset blocks the shared loop ~0.1 s: a world starts over
    resets_burst: int = Field(default=2, ge=1)
    sockets: int = Field(default=24, ge=1)
    socket_frames_hz: float = Field(
        default=400.0, gt=0
    )  # a page's pose stream is 100; bursts of a second's worth
    socket_requests_hz: float = Field(default=200.0, gt=0)
    # Samples a second a world takes from other processes on Zenoh (its student's nodes); a flood
    # beyond that is dropped as it arrives, so it costs the shared loop nothing.
    samples_hz: float = Field(default=2000.0, gt=0)


class JoinLimits(Section):
    """How fast a class takes joins and wrong class codes, per client address and for the whole
    class (over it: 429 with Retry-After), and how many worlds one address may hold (None: any,
    for a class behind one NAT address)."""

    per_address_hz: float = 1.0  # a class behind one NAT address: 30 at once, then one a second
    per_address_burst: int = 30
    class_hz: float = 2.0
    class_burst: int = 60
    wrong_codes_per_address_hz: float = 0.1  # one guess in 10 s, after a burst of typos
    wrong_codes_per_address_burst: int = 5
    wrong_codes_class_hz: float = 1.0  # every address together: ~30 years for the code space
    wrong_codes_class_burst: int = 30
    max_worlds_per_address: int | None = None

    @field_validator("max_worlds_per_address")
    @classmethod
    def _at_least_one(cls, value: int | None) -> int | None:
        if value is not None and value < 1:
            raise ValueError("--max-worlds-per-address needs --classroom, and N >= 1")
        return value


class JoinQueueSettings(Section):
    """Joins that wait while the class server is at its capacity (server/classroom/join_queue.py):
    at most ``size`` wait, each at most ``wait_s`` and while its page polls at least every
    ``abandon_s``; a join refused is told to try again in ``retry_after_s``. ``size`` 0: a join
    past capacity is refused at once."""

    size: int = Field(default=20, ge=0, le=1000)
    wait_s: float = Field(default=300.0, gt=0, le=3600)
    abandon_s: float = Field(default=30.0, gt=0, le=3600)
    retry_after_s: float = Field(default=30.0, ge=1, le=3600)


class ClassroomSettings(Section):
    """A class on one server (``--classroom``): a world per student behind signed tokens; the
    instructor sees all. A world worker has one too: the class whose worlds it hosts."""

    code: str | None = None  # what students type to join; None: a new random one
    max_worlds: int = 60
    world: WorldLimits = WorldLimits()
    joins: JoinLimits = JoinLimits()
    join_queue: JoinQueueSettings = JoinQueueSettings()
    # Worlds the class server hosts itself; the rest go to world workers (None: up to max_worlds).
    local_worlds: int | None = None
    # World workers the class server starts on its own machine (--workers), on its own router:
    # N at its start, or "auto": one per spare core as the class grows, each ``spread_at`` worlds.
    local_workers: int | Literal["auto"] = "auto"
    spread_at: int = Field(default=SPREAD_AT_WORLDS, ge=1, le=1000)
    # Worlds a machine runs for each of its cores, over every place on it; a class whose machines
    # all have theirs queues the next join (server/classroom/budget.py). 0: no budget.
    worlds_per_core: int = Field(default=WORLDS_PER_CORE, ge=0, le=1000)
    worker_timeout_s: float = WORKER_TIMEOUT_S  # a world worker silent this long is gone: its worlds move
    world_log_level: str = "warning"  # the lowest level of a class world's node lines on the console
    # Each world's workspace is the folder of its name in here: kept across resets and restarts of
    # the server, removed when the instructor removes the student.
    workspaces_dir: Path = Path("workspaces")
    # The class secret, shared with the class's world workers (--class-secret-file): the class server
    # signs with it, so its tokens, the instructor's too, are the same after a restart. None: a
    # new random secret at every start.
    class_secret_file: Path | None = None

    @field_validator("max_worlds")
    @classmethod
    def _some_worlds(cls, value: int) -> int:
        if value < 1:
            raise ValueError("--max-worlds must be at least 1")
        return value

    @field_validator("local_worlds")
    @classmethod
    def _local_worlds(cls, value: int | None) -> int | None:
        if value is not None and value < 0:
            raise ValueError(LOCAL_WORLDS_RULE)
        return value

    @field_validator("local_workers")
    @classmethod
    def _local_workers(cls, value: int | str) -> int | str:
        if value != "auto" and not 0 <= int(value) <= MAX_LOCAL_WORKERS:
            raise ValueError(WORKERS_RULE)
        return value

    @property
    def auto_workers(self) -> bool:
        """Whether world workers start on this machine as the class grows (``--workers auto``)."""
        return self.local_workers == "auto"

    @property
    def workers_at_start(self) -> int:
        """World workers started with the class server (``--workers N``; none with auto)."""
        return 0 if self.local_workers == "auto" else self.local_workers

    @field_validator("worker_timeout_s")
    @classmethod
    def _worker_timeout(cls, value: float) -> float:
        if not 2.0 <= value <= 3600.0:
            raise ValueError("--worker-timeout must be in 2..3600 s")
        return value

    @field_validator("world_log_level")
    @classmethod
    def _level(cls, value: str) -> str:
        return log_level(value)

    @property
    def local_capacity(self) -> int:
        """Worlds this process hosts at most; the rest go to world workers."""
        return self.max_worlds if self.local_worlds is None else min(self.local_worlds, self.max_worlds)


class WorkerSettings(Section):
    """A world worker's identity (``ros2lab world-worker``): it hosts worlds a class server places."""

    id: str
    url: str  # where the class server reaches its HTTP API
    class_token: str = Field(repr=False)  # the instructor's token of its class (never sent anywhere)
    orphan_timeout_s: float = ORPHAN_TIMEOUT_S  # no hello from the class server this long: free the worlds
    # A worker its class server started on its own machine shares that machine's node-start slots
    # with it (server/host/processes/start_pacing.py): the file they are kept in. None: its own.
    start_slots: Path | None = None

    @field_validator("orphan_timeout_s")
    @classmethod
    def _orphan_timeout(cls, value: float) -> float:
        if not 1.0 <= value <= 3600.0:
            raise ValueError("--orphan-timeout must be in 1..3600 s")
        return value
