"""What the ROS tools show about a bus, as plain data: ``ros2 topic hz`` (``rates``), rqt_graph's
graph (``graph``), ``ros2 node info`` (``node_info``) and message types as JSON Schema
(``schemas``). Pure functions; the web layer only serialises.
"""

from server.host.introspection.graph import (
    EdgeKind,
    GraphEdge,
    GraphNode,
    GraphSnapshot,
    GraphTopic,
    graph_snapshot,
)
from server.host.introspection.node_info import node_info, timer_info
from server.host.introspection.rates import RateStats, percentile, rate_stats
from server.host.introspection.schemas import FLOAT32_MAX, JSON_SCHEMA_DIALECT, type_schema

__all__ = [
    "FLOAT32_MAX",
    "JSON_SCHEMA_DIALECT",
    "EdgeKind",
    "GraphEdge",
    "GraphNode",
    "GraphSnapshot",
    "GraphTopic",
    "RateStats",
    "graph_snapshot",
    "node_info",
    "percentile",
    "rate_stats",
    "timer_info",
    "type_schema",
]
