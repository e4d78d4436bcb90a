"""Settings for one app instance, in one frozen model: where it listens and what it lets in
(``listen``), what its lab runs (``lab``), what a lab's clients may hold (``limits``), and, for a
class server or a world worker, the class (``classroom``) and the worker (``worker``).

Every rule across fields lives here, so ``python -m server``, ``ros2lab world-worker`` and a test
that builds settings by hand meet the same ones. Their messages name the command-line options,
where people meet them; :func:`explain` turns a ``ValidationError`` into those lines, and
:func:`is_refusal` tells an unsafe combination (no login beyond loopback) from a usage mistake.
"""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    InstanceOf,
    ValidationError,
    field_validator,
    model_validator,
)
from pydantic_core import PydanticCustomError

from server.console import LEVELS
from server.transport.config import ZenohSettings, is_loopback

LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
ANY_ADDRESS = ("0.0.0.0", "::")
# A class's world workers: the class server takes a worker silent this long as gone and
# starts its worlds again elsewhere; a worker that hears no hello this long frees its worlds first.
WORKER_TIMEOUT_S = 20.0
ORPHAN_TIMEOUT_S = 12.0
MAX_LOCAL_WORKERS = 32  # --workers: world workers a class server starts on its own machine
SPREAD_AT_WORLDS = 10  # --workers auto: another world worker on this machine each this many worlds
REFUSAL = "login_required"  # the error type of an app that would listen beyond loopback with no login

WORKERS_RULE = (
    "--workers needs --classroom and this server's own Zenoh router (world workers join it), "
    f"and N in 0..{MAX_LOCAL_WORKERS} or auto"
)
LOCAL_WORLDS_RULE = "--local-worlds needs --classroom and Zenoh (world workers join its router), and N >= 0"


def is_loopback_host(host: str) -> bool:
    return host in LOOPBACK_HOSTS or host.startswith("127.")


class Section(BaseModel):
    """A frozen group of settings that refuses names it does not know (a typo is an error)."""

    model_config = ConfigDict(frozen=True, extra="forbid")


class Listening(Section):
    """Where the app listens and what its doors let in (the HTTP port and every bridge port)."""

    host: str = "127.0.0.1"
    port: int = Field(default=8000, ge=0, le=65535)
    # One lab behind a token (``--token``): every call, page and bridge port needs it. Required
    # (with --classroom the other way) when the app listens beyond loopback.
    token: str | None = None
    # Extra Host names and Origins to accept besides this machine's loopback names.
    allowed_hosts: tuple[str, ...] = ()
    allowed_origins: tuple[str, ...] = ()
    max_body_bytes: int = Field(default=64 * 1024, ge=1024)  # smaller could not carry a message
    max_ws_frame_bytes: int = Field(default=16 * 1024, ge=256)

    @property
    def on_loopback(self) -> bool:
        return is_loopback_host(self.host)

    @property
    def accepted_hosts(self) -> frozenset[str]:
        hosts = set(LOOPBACK_HOSTS) | set(self.allowed_hosts)
        if self.host not in ANY_ADDRESS:
            hosts.add(self.host)
        return frozenset(h.lower() for h in hosts)


class LabSettings(Section):
    """What a lab runs: its launch, the students' packages, the 3D view, its graph and its tools."""

    launch: str = "all"  # rocket | fly | all | a path to a launch file
    launch_args: dict[str, str] = Field(default_factory=dict)
    workspace: Path | None = Path("workspace")  # students' packages (src/<pkg>/...); may not exist
    viewer: bool = True  # start viser (tests of the API alone may switch it off)
    # The graph on Zenoh (rmw_zenoh's wire format); None keeps every node in this process. The
    # command line turns it on (a router on tcp/127.0.0.1:7447); tests that need it say so.
    zenoh: InstanceOf[ZenohSettings] | None = None
    # Which nodes run as their own processes: a student's files always; "all" adds every lab node
    # but those that drive the app's devices (the page's keys, the 3D view).
    node_processes: Literal["student", "all"] = "student"
    bag_dir: Path = Path("bags")  # where recordings go, one folder per bag, as ros2 bag writes them
    # What the server keeps across restarts: the key that signs checkpoint reports, and each world's
    # checkpoint progress (server/checkpoints/store.py).
    state_dir: Path = Path("state")
    # Checkpoints a lab adds to the three of this one, as ``package.module:NAME`` (docs/checkpoints.md).
    checkpoints: tuple[str, ...] = ()
    # The Foxglove WebSocket server's port on the listening host; None: off (``python -m server`` uses 8765).
    foxglove_port: int | None = Field(default=None, ge=0, le=65535)
    # rosbridge on a port of its own too, as rosbridge_server's 9090; None: only at /rosbridge.
    rosbridge_port: int | None = Field(default=None, ge=0, le=65535)

    @property
    def zenoh_router(self) -> ZenohSettings | None:
        """The Zenoh session when this lab is the graph's router (None: no Zenoh, or a peer/client)."""
        return self.zenoh if self.zenoh is not None and self.zenoh.mode == "router" else None


