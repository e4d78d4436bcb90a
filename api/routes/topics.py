"""REST: topics (like ``ros2 topic list/info/echo --once``) and one-shot publishing."""

from __future__ import annotations

from fastapi import APIRouter

from api.deps import LabDep
from api.protocol.responses import NOT_FOUND, TOO_MANY, TYPE_CONFLICT, responses
from api.protocol.schemas import EndpointDetail, PublishRequest, PublishResult, TopicDetail, TopicSummary
from node_runtime.bus import UnknownTopicError, validate_topic_name
from node_runtime.msgs import UnknownTypeError, get_type
from server.host.introspection.merged import LOCAL, EndpointView, TopicView, topic_views
from server.services.api_node.topic_watch import NODE_NAME as WATCH_NODE
from server.services.api_node.topic_watch import WatchState
from server.world.lab import Lab

# Handlers are ``async def`` on purpose: the bus belongs to the event loop, and a plain ``def``
# handler would run in a worker thread and race the executor (timer heap, wake-up future).
# Errors are mapped in api/errors.py; handlers do not catch.
router = APIRouter(prefix="/api", tags=["topics"], responses=responses())


def summary(view: TopicView) -> TopicSummary:
    return TopicSummary(
        name=view.name,
        type=view.type,
        publishers=[p.node for p in view.publishers],
        subscribers=[s.node for s in _subscribers(view)],
        type_conflict=view.type_conflict,
    )


def _views(lab: Lab) -> list[TopicView]:
    """The graph's topics, but one that only the app's watch holds (its other endpoints are gone)."""
    return [v for v in topic_views(lab.bus, lab.remote_graph()) if v.publishers or _subscribers(v)]


def _subscribers(view: TopicView) -> list[EndpointView]:
    """The topic's subscriptions but the app's own watch: asking about a topic does not change what
    ``topic info`` counts."""
    return [s for s in view.subscribers if not (s.location == LOCAL and s.node == "/" + WATCH_NODE)]


@router.get("/topics")
async def list_topics(lab: LabDep, hidden: bool = False) -> list[TopicSummary]:
    """Every topic in the graph, this process's and other processes', with its type, publishers and
    subscribers (``hidden=true`` adds /rosout and the like)."""
    return [summary(v) for v in _views(lab) if hidden or not v.hidden]


@router.get("/topics/{name:path}", responses=responses(NOT_FOUND, 422))
async def topic_info(name: str, lab: LabDep) -> TopicDetail:
    """One topic (its name without the leading slash), with its latest message and every endpoint
    with where it runs. For a topic only other processes use, the first request starts listening,
    as ``ros2 topic echo`` does (``watch`` says so; ``latest`` is null until a message comes)."""
    full = "/" + validate_topic_name(name).lstrip("/")
    views = [v for v in _views(lab) if v.name == full]
    if not views:
        raise UnknownTopicError(full)
    view = next((v for v in views if v.local), views[0])
    watch = _watch(lab, full, view.type) if len(views) == 1 else None
    topic = lab.bus.topics.get(full)
    endpoints = [
        EndpointDetail(node=e.node, kind=kind, depth=e.depth, location=e.location)
        for kind, side in (("publisher", view.publishers), ("subscriber", _subscribers(view)))
        for e in side
    ]
    return TopicDetail(
        **summary(view).model_dump(),
        endpoints=endpoints,
        latest=topic.latest.to_dict() if topic is not None and topic.latest is not None else None,
        latest_time=topic.latest_time_s if topic is not None else None,
        publish_count=topic.publish_count if topic is not None else 0,
        watch=watch,
        publisher_depths=[p.depth for p in view.publishers],
        subscriber_depths=[s.depth for s in _subscribers(view)],
    )


def _watch(lab: Lab, name: str, type_name: str) -> WatchState | None:
    """Listen on ``name`` if the app needs to, and can: a type it knows, and room for one more watch
    (over the limit the answer is the graph alone, as it was before anyone asked)."""
    watch = lab.topic_watch
    if not watch.needed(name) or not watch.has_room(name):
        return None
    try:
        msg_type = get_type(type_name)
    except UnknownTypeError:
        return None  # a student's own type: nothing here can decode it
    return watch.watch(name, msg_type)


@router.post("/publish", responses=responses(NOT_FOUND, TYPE_CONFLICT, TOO_MANY, body=True))
async def publish(body: PublishRequest, lab: LabDep) -> PublishResult:
    """Publish one message, as ``ros2 topic pub --once``; give ``type`` to create a new topic."""
    name, type_name, count = lab.publish(body.topic, body.msg, body.type)
    return PublishResult(topic=name, type=type_name, subscribers=count)
