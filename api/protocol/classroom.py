"""What a class server's routes take and answer (api/routes/classroom.py, classroom_load.py): a join
and its queue, who a token is, the instructor's view of the worlds, the workers and the class's
graph, the instructor's controls, and the class's load."""

from __future__ import annotations

from typing import Any, Literal, Required

from pydantic import BaseModel, ConfigDict, Field, model_validator
from typing_extensions import TypedDict


class CpuOut(TypedDict):
    process_cores: float  # the process's CPU over its last window, in cores
    host_busy: float | None  # the machine's busy share (steal included)
    cores: int
    machine: str | None
    rss_mb: float | None  # the process's resident memory, MiB
    loop: Literal["realtime", "normal"] | None  # its worlds' loop thread's scheduling class
    saturated: bool


class PlaceOut(TypedDict):
    place: str  # "server" (this process) or a world worker's id
    worlds: int
    max_worlds: int
    late: int | None  # None: a worker that did not say
    cpu: CpuOut | None


class MachineOut(TypedDict):
    machine: str  # the digest of its boot id ("place:<id>" for a place that names none)
    worlds: int  # on every place of this machine
    cores: int
    budget: int  # worlds per core times cores: past it the machine takes no more worlds


class WaitingOut(TypedDict):
    student: str
    world: str
    waited_s: float


class QueueOut(TypedDict):
    waiting: list[WaitingOut]
    size: int
    wait_s: float
    let_through: int
    admitted: int
    refused: int


class ClassLoadOut(BaseModel):
    capacity: Literal["ok", "near", "full"] = Field(
        description="ok; near: a place's CPU is busy, a world is late or little room is left (joins still "
        "go ahead); full: no place has room by count or by its machine's world budget, or every place with "
        "room is saturated and a quarter of the worlds are late (new joins wait in the queue)"
    )
    reasons: list[str] = Field(description="why the verdict is near or full, one line each")
    worlds: int = Field(description="worlds in the class")
    late: int = Field(
        description="worlds late now: a timer of theirs ran over 50 ms after its deadline (median of its "
        "last 20 calls) or is 1 s overdue now (a stalled loop)"
    )
    room: int = Field(
        description="worlds that fit by count and by the machines' world budgets, over every place and the "
        "class's max_worlds"
    )
    places: list[PlaceOut] = Field(
        description="each place worlds run: 'server' (this process) or a world worker's id, with worlds, "
        "max_worlds, late and cpu (process_cores in cores, host_busy share, cores, rss_mb in MiB, loop: its "
        "worlds' loop thread's scheduling class, realtime or normal, saturated)"
    )
    machines: list[MachineOut] = Field(
        description="each machine's world budget (--worlds-per-core): its worlds over every place on it, its "
        "cores and its budget; empty without a budget"
    )
    queue: QueueOut = Field(
        description="joins waiting (student, world, waited_s), the queue's size and wait_s, let_through "
        "(joins the instructor let past a full verdict), admitted and refused so far"
    )


