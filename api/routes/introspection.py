"""REST: the ROS tools' view of the graph: ``rqt_graph``, ``ros2 node list/info``, ``ros2 topic hz``,
``ros2 interface list/show`` (as JSON Schema) and ``ros2 interface proto`` (the default message)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fastapi import APIRouter, HTTPException, Query, status

from api.deps import LabDep
from api.protocol.introspection import (
    GraphEdgeOut,
    GraphNodeOut,
    GraphOut,
    GraphTopicOut,
    NodeDetailOut,
    NodeSummaryOut,
    RateOut,
    TypeDefault,
    TypeSchema,
)
from api.protocol.responses import NOT_FOUND, responses
from node_runtime.bus import Node, UnknownNodeError, is_hidden, validate_topic_name
from node_runtime.bus.topic import HZ_WINDOW_MAX
from node_runtime.msgs import Message, UnknownTypeError, get_type, type_names
from server.host.introspection import graph_snapshot, node_info, rate_stats, type_schema
from server.host.introspection.merged import remote_node_endpoints
from server.world.lab import Lab

# Handlers are ``async def`` so that they read the bus on the event loop that owns it, never
# from a worker thread while the executor changes it.
# Errors are mapped in api/errors.py; handlers do not catch.
router = APIRouter(prefix="/api", tags=["introspection"], responses=responses())
HZ_WINDOW_DEFAULT = 100


@router.get("/graph")
async def graph(lab: LabDep, hidden: bool = False) -> GraphOut:
    """The computation graph, as rqt_graph draws it; ``hidden=true`` adds debug nodes and /rosout."""
    snap = graph_snapshot(lab.bus, include_hidden=hidden, remote=lab.remote_graph())
    shown = {n.name for n in snap.nodes}
    died = [
        GraphNodeOut(name=n.name, state="died", hidden=is_hidden(n.name), location=n.location)
        for n in died_nodes(lab)
        if n.name not in shown and (hidden or not is_hidden(n.name))
    ]
    return GraphOut(
        version=snap.version + len(died),
        nodes=[GraphNodeOut.model_validate(vars(n)) for n in snap.nodes] + died,
        topics=[GraphTopicOut.model_validate(vars(t)) for t in snap.topics],
        edges=[
            GraphEdgeOut.model_validate({"from": e.source, "to": e.target, "kind": e.kind})
            for e in snap.edges
        ],
    )


@router.get("/nodes")
async def list_nodes(lab: LabDep, hidden: bool = False) -> list[NodeSummaryOut]:
    """Every node, as ``ros2 node list`` (``hidden=true`` adds the '_' ones, as ``--all``)."""
    nodes = [n for n in lab.bus.nodes if hidden or not is_hidden(n.fully_qualified_name)]
    local = [NodeSummaryOut.model_validate(_summary(lab, n)) for n in nodes]
    remote = lab.remote_graph()
    others = [
        NodeSummaryOut(name=n.name, namespace=n.namespace, state="active", location=n.location, respawn=None)
        for n in (remote.nodes() if remote is not None else [])
        if hidden or not is_hidden(n.name)
    ]
    died: list[NodeSummaryOut] = [n for n in died_nodes(lab) if hidden or not is_hidden(n.name)]
    return sorted(local + others + died, key=lambda n: (n.name, n.location))


def _summary(lab: Lab, node: Node) -> dict[str, Any]:
    respawn = lab.launcher.respawn_of(node)
    return {
        "name": node.fully_qualified_name,
        "namespace": node.get_namespace(),
        "state": node.state,
        "location": "app",
        "respawn": None if respawn is None else respawn.describe(),
    }


@router.get("/nodes/{name:path}", responses=responses(NOT_FOUND, 422))
async def get_node(name: str, lab: LabDep) -> NodeDetailOut:
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
        return NodeDetailOut.model_validate({
            "name": fq, "namespace": found.namespace, "state": "active", "location": found.location,
            "respawn": None, "crash_reason": None, "publishers": endpoints["publishers"],
            "subscribers": endpoints["subscribers"], "timers": [], "parameters": {}, "origin": {},
        })  # fmt: skip
    return NodeDetailOut.model_validate({**node_info(node), **_summary(lab, node)})


@router.get("/hz/{name:path}", responses=responses(NOT_FOUND, 422))
async def topic_hz(
    name: str,
    lab: LabDep,
    window: int = Query(HZ_WINDOW_DEFAULT, ge=2, le=HZ_WINDOW_MAX, description="periods"),
) -> RateOut:
    """A topic's publishing rate over its last ``window`` periods, as ``ros2 topic hz``. For a topic
    only other processes use, the first request starts listening (``watch`` says so; ``window`` is 0
    until messages come)."""
    full = "/" + validate_topic_name(name).lstrip("/")
    watch = None
    if lab.topic_watch.needed(full):
        watch = lab.topic_watch.watch(full, lab.topic_type(full, None))
    topic = lab.bus.get_topic(full)
    stats = rate_stats(topic.publish_times_s, window)
    return RateOut(topic=topic.name, **vars(stats), count=topic.publish_count, watch=watch)


def _type(name: str) -> type[Message]:
    try:
        return get_type(name)
    except UnknownTypeError as exc:
        raise HTTPException(status.HTTP_404_NOT_FOUND, str(exc)) from exc


@router.get("/types")
async def list_types() -> list[str]:
    """Every message type the lab knows, as ``ros2 interface list -m``."""
    return type_names()


# Declared before /types/{type} so that the path parameter does not swallow "/default".
@router.get("/types/{type_name:path}/default", responses=responses(NOT_FOUND))
async def type_default(type_name: str) -> TypeDefault:
    """The message with every field at its default, as ``ros2 interface proto``."""
    return TypeDefault(_type(type_name)().to_dict())


@router.get("/types/{type_name:path}", responses=responses(NOT_FOUND))
async def type_info(type_name: str) -> TypeSchema:
    """A JSON Schema (draft 2020-12) of the type's JSON form, with ROS integer ranges and defaults."""
    return TypeSchema(type_schema(_type(type_name)))


def died_nodes(lab: Lab) -> list[NodeSummaryOut]:
    """Node processes that ended and that their launch respawns, while they wait for their next try.

    A process that ended for good is no node any more: it leaves the lists at once (its run's
    output said so with its exit code, and its launch, GET /api/launches, keeps it). Listing it
    as "died" made a crash outlive the fixed run that followed it, so Stop looked as if it failed.
    """
    out: list[NodeSummaryOut] = []
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
            out.append(NodeSummaryOut.model_validate({
                "name": name, "namespace": name.rsplit("/", 1)[0] or "/", "state": "died",
                "location": f"process {process.pid}", "exit_code": process.exit_code,
                "respawn": None if entry.respawn is None else entry.respawn.describe(),
            }))  # fmt: skip
    return out
