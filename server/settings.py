"""Settings for one app instance: where it listens, what it launches, what it lets in."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from server.transport.config import ZenohSettings

LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
# A class's world workers: the class server takes a worker silent this long as gone and
# starts its worlds again elsewhere; a worker that hears no hello this long frees its worlds first.
WORKER_TIMEOUT_S = 20.0
ORPHAN_TIMEOUT_S = 12.0
MAX_LOCAL_WORKERS = 32  # --workers: world workers a class server starts on its own machine


@dataclass(frozen=True)
class WorkerSettings:
    """A world worker's identity (``ros2lab world-worker``): it hosts worlds a class server places."""

    id: str
    url: str  # where the class server reaches its HTTP API
    class_token: str  # the instructor's token of the class it serves (never sent anywhere)
    orphan_timeout_s: float = ORPHAN_TIMEOUT_S  # no hello from the class server this long: free the worlds


@dataclass(frozen=True)
class JoinLimits:
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


@dataclass(frozen=True)
class Settings:
    host: str = "127.0.0.1"
    port: int = 8000
    launch: str = "all"  # rocket | fly | all | a path to a launch file
    launch_args: dict[str, str] = field(default_factory=dict)
    workspace: Path | None = Path("workspace")  # students' packages (src/<pkg>/...); may not exist
    viewer: bool = True  # start viser (tests of the API alone may switch it off)
    # Extra Host names and Origins to accept besides this machine's loopback names.
    allowed_hosts: tuple[str, ...] = ()
    allowed_origins: tuple[str, ...] = ()
    max_body_bytes: int = 64 * 1024
    max_ws_frame_bytes: int = 16 * 1024
    # Key frames a lab (a world, on a class server) takes a second, bursts of: over it, keydowns
    # are dropped (keyups and release_all never are, so no key sticks).
    key_frames_hz: float = 200.0
    key_frames_burst: int = 400
    # Frames a lab's WebSockets send a second, all together (topic echoes and rosbridge), and
    # rosbridge requests they take; None: no limit. Over it a socket waits its turn (its oldest
    # messages drop as for a slow client; a client's requests wait in its own TCP buffer).
    socket_frames_hz: float | None = None
    socket_requests_hz: float | None = None
    deadman_s: float = 0.5  # a key channel silent this long with keys held has them released
    max_api_topics: int = 256  # topics the REST API may create, so a loop of typos cannot grow memory
    max_publishers: int = 64  # periodic publishers running at once
    max_echo_sockets: int = 64  # /ws/topics clients at once
    max_launch_groups: int = 32  # launches and runs started through the API, at once
    max_nodes_per_launch: int = 64
    # The graph on Zenoh (rmw_zenoh's wire format); None keeps every node in this process. The
    # command line turns it on (a router on tcp/127.0.0.1:7447); tests that need it say so.
    zenoh: ZenohSettings | None = None
    # Which nodes run as their own processes: a student's files always; "all" adds every lab node
    # but those that drive the app's devices (the page's keys, the 3D view).
    node_processes: Literal["student", "all"] = "student"
    # -- tools robotics people use --
    bag_dir: Path = Path("bags")  # where recordings go, one folder per bag, as ros2 bag writes them
    # The Foxglove WebSocket server's port on ``host``; None: off (``python -m server`` uses 8765).
    foxglove_port: int | None = None
    # rosbridge on a port of its own too, as rosbridge_server's 9090; None: only at /rosbridge.
    rosbridge_port: int | None = None

    # One lab behind a token (``--token``): every call, page and bridge port needs it. Required
    # (with --classroom the other way) when the app listens beyond loopback.
    token: str | None = None
    # -- a class on one server --
    classroom: bool = False  # a world per student, behind signed tokens; the instructor sees all
    class_code: str | None = None  # what students type to join; None: a new random one
    max_worlds: int = 60
    world_writes_hz: float = 20.0  # a student's REST writes per second in their world, bursts of:
    world_writes_burst: int = 40
    # What one student's world may hold, so its load stays its own: launches and runs started
    # through the API (and nodes in each), resets (also writes), and WebSockets of every kind.
    world_launches: int = 4
    world_launch_nodes: int = 16
    world_resets_hz: float = 1 / 30  # a reset blocks the shared loop ~0.1 s: a world starts over
    world_resets_burst: int = 2
    world_sockets: int = 24
    world_socket_frames_hz: float = 400.0  # a page's pose stream is 100; bursts of a second's worth
    world_socket_requests_hz: float = 200.0
    joins: JoinLimits = field(default_factory=JoinLimits)
    # Samples a second a class world takes from other processes on Zenoh (its student's nodes);
    # a flood beyond that is dropped as it arrives, so it costs the shared loop nothing.
    world_samples_hz: float = 2000.0
    # Worlds the class server hosts itself; the rest go to world workers (None: up to max_worlds).
    local_worlds: int | None = None
    # World workers the class server starts on its own machine (--workers), on its own router.
    local_workers: int = 0  # at most MAX_LOCAL_WORKERS
    worker: WorkerSettings | None = None  # set on a world worker: worlds come from a class server
    worker_timeout_s: float = WORKER_TIMEOUT_S  # a world worker silent this long is gone: its worlds move
    world_log_level: str = "warning"  # the lowest level of a class world's node lines on the console

    def __post_init__(self) -> None:
        for name in ("port", "foxglove_port", "rosbridge_port"):
            port = getattr(self, name)
            if port is not None and not 0 <= port <= 65535:
                raise ValueError(f"{name} must be in 0..65535, got {port}")
        if not 0 <= self.local_workers <= MAX_LOCAL_WORKERS:
            raise ValueError(f"local_workers must be in 0..{MAX_LOCAL_WORKERS}, got {self.local_workers}")
        if self.max_body_bytes < 1024 or self.max_ws_frame_bytes < 256:
            raise ValueError("size limits are too small to carry a message")

    @property
    def confines_paths(self) -> bool:
        """Bag and launch files are names inside the world's own folders, never paths: on a class
        server (and its world workers), and when a lab behind a token listens beyond loopback. A
        single lab on loopback serves its user alone, whose own files it may open."""
        loopback = self.host in LOOPBACK_HOSTS or self.host.startswith("127.")
        return self.classroom or self.worker is not None or not loopback

    @property
    def accepted_hosts(self) -> frozenset[str]:
        hosts = set(LOOPBACK_HOSTS) | set(self.allowed_hosts)
        if self.host not in ("0.0.0.0", "::"):
            hosts.add(self.host)
        return frozenset(h.lower() for h in hosts)
