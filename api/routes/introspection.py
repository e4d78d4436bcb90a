"""REST: the ROS tools' view of the graph: ``rqt_graph``, ``ros2 node list/info``, ``ros2 topic hz``,
``ros2 interface list/show`` (as JSON Schema) and ``ros2 interface proto`` (the default message)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Literal

from fastapi import APIRouter, HTTPException, Query, status
from pydantic import BaseModel, ConfigDict, Field

from api.deps import LabDep
from api.protocol.responses import NOT_FOUND, responses
from api.protocol.schemas import WATCH
from node_runtime.bus import Node, UnknownNodeError, is_hidden, validate_topic_name
from node_runtime.bus.topic import HZ_WINDOW_MAX
from node_runtime.msgs import Message, UnknownTypeError, get_type, type_names
from server.host.introspection import graph_snapshot, node_info, rate_stats, type_schema
from server.host.introspection.merged import remote_node_endpoints
from server.services.api_node.topic_watch import WatchState
from server.world.lab import Lab

# Handlers are ``async def`` so that they read the bus on the event loop that owns it, never
# from a worker thread while the executor changes it.
# Errors are mapped in api/errors.py; handlers do not catch.
router = APIRouter(prefix="/api", tags=["introspection"], responses=responses())
HZ_WINDOW_DEFAULT = 100


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


@router.get("/graph", response_model=GraphOut)
async def graph(lab: LabDep, hidden: bool = False) -> dict[str, Any]:
    """The computation graph, as rqt_graph draws it; ``hidden=true`` adds debug nodes and /rosout."""
    snap = graph_snapshot(lab.bus, include_hidden=hidden, remote=lab.remote_graph())
    shown = {n.name for n in snap.nodes}
    died = [
        {"name": n["name"], "state": "died", "hidden": is_hidden(n["name"]), "location": n["location"]}
        for n in died_nodes(lab)
        if n["name"] not in shown and (hidden or not is_hidden(n["name"]))
    ]
    return {
        "version": snap.version + len(died),
        "nodes": [vars(n) for n in snap.nodes] + died,
        "topics": [vars(t) for t in snap.topics],
        "edges": [{"from": e.source, "to": e.target, "kind": e.kind} for e in snap.edges],
    }


@router.get("/nodes", response_model=list[NodeSummaryOut])
async def list_nodes(lab: LabDep, hidden: bool = False) -> list[dict[str, Any]]:
    """Every node, as ``ros2 node list`` (``hidden=true`` adds the '_' ones, as ``--all``)."""
    nodes = [n for n in lab.bus.nodes if hidden or not is_hidden(n.fully_qualified_name)]
    local = [_summary(lab, n) for n in nodes]
    remote = lab.remote_graph()
    others = [
        {"name": n.name, "namespace": n.namespace, "state": "active", "location": n.location, "respawn": None}
        for n in (remote.nodes() if remote is not None else [])
        if hidden or not is_hidden(n.name)
    ]
    died = [n for n in died_nodes(lab) if hidden or not is_hidden(n["name"])]
    return sorted(local + others + died, key=lambda n: (n["name"], n["location"]))


def _summary(lab: Lab, node: Node) -> dict[str, Any]:
    respawn = lab.launcher.respawn_of(node)
    return {
        "name": node.fully_qualified_name,
        "namespace": node.get_namespace(),
        "state": node.state,
        "location": "app",
        "respawn": None if respawn is None else respawn.describe(),
    }


@router.get("/nodes/{name:path}", response_model=NodeDetailOut, responses=responses(NOT_FOUND, 422))
async def get_node(name: str, lab: LabDep) -> dict[str, Any]:
    """One node (its name without the leading slash), as ``ros2 node info``; a node of another
    process shows what its tokens tell (endpoints; no timers or parameters)."""
    try:
        node = lab.bus.get_node(name)
    except UnknownNodeError:
        remote = lab.remote_graph()
        fq = "/" + name.lstrip("/")
        found = next((n for n in remote.nodes() if n.name == fq), None) if remote is not None else None
        if remote is None or found is None:
            raise
        endpoints = remote_node_endpoints(remote, fq)
        return {
            "name": fq, "namespace": found.namespace, "state": "active", "location": found.location,
            "respawn": None, "crash_reason": None, "publishers": endpoints["publishers"],
            "subscribers": endpoints["subscribers"], "timers": [], "parameters": {}, "origin": {},
        }  # fmt: skip
    return {**node_info(node), **_summary(lab, node)}


@router.get("/hz/{name:path}", response_model=RateOut, responses=responses(NOT_FOUND, 422))
async def topic_hz(
    name: str,
    lab: LabDep,
    window: int = Query(HZ_WINDOW_DEFAULT, ge=2, le=HZ_WINDOW_MAX, description="periods"),
) -> dict[str, Any]:
    """A topic's publishing rate over its last ``window`` periods, as ``ros2 topic hz``. For a topic
    only other processes use, the first request starts listening (``watch`` says so; ``window`` is 0
    until messages come)."""
    full = "/" + validate_topic_name(name).lstrip("/")
    watch = None
    if lab.topic_watch.needed(full):
        watch = lab.topic_watch.watch(full, lab.topic_type(full, None))
    topic = lab.bus.get_topic(full)
    stats = rate_stats(topic.publish_times_s, window)
    return {"topic": topic.name, **vars(stats), "count": topic.publish_count, "watch": watch}


def _type(name: str) -> type[Message]:
    try:
        return get_type(name)
    except UnknownTypeError as exc:
        raise HTTPException(status.HTTP_404_NOT_FOUND, str(exc)) from exc


@router.get("/types", response_model=list[str])
async def list_types() -> list[str]:
    """Every message type the lab knows, as ``ros2 interface list -m``."""
    return type_names()


# Declared before /types/{type} so that the path parameter does not swallow "/default".
@router.get("/types/{type_name:path}/default", responses=responses(NOT_FOUND))
async def type_default(type_name: str) -> dict[str, Any]:
    """The message with every field at its default, as ``ros2 interface proto``."""
    return _type(type_name)().to_dict()


@router.get("/types/{type_name:path}", responses=responses(NOT_FOUND))
async def type_info(type_name: str) -> dict[str, Any]:
    """A JSON Schema (draft 2020-12) of the type's JSON form, with ROS integer ranges and defaults."""
    return type_schema(_type(type_name))


def died_nodes(lab: Lab) -> list[dict[str, Any]]:
    """Node processes that ended and that their launch respawns, while they wait for their next try.

    A process that ended for good is no node any more: it leaves the lists at once (its run's
    output said so with its exit code, and its launch, GET /api/launches, keeps it). Listing it
    as "died" made a crash outlive the fixed run that followed it, so Stop looked as if it failed.
    """
    out = []
    remote = lab.remote_graph()
    for entry in lab.launcher.launched:
        process = entry.process
        if process is None or process.state != "died":
            continue
        if entry.respawn is None or entry.respawn.state != "waiting":
            continue
        action = entry.action
        namespace = action.namespace or "/"
        names = remote.names_seen(process.command.zid) if remote is not None else []
        fallback = namespace.rstrip("/") + "/" + (action.name or Path(action.exec).stem).split("/")[-1]
        for name in names or [fallback]:
            out.append({
                "name": name, "namespace": name.rsplit("/", 1)[0] or "/", "state": "died",
                "location": f"process {process.pid}", "exit_code": process.exit_code,
                "respawn": None if entry.respawn is None else entry.respawn.describe(),
            })  # fmt: skip
    return out
