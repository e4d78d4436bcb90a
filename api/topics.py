"""REST: topics (like ``ros2 topic list/info/echo --once``) and one-shot publishing."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter

from server.bus import Topic, validate_topic_name

from .deps import LabDep
from .responses import NOT_FOUND, TOO_MANY, TYPE_CONFLICT, responses
from .schemas import PublishRequest, PublishResult, TopicDetail, TopicSummary

# Handlers are ``async def`` on purpose: the bus belongs to the event loop, and a plain ``def``
# handler would run in a worker thread and race the executor (timer heap, wake-up future).
# Errors are mapped in api/errors.py; handlers do not catch.
router = APIRouter(prefix="/api", tags=["topics"], responses=responses())


def summary(topic: Topic) -> dict[str, Any]:
    return {
        "name": topic.name,
        "type": topic.msg_type.TYPE,
        "publishers": [p.node.fully_qualified_name for p in topic.publishers],
        "subscribers": [s.node.fully_qualified_name for s in topic.subscriptions],
    }


@router.get("/topics", response_model=list[TopicSummary])
async def list_topics(lab: LabDep, hidden: bool = False) -> list[dict[str, Any]]:
    """Every topic with its type, publishers and subscribers (``hidden=true`` adds /rosout and the like)."""
    topics = sorted(lab.bus.topics.values(), key=lambda t: t.name)
    return [summary(t) for t in topics if hidden or not t.hidden]


@router.get("/topics/{name:path}", response_model=TopicDetail, responses=responses(NOT_FOUND, 422))
async def topic_info(name: str, lab: LabDep) -> dict[str, Any]:
    """One topic (its name without the leading slash), with its latest message."""
    topic = lab.bus.get_topic("/" + validate_topic_name(name).lstrip("/"))
    return {
        **summary(topic),
        "latest": topic.latest.to_dict() if topic.latest is not None else None,
        "latest_time": topic.latest_time_s,
        "publish_count": topic.publish_count,
        "publisher_depths": [p.depth for p in topic.publishers],
        "subscriber_depths": [s.depth for s in topic.subscriptions],
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
