"""``ros2 node info``: a node's endpoints, timers (with lateness), parameters, state and origin."""

from __future__ import annotations

from typing import Any

from node_runtime.bus import Node, Timer
from server.host.introspection.rates import percentile


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
