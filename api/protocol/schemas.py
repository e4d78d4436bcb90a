"""Request and response bodies of the REST API (pydantic at the boundary only)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from server.services.api_node.publishers import MAX_RATE_HZ, MIN_RATE_HZ
from server.services.api_node.topic_watch import WatchState

MAX_NAME_CHARS = 256  # topic and type names
WATCH = Field(
    default=None,
    description="for a topic only other processes use: 'started' when this request began listening "
    "to it, as ros2 topic echo does (its messages show from now on), 'running' while an earlier "
    "request's listening goes on (until 30 s after the last); null when the app itself subscribes",
)


class TopicSummary(BaseModel):
    name: str = Field(examples=["/countdown"])
    type: str = Field(examples=["std_msgs/msg/Int64"])
    publishers: list[str] = Field(description="fully qualified names of the publishing nodes")
    subscribers: list[str] = Field(description="fully qualified names of the subscribing nodes")
    type_conflict: bool = Field(
        default=False, description="endpoints on this name disagree on its type (each type is listed)"
    )


class EndpointDetail(BaseModel):
    node: str = Field(examples=["/CountDownNode"])
    kind: str = Field(examples=["publisher"], description="publisher or subscriber")
    depth: int = Field(description="QoS depth (keep-last)")
    location: str = Field(
        examples=["app"], description="'app' (the lab's own process) or 'zenoh:<session>' (another process)"
    )


class TopicDetail(TopicSummary):
    endpoints: list[EndpointDetail] = Field(
        default_factory=list, description="who publishes and subscribes, where"
    )
    latest: dict[str, Any] | None = Field(description="the last message published, or null")
    latest_time: float | None = Field(description="when it was published (s, Unix epoch)")
    publish_count: int
    watch: WatchState | None = WATCH
    publisher_depths: list[int] = Field(description="QoS depth (keep-last) of each publisher")
    subscriber_depths: list[int] = Field(description="QoS depth (keep-last) of each subscription")


class PublishRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    topic: str = Field(max_length=MAX_NAME_CHARS, examples=["/abort_takeoff"])
    msg: dict[str, Any] = Field(default_factory=dict, examples=[{"data": True}])
    type: str | None = Field(
        default=None,
        max_length=MAX_NAME_CHARS,
        description="needed only when the topic does not exist yet",
        examples=["std_msgs/msg/Bool"],
    )


class PublishResult(BaseModel):
    topic: str
    type: str
    subscribers: int = Field(description="how many subscriptions received the message")


class ZenohStatus(BaseModel):
    mode: str = Field(examples=["router"], description="router (the app is the graph's router) or peer")
    router: str = Field(examples=["tcp/127.0.0.1:7447"], description="where node processes connect")
    listen: list[str] = Field(description="where the app's router listens")
    connect: list[str] = Field(description="the router the app joined, in peer mode")
    domain_id: int
    login: bool = Field(description="the router asks for a user and password: GET /api/zenoh/join gives them")
    zid: str = Field(description="the app's Zenoh session id")
    processes: int = Field(description="other processes in the graph now")
    sent: int = Field(description="samples the app put on Zenoh")
    received: int = Field(description="samples the app took from Zenoh")
    dropped_without_attachment: int = Field(description="samples refused: no rmw_zenoh attachment")
    dropped_over_rate: int = Field(
        description="samples dropped as they arrived: a class world takes at most so many a second from other processes"
    )


class WorkspaceInfo(BaseModel):
    """Where the lab's students' packages are, for ``ros2lab run`` and ``ros2lab pkg`` on its machine."""

    path: str | None = Field(description="the workspace folder's absolute path on the lab's machine, or null")


class ZenohJoin(BaseModel):
    """How a node process joins this lab's graph on Zenoh (a student's: their world's; the instructor
    naming no world: the class's own, every world under its name)."""

    router: str = Field(examples=["tcp/127.0.0.1:7447"], description="the router to connect to")
    domain_id: int = Field(description="the ROS_DOMAIN_ID of the graph")
    user: str | None = Field(
        description="the user the router asks for (a class server's: the world's own), or null"
    )
    password: str | None = Field(description="its password, or null")
    env: dict[str, str] = Field(
        description="the environment that makes ros2lab run, or a ROS 2 node on rmw_zenoh, join this graph",
        examples=[
            {"ROS_DOMAIN_ID": "3", "ZENOH_CONFIG_OVERRIDE": 'connect/endpoints=["tcp/127.0.0.1:7447"]'}
        ],
    )
    nice: int | None = Field(
        default=None,
        description="the CPU niceness a node process of this server's graph takes, so the worlds' loop "
        "goes first (a class server's students' nodes: ros2lab run lowers its node to it); null: none",
    )


class Status(BaseModel):
    """What a control that only acts answers: what it did."""

    status: str = Field(examples=["reset"])


class Health(BaseModel):
    status: str
    launch: str
    nodes: int
    topics: int
    uptime_s: float
    zenoh: ZenohStatus | None = Field(default=None, description="null when the graph stays in the app")
    zenoh_error: str | None = Field(default=None, description="why Zenoh is off, when it was asked for")


class RatePublisherRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    topic: str = Field(max_length=MAX_NAME_CHARS, examples=["/uav/input/position"])
    msg: dict[str, Any] = Field(default_factory=dict, examples=[{"x": 5.0, "y": 5.0, "z": 10.0}])
    type: str | None = Field(
        default=None, max_length=MAX_NAME_CHARS, description="needed only when the topic does not exist yet"
    )
    rate_hz: float = Field(
        ge=MIN_RATE_HZ, le=MAX_RATE_HZ, examples=[1.0], description="publishing rate, 0.01 to 1000 Hz"
    )
    enabled: bool = True


class RatePublisherUpdate(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    msg: dict[str, Any] | None = None
    rate_hz: float | None = Field(default=None, ge=MIN_RATE_HZ, le=MAX_RATE_HZ)
    enabled: bool | None = None


class RatePublisherInfo(BaseModel):
    id: str
    topic: str
    type: str
    msg: dict[str, Any]
    rate_hz: float
    enabled: bool
    count: int = Field(description="messages published so far")
