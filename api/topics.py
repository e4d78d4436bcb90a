"""REST: topics (like ``ros2 topic list/info/echo --once``) and one-shot publishing."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter

from server.bus import UnknownTopicError, validate_topic_name
from server.introspection.merged import TopicView, topic_views

from .deps import LabDep
from .responses import NOT_FOUND, TOO_MANY, TYPE_CONFLICT, responses
from .schemas import PublishRequest, PublishResult, TopicDetail, TopicSummary

# Handlers are ``async def`` on purpose: the bus belongs to the event loop, and a plain ``def``
# handler would run in a worker thread and race the executor (timer heap, wake-up future).
# Errors are mapped in api/errors.py; handlers do not catch.
router = APIRouter(prefix="/api", tags=["topics"], responses=responses())


def summary(view: TopicView) -> dict[str, Any]:
    return {
        "name": view.name,
        "type": view.type,
        "publishers": [p.node for p in view.publishers],
        "subscribers": [s.node for s in view.subscribers],
        "type_conflict": view.type_conflict,
    }


@router.get("/topics", response_model=list[TopicSummary])
async def list_topics(lab: LabDep, hidden: bool = False) -> list[dict[str, Any]]:
    """Every topic in the graph, this process's and other processes', with its type, publishers and
    subscribers (``hidden=true`` adds /rosout and the like)."""
    return [summary(v) for v in topic_views(lab.bus, lab.remote_graph()) if hidden or not v.hidden]


@router.get("/topics/{name:path}", response_model=TopicDetail, responses=responses(NOT_FOUND, 422))
async def topic_info(name: str, lab: LabDep) -> dict[str, Any]:
    """One topic (its name without the leading slash), with its latest message (when this process
    has seen one) and every endpoint with where it runs."""
    full = "/" + validate_topic_name(name).lstrip("/")
    views = [v for v in topic_views(lab.bus, lab.remote_graph()) if v.name == full]
    if not views:
        raise UnknownTopicError(full)
    view = next((v for v in views if v.local), views[0])
    topic = lab.bus.topics.get(full)
    endpoints = [
        {"node": e.node, "kind": kind, "depth": e.depth, "location": e.location}
        for kind, side in (("publisher", view.publishers), ("subscriber", view.subscribers))
        for e in side
    ]
    return {
        **summary(view),
        "endpoints": endpoints,
        "latest": topic.latest.to_dict() if topic is not None and topic.latest is not None else None,
        "latest_time": topic.latest_time_s if topic is not None else None,
        "publish_count": topic.publish_count if topic is not None else 0,
        "publisher_depths": [p.depth for p in view.publishers],
        "subscriber_depths": [s.depth for s in view.subscribers],
    }


@router.post(
    "/publish",
    response_model=PublishResult,
    responses=responses(NOT_FOUND, TYPE_CONFLICT, TOO_MANY, body=True),
)
async def publish(body: PublishRequest, lab: LabDep) -> dict[str, Any]:
    """Publish one message, as ``ros2 topic pub --once``; give ``type`` to create a new topic."""
    name, type_name, count = lab.publish(body.topic, body.msg, body.type)
    return {"topic": name, "type": type_name, "subscribers": count}
