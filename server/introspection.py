"""What the ROS tools show about a bus, as plain data: ``ros2 topic hz``, ``ros2 node info``,
rqt_graph's graph, and message types as JSON Schema. Pure functions; the web layer only serialises.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from itertools import islice, pairwise
from typing import Any, Literal

from server.bus import Bus, Node, Timer, is_hidden
from server.msgs import schema

EdgeKind = Literal["publish", "subscribe"]


# -- ros2 topic hz ---------------------------------------------------------------------------
@dataclass(frozen=True)
class RateStats:
    """Statistics of the periods between consecutive messages, as ``ros2 topic hz`` prints them.

    ``window`` is how many periods were used; with none, every other field is None. ``rate_hz``
    is 1 / mean period (None when the mean is 0: every message at one instant). ``std_dev_s`` is
    the population standard deviation, as ros2 computes it.
    """

    window: int
    rate_hz: float | None = None
    min_s: float | None = None
    max_s: float | None = None
    std_dev_s: float | None = None


def rate_stats(times_s: Sequence[float], window: int) -> RateStats:
    """Rate over the last ``window`` periods, i.e. between the last ``window + 1`` of ``times_s``."""
    if window < 1:
        raise ValueError(f"window must be at least 1 period, got {window}")
    start = max(0, len(times_s) - (window + 1))
    recent = list(islice(times_s, start, None))
    periods = [b - a for a, b in pairwise(recent)]
    if not periods:
        return RateStats(window=0)
    mean = sum(periods) / len(periods)
    std = math.sqrt(sum((p - mean) ** 2 for p in periods) / len(periods))
    return RateStats(
        window=len(periods), rate_hz=1.0 / mean if mean > 0 else None,
        min_s=min(periods), max_s=max(periods), std_dev_s=std,
    )  # fmt: skip


def percentile(values: Iterable[float], q: float) -> float | None:
    """The ``q``-th percentile (0..100), linearly interpolated as numpy's default; None if empty."""
    data = sorted(values)
    if not data:
        return None
    pos = (len(data) - 1) * q / 100.0
    lo = math.floor(pos)
    hi = min(lo + 1, len(data) - 1)
    return data[lo] + (data[hi] - data[lo]) * (pos - lo)


# -- rqt_graph -------------------------------------------------------------------------------
@dataclass(frozen=True)
class GraphNode:
    name: str
    state: str
    hidden: bool


@dataclass(frozen=True)
class GraphTopic:
    name: str
    type: str
    hidden: bool


@dataclass(frozen=True)
class GraphEdge:
    """``publish``: node → topic; ``subscribe``: topic → node (the way the data flows)."""

    source: str
    target: str
    kind: EdgeKind


@dataclass(frozen=True)
class GraphSnapshot:
    version: int
    nodes: list[GraphNode]
    topics: list[GraphTopic]
    edges: list[GraphEdge]


def graph_snapshot(bus: Bus, include_hidden: bool = False) -> GraphSnapshot:
    """The computation graph, sorted by name; hidden nodes, internal topics and their edges
    are left out unless ``include_hidden``. A node with two endpoints on one topic gives one edge."""
    nodes = [GraphNode(n.fully_qualified_name, n.state, is_hidden(n.fully_qualified_name)) for n in bus.nodes]
    nodes = sorted((n for n in nodes if include_hidden or not n.hidden), key=lambda n: n.name)
    shown = {n.name for n in nodes}
    topics: list[GraphTopic] = []
    edges: dict[GraphEdge, None] = {}  # an ordered set
    for topic in sorted(bus.topics.values(), key=lambda t: t.name):
        if topic.hidden and not include_hidden:
            continue
        topics.append(GraphTopic(topic.name, topic.msg_type.TYPE, topic.hidden))
        for pub in topic.publishers:
            if pub.node.fully_qualified_name in shown:
                edges[GraphEdge(pub.node.fully_qualified_name, topic.name, "publish")] = None
        for sub in topic.subscriptions:
            if sub.node.fully_qualified_name in shown:
                edges[GraphEdge(topic.name, sub.node.fully_qualified_name, "subscribe")] = None
    return GraphSnapshot(bus.graph_version, nodes, topics, list(edges))


# -- ros2 node info --------------------------------------------------------------------------
def timer_info(timer: Timer) -> dict[str, Any]:
    """Period, calls so far and lateness percentiles (ms after the deadline the callback ran)."""
    p50 = percentile(timer.lateness_s, 50)
    p99 = percentile(timer.lateness_s, 99)
    return {
        "period_s": timer.period_s,
        "calls": timer.call_count,
        "lateness_p50_ms": None if p50 is None else p50 * 1000.0,
        "lateness_p99_ms": None if p99 is None else p99 * 1000.0,
    }


def node_info(node: Node) -> dict[str, Any]:
    """What ``ros2 node info`` shows, plus state, timers, parameters and where the node came from."""
    return {
        "name": node.fully_qualified_name,
        "namespace": node.get_namespace(),
        "state": node.state,
        "crash_reason": node.crash_reason,
        "publishers": [
            {"topic": p.topic_name, "type": p.msg_type.TYPE, "depth": p.depth} for p in node.publishers
        ],
        "subscribers": [
            {"topic": s.topic_name, "type": s.msg_type.TYPE, "depth": s.depth} for s in node.subscriptions
        ],
        "timers": [timer_info(t) for t in node.timers],
        "parameters": node.get_parameters_dict(),
        "origin": dict(node.origin),
    }


# -- message types as JSON Schema ------------------------------------------------------------
type_schema = schema.type_schema
