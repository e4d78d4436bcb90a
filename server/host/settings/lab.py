"""The sections every app has: where it listens (``listen``), what its lab runs (``lab``), what a
lab's clients may hold (``limits``), a student's workspace (``workspace``) and how a student's
node runs where the server serves others (``sandbox``)."""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import Field, InstanceOf

from node_runtime.transport.config import ZenohSettings
from server.host.settings.base import ANY_ADDRESS, LOOPBACK_HOSTS, Section, is_loopback_host

WORKSPACE_DEPTH = 16  # the default depth of a workspace path (server/services/workspace/paths.py)
# The Foxglove WebSocket server's port of ``python -m server`` (--foxglove-port); a lab built by
# hand (a test's) starts none: ``LabSettings.foxglove_port`` is None.
FOXGLOVE_PORT = 8765


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
    # checkpoint progress (server/world/checkpoints/store.py).
    state_dir: Path = Path("state")
    # Checkpoints a lab adds to the three of this one, as ``package.module:NAME`` (docs/checkpoints.md).
    checkpoints: tuple[str, ...] = ()
    # The Foxglove WebSocket server's port on the listening host; None: off (``python -m server``
    # uses FOXGLOVE_PORT).
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
    # Folders a path may go down (a file at this depth is the deepest the API reads, writes and
    # lists); the tree counts what lies deeper instead of listing it. At most 64: a walk holds a
    # folder open per level.
    max_depth: int = Field(default=WORKSPACE_DEPTH, ge=1, le=64)


class SandboxSettings(Section):
    """How a server that serves others runs a student's node process (server/host/processes/sandbox.py):
    in bubblewrap with these limits, or (``unsandboxed``, said out loud) as a single lab does."""

    student_code: Literal["sandboxed", "unsandboxed"] = "sandboxed"
    memory_mib: int = Field(default=512, ge=64)  # heap, stacks and private mappings
    processes: int = Field(default=64, ge=16)  # processes and threads (Zenoh's take about 10)
    open_files: int = Field(default=256, ge=64)
    file_size_mib: int = Field(default=64, ge=1)
    cpu_s: int = Field(default=3600, ge=1)  # CPU seconds of one run
    nice: int = Field(default=19, ge=0, le=19)  # below the sims' loop