class LetThrough(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid")
    count: int = Field(default=1, ge=1, le=100, description="waiting joins to let in past a full verdict")


class JoinRequest(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid")
    name: str = Field(min_length=1, max_length=64, examples=["Ada Lovelace"])
    code: str = Field(min_length=1, max_length=16, examples=["K7PX2M"])


class BroadcastRequest(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid")
    topic: str = Field(min_length=1, max_length=256, examples=["/uav/input/position"])
    msg: dict[str, Any] = Field(examples=[{"x": 5.0, "y": 5.0, "z": 10.0}])
    type: str | None = Field(default=None, max_length=128, examples=["geometry_msgs/msg/Vector3"])


class HostRequest(BaseModel):
    """A class server placing a world on this world worker."""

    model_config = ConfigDict(strict=True, extra="forbid")
    world: str = Field(min_length=1, max_length=32, pattern=r"^[a-z_][a-z0-9_]*$")
    student: str = Field(min_length=1, max_length=64)
    domain_id: int = Field(ge=1, le=232)
    launch: str = Field(min_length=1, max_length=256)
    launch_args: dict[str, str] = Field(default_factory=dict, max_length=32)
    # The world's own Zenoh login, drawn by the class server (its graph joins the router with it).
    zenoh_user: str | None = Field(None, min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_-]+$")
    zenoh_password: str | None = Field(None, min_length=1, max_length=64, pattern=r"^[A-Za-z0-9]+$")
    # The class router's Unix socket: a worker on its machine runs the world's students' nodes
    # in a sandbox that reaches the router there.
    router_socket: str | None = Field(None, min_length=2, max_length=256, pattern=r"^/[A-Za-z0-9_./-]+$")
    # The class server's copy of the world's progress, for a worker whose own folder lacks it
    # (server/world/checkpoints/handover.py's form).
    progress: dict[str, Any] | None = None

    @model_validator(mode="after")
    def _login_whole(self) -> HostRequest:
        if (self.zenoh_user is None) != (self.zenoh_password is None):
            raise ValueError("zenoh_user and zenoh_password come together")
        return self


class Joined(BaseModel):
    world: str = Field(examples=["ada_lovelace"])
    student: str = Field(examples=["Ada Lovelace"])
    token: str = Field(description="this world's bearer token; the page keeps it in an HTTP-only cookie")


class QueuedJoin(BaseModel):
    ticket: str = Field(description="the join's secret: ask again with GET /api/classroom/join/{ticket}")
    ahead: int = Field(description="joins waiting ahead of this one")
    student: str
    poll_s: float = Field(description="ask again this often, or the join leaves the queue")
    why: str = Field(description="why it waits")


class Me(BaseModel):
    role: Literal["student", "instructor"]
    world: str | None = Field(description="the student's world; none for the instructor")
    name: str
    class_code: str | None = Field(default=None, description="only for the instructor")


class RocketState(TypedDict):
    phase: str
    altitude_m: float


class ClassWorld(TypedDict, total=False):
    """One world as the instructor's page shows it; the lab's own figures only while it runs,
    and a world on a world worker as its worker reports them."""

    world: Required[str]
    student: Required[str]
    domain_id: Required[int | None]  # its ROS domain on the class's Zenoh graph; null: no graph
    joined_at: Required[float]  # s, Unix epoch
    resets: Required[int]
    writes_refused: Required[int]  # the student's writes over the world's rate limit
    worker: Required[str | None]  # the world worker hosting it; null on this server
    moves: Required[int]  # times it started again elsewhere because its world worker was gone
    lost: Required[str | None]  # why it cannot be reached now
    worker_error: str  # why its world worker did not answer
    keys_held: list[str]
    rocket: RocketState | None
    drone: list[float] | None  # x, y, z (m); null before the first fix
    crashed_nodes: list[str]
    nodes: int


class ClassWorlds(BaseModel):
    class_code: str
    max_worlds: int
    worlds: list[ClassWorld] = Field(
        description="each world: student, where it runs, keys held, rocket phase, drone, crashed nodes"
    )


class LocalRoom(BaseModel):
    worlds: int = Field(description="worlds this server runs itself")
    max_worlds: int = Field(description="how many it takes")
    cpu: CpuOut


class WorkerOut(BaseModel):
    id: str
    url: str
    worlds: int
    max_worlds: int
    cpu: CpuOut | None = Field(description="null: it did not say")
    late: int | None = Field(description="its worlds late now; null: it did not say")


class StartedWorker(BaseModel):
    id: str
    pid: int | None = Field(description="null while it is down")
    restarts: int
    given_up: bool = Field(description="it kept dying: no more restarts")


class Spread(BaseModel):
    at_worlds: int = Field(description="another world worker each this many worlds")
    up_to: int = Field(description="at most this many (the machine's spare cores)")


class ClassWorkers(BaseModel):
    local: LocalRoom = Field(
        description="this server's own worlds, how many it takes, and its CPU (process_cores: this process's "
        "CPU over the last window in cores; host_busy: the machine's busy share; machine: a digest of its "
        "boot id; loop: its worlds' loop thread's scheduling class, realtime or normal; saturated: the process "
        "uses 0.85 core or the machine is 90 % busy. No new world goes to a "
        "full process while another place has room, nor to a busy machine while another machine has room)"
    )
    workers: list[WorkerOut] = Field(
        description="each world worker that answers now, with its load: worlds, max_worlds and cpu, as for local"
    )
    started_here: list[StartedWorker] = Field(
        default_factory=list,
        description="the world workers this server started on its machine (--workers): id, pid (null while "
        "down), restarts, and given_up once it kept dying",
    )
    spread: Spread | None = Field(
        default=None,
        description="with --workers auto: another world worker on this machine each at_worlds worlds, at most "
        "up_to (the machine's spare cores); null when workers start only as --workers N said",
    )


class ClassGraph(BaseModel):
    domain_id: int = Field(description="the class's own ROS domain, where every world shows under /<world>")
    topics: dict[str, list[str]] = Field(
        description="by world, each bridged topic or service: 'out' (the world publishes it; 'out*' while "
        "something in the class domain subscribes, so it crosses now), 'in' (the world subscribes to it) "
        "or 'srv' (the world serves it; a call in the class domain goes to that world's server)",
        examples=[
            {"ada": ["in /ada/uav/input/position", "out* /ada/uav/sensors/gps", "srv /ada/rocket/reset"]}
        ],
    )
    samples_out: int = Field(description="samples passed from worlds into the class domain")
    samples_in: int = Field(description="samples passed from the class domain into worlds")
    dropped: int = Field(description="samples dropped (no rmw_zenoh attachment, or a watcher too slow)")
    calls: int = Field(description="service calls in the class domain answered by a world's server")
    names_refused: dict[str, int] = Field(
        description="by world, its entities not bridged because their name is not a fully qualified ROS "
        "name (or their type is not a plain type name): 'm/uav/sensors/gps' in world ada would be /adam/...",
        examples=[{"ada": 1}],
    )
    calls_refused: int = Field(
        description="service calls refused: no rmw_zenoh attachment, a key pattern instead of one service, "
        "or too many waiting on one world"
    )


class Broadcast(BaseModel):
    reached: list[str]
    refused: dict[str, str] = Field(description="world: why its graph refused the message")


class ResetWorlds(BaseModel):
    reset: list[str] = Field(description="the worlds started over")


class Kicked(BaseModel):
    kicked: str = Field(description="the world removed")
    student: str
