"""What the ROS tools' routes answer (api/routes/introspection.py): rqt_graph's graph,
``ros2 node list/info``, ``ros2 topic hz``, and a message type's default and JSON Schema."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, RootModel
from typing_extensions import TypedDict

from api.protocol.schemas import WATCH
from server.services.api_node.topic_watch import WatchState

LOCATION = Field(
    default="app",
    description="where the node runs: 'app' (the lab's own process) or 'zenoh:<session>' (another process)",
    examples=["app", "zenoh:3ca7751b"],
)


class GraphNodeOut(BaseModel):
    name: str = Field(examples=["/CountDownNode"])
    state: Literal["active", "crashed", "died"]
    hidden: bool = Field(description="a name token starts with '_'")
    location: str = LOCATION


class GraphTopicOut(BaseModel):
    name: str = Field(examples=["/countdown"])
    type: str = Field(examples=["std_msgs/msg/Int64"])
    hidden: bool = Field(description="an internal topic (/rosout, /parameter_events) or a '_' token")
    type_conflict: bool = Field(
        default=False, description="endpoints on this name disagree on its type: one box per type"
    )


class GraphEdgeOut(BaseModel):
    model_config = ConfigDict(populate_by_name=True)
    from_: str = Field(alias="from", description="the publishing node, or the topic a node subscribes to")
    to: str = Field(description="the topic published on, or the subscribing node")
    kind: Literal["publish", "subscribe"]


class GraphOut(BaseModel):
    version: int = Field(
        description="changes whenever a node, topic or endpoint comes or goes, or a node crashes"
    )
    nodes: list[GraphNodeOut]
    topics: list[GraphTopicOut]
    edges: list[GraphEdgeOut]


class RespawnOut(BaseModel):
    state: Literal["running", "waiting", "gave up"]
    respawns: int = Field(description="restarts so far")
    fast_failures: int = Field(description="crashes in a row soon after starting (the backoff doubles each)")
    next_in_s: float | None = Field(description="seconds until the next restart, while waiting")


class NodeSummaryOut(BaseModel):
    name: str = Field(examples=["/CountDownNode"])
    namespace: str = Field(examples=["/"])
    state: Literal["active", "crashed", "died"] = Field(
        description="crashed: a node inside the app whose callback raised; died: a node process that ended"
    )
    location: str = LOCATION
    exit_code: int | None = Field(default=None, description="a died process's exit code")
    respawn: RespawnOut | None = Field(
        default=None, description='only for nodes launched with respawn="true"'
    )


class EndpointOut(BaseModel):
    topic: str
    type: str
    depth: int = Field(description="QoS depth (keep-last)")


class TimerOut(BaseModel):
    period_s: float
    calls: int
    lateness_p50_ms: float | None = Field(description="median delay of a call past its deadline (ms)")
    lateness_p99_ms: float | None


class NodeDetailOut(NodeSummaryOut):
    crash_reason: str | None
    publishers: list[EndpointOut]
    subscribers: list[EndpointOut]
    timers: list[TimerOut]
    parameters: dict[str, Any]
    origin: dict[str, str] = Field(description="package, executable and launch file, when launched")


class RateOut(BaseModel):
    topic: str
    window: int = Field(description="how many periods between messages the statistics use")
    rate_hz: float | None = Field(description="1 / mean period; null with fewer than 2 messages")
    min_s: float | None
    max_s: float | None
    std_dev_s: float | None
    count: int = Field(description="messages published on the topic so far")
    watch: WatchState | None = WATCH


class TypeDefault(RootModel[dict[str, Any]]):
    """A message with every field at its default, in its JSON form (``ros2 interface proto``)."""


class TypeSchema(RootModel[dict[str, Any]]):
    """A JSON Schema (draft 2020-12) of a message type's JSON form, with ROS integer ranges and
    defaults."""


class KeyManagerParams(TypedDict):
    """The drone keyboard manager's parameters the page's setpoint prediction reads from its node
    (``GET /api/nodes/{name}``'s ``parameters``); server/packages/simple_control/keyboard_manager.py
    declares them, with their ranges."""

    mode: str  # "lab", "adopt" (a step per press) or "hold" (move while held)
    step_m: float
    hold_speed_m_s: float
    lead_s: float
    brake_s: float