class LabLimits(Section):
    """What one lab's clients may hold and send, so a loop of typos cannot grow memory."""

    # Key frames a lab (a world, on a class server) takes a second, bursts of: over it, keydowns
    # are dropped (keyups and release_all never are, so no key sticks).
    key_frames_hz: float = Field(default=200.0, gt=0)
    key_frames_burst: int = Field(default=400, ge=1)
    # Frames a lab's WebSockets send a second, all together (topic echoes and rosbridge), and
    # rosbridge requests they take; None: no limit. Over it a socket waits its turn (its oldest
    # messages drop as for a slow client; a client's requests wait in its own TCP buffer).
    socket_frames_hz: float | None = Field(default=None, gt=0)
    socket_requests_hz: float | None = Field(default=None, gt=0)
    deadman_s: float = Field(
        default=0.5, gt=0
    )  # a key channel silent this long with keys held has them released
    max_api_topics: int = Field(default=256, ge=1)  # topics the REST API may create
    max_publishers: int = Field(default=64, ge=1)  # periodic publishers running at once
    max_echo_sockets: int = Field(default=64, ge=1)  # /ws/topics clients at once
    max_launch_groups: int = Field(default=32, ge=1)  # launches and runs started through the API, at once
    max_nodes_per_launch: int = Field(default=64, ge=1)
    # Node processes the API's launches and runs keep running at once: in this lab (a class's
    # world), and in every lab of this process together (a class server's or world worker's).
    max_running_nodes: int = Field(default=8, ge=1)
    max_server_nodes: int = Field(default=64, ge=1)


class WorkspaceLimits(Section):
    """What a student's workspace may hold (the API's saves, uploads and new packages), and the
    largest body a workspace route takes (a save's JSON, a zip upload)."""

    max_file_bytes: int = Field(default=256 * 1024, ge=1024)
    max_workspace_bytes: int = Field(default=20 * 1024 * 1024, ge=1024)
    max_files: int = Field(default=2000, ge=1)
    max_body_bytes: int = Field(default=8 * 1024 * 1024, ge=1024)


class SandboxSettings(Section):
    """How a server that serves others runs a student's node process (server/processes/sandbox.py):
    in bubblewrap with these limits, or (``unsandboxed``, said out loud) as a single lab does."""

    student_code: Literal["sandboxed", "unsandboxed"] = "sandboxed"
    memory_mib: int = Field(default=512, ge=64)  # heap, stacks and private mappings
    processes: int = Field(default=64, ge=16)  # processes and threads (Zenoh's take about 10)
    open_files: int = Field(default=256, ge=64)
    file_size_mib: int = Field(default=64, ge=1)
    cpu_s: int = Field(default=3600, ge=1)  # CPU seconds of one run
    nice: int = Field(default=19, ge=0, le=19)  # below the sims' loop


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
    worker_timeout_s: float = WORKER_TIMEOUT_S  # a world worker silent this long is gone: its worlds move
    world_log_level: str = "warning"  # the lowest level of a class world's node lines on the console
    # Each world's workspace is the folder of its name in here: kept across resets and restarts of
    # the server, removed when the instructor removes the student.
    workspaces_dir: Path = Path("workspaces")

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
        return _log_level(value)

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

    @field_validator("orphan_timeout_s")
    @classmethod
    def _orphan_timeout(cls, value: float) -> float:
        if not 1.0 <= value <= 3600.0:
            raise ValueError("--orphan-timeout must be in 1..3600 s")
        return value


class Settings(Section):
    """One app: a single lab (no ``classroom``), a class server (``classroom``) or a world
    worker (``classroom`` and ``worker``)."""

    listen: Listening = Listening()
    lab: LabSettings = LabSettings()
    limits: LabLimits = LabLimits()
    workspace: WorkspaceLimits = WorkspaceLimits()
    classroom: ClassroomSettings | None = None
    worker: WorkerSettings | None = None
    sandbox: SandboxSettings = SandboxSettings()
    log_level: str = "info"  # the app's own console lines and uvicorn's

    @field_validator("log_level")
    @classmethod
    def _level(cls, value: str) -> str:
        return _log_level(value)

    @model_validator(mode="after")
    def _class_needs_zenoh(self) -> Settings:
        classroom = self.classroom
        if classroom is None:
            return self
        # auto needs no router: without one (--no-zenoh, or a client of another) none are started
        if classroom.workers_at_start and self.lab.zenoh_router is None:
            raise ValueError(WORKERS_RULE)
        if classroom.local_worlds is not None and self.lab.zenoh is None:
            raise ValueError(LOCAL_WORLDS_RULE)
        return self

    @model_validator(mode="after")
    def _worker_is_reachable(self) -> Settings:
        if self.worker is None:
            return self
        if self.classroom is None:
            raise ValueError("a world worker hosts a class's worlds: it needs the classroom section")
        host = self.worker.url.partition("://")[2].rpartition(":")[0].strip("[]")
        if host in ANY_ADDRESS:
            raise ValueError(
                "with --host 0.0.0.0, name the address the class server reaches this machine on: --advertise HOST"
            )
        return self

    @model_validator(mode="after")
    def _login_beyond_loopback(self) -> Settings:
        """Anyone who reaches a port beyond loopback could fly the drone: such an app needs a login,
        one lab's token or a class's."""
        if self.classroom is not None or self.listen.token is not None:
            return self
        if not self.listen.on_loopback:
            raise PydanticCustomError(
                REFUSAL,
                "refusing to listen on {host} with no login: anyone who reaches this machine could fly the "
                "drone. Add --token auto (one lab behind a token) or --classroom (a world per student).",
                {"host": self.listen.host},
            )
        router = self.lab.zenoh_router
        wide = [e for e in router.listen if not is_loopback(e)] if router is not None else []
        if wide:
            raise PydanticCustomError(
                REFUSAL,
                "refusing to open the Zenoh router on {wide} with no login: anyone who reaches it could join "
                "the graph and fly the drone. Add --token auto (the router then asks every session for the "
                "lab's login: GET /api/zenoh/join gives it) or --classroom.",
                {"wide": ", ".join(wide)},
            )
        return self

    def for_world(
        self, name: str, zenoh: ZenohSettings | None, launch: str, launch_args: dict[str, str]
    ) -> Settings:
        """A class world's lab: its own graph session (``zenoh``), launch, bag folder and workspace, no bridge
        port of its own (the class's serve every world), and the smaller of each lab limit and the
        class's limit per world."""
        if self.classroom is None:
            raise ValueError("only a class server or a world worker has worlds")
        world, limits = self.classroom.world, self.limits
        lab = self.lab.model_copy(update={
            "zenoh": zenoh, "foxglove_port": None, "rosbridge_port": None, "bag_dir": self.lab.bag_dir / name,
            "launch": launch, "launch_args": launch_args, "workspace": self.classroom.workspaces_dir / name,
        })  # fmt: skip
        limits = limits.model_copy(update={
            "max_launch_groups": min(limits.max_launch_groups, world.launches),
            "max_nodes_per_launch": min(limits.max_nodes_per_launch, world.launch_nodes),
            "socket_frames_hz": world.socket_frames_hz, "socket_requests_hz": world.socket_requests_hz,
        })  # fmt: skip
        return self.model_copy(update={"lab": lab, "limits": limits})

    @property
    def confines_paths(self) -> bool:
        """Bag and launch files are names inside the world's own folders, never paths: on a class
        server (and its world workers), and when a lab behind a token listens beyond loopback. A
        single lab on loopback serves its user alone, whose own files it may open."""
        return self.classroom is not None or not self.listen.on_loopback

    @property
    def sandboxes_students(self) -> bool:
        """Students' node processes run in a sandbox: wherever the server serves others, unless
        started with ``--student-code unsandboxed``."""
        return self.confines_paths and self.sandbox.student_code == "sandboxed"


def class_section(settings: Settings) -> ClassroomSettings:
    """The class's section of a class server's or a world worker's settings (ValueError on a
    single lab's, which has no class)."""
    if settings.classroom is None:
        raise ValueError("a class server or world worker needs settings with a classroom section")
    return settings.classroom


def _log_level(value: str) -> str:
    if value not in LEVELS:
        raise ValueError(f"a log level is one of {', '.join(LEVELS)}, got {value!r}")
    return value


def explain(error: ValidationError) -> str:
    """The error's lines as a person reads them: a rule's own message, or a field's path and what
    is wrong with its value."""
    lines = []
    for item in error.errors(include_url=False):
        message = item["msg"].removeprefix("Value error, ")
        where = ".".join(str(part) for part in item["loc"])
        lines.append(f"{where}: {message}" if where and item["type"] != "value_error" else message)
    return "\n".join(lines)


def is_refusal(error: ValidationError) -> bool:
    """The settings are well formed but unsafe: a port beyond loopback with no login."""
    return any(item["type"] == REFUSAL for item in error.errors())
