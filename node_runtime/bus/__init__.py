"""A publish/subscribe bus with ROS 2 semantics, in-process: nodes, topics, timers, an executor."""

from node_runtime.bus.clock import Clock, ManualClock, RosTime, SystemClock
from node_runtime.bus.endpoints import Publisher, Subscription, Timer
from node_runtime.bus.errors import (
    BusError,
    DestroyedError,
    InvalidNameError,
    InvalidQoSError,
    NoBusError,
    ServiceTimeoutError,
    TopicTypeError,
    UnknownNodeError,
    UnknownServiceError,
    UnknownTopicError,
)
from node_runtime.bus.executor import Executor
from node_runtime.bus.executor_group import ExecutorGroup
from node_runtime.bus.graph import Bus, NodeOverrides, current_bus
from node_runtime.bus.names import (
    is_hidden,
    resolve_topic_name,
    validate_namespace,
    validate_node_name,
    validate_topic_name,
)
from node_runtime.bus.node import Node
from node_runtime.bus.parameters import Parameter
from node_runtime.bus.services import Future, ServiceChannel, ServiceClient, ServiceServer
from node_runtime.bus.topic import INTERNAL_TOPICS, Topic

__all__ = [
    "INTERNAL_TOPICS",
    "Bus",
    "BusError",
    "Clock",
    "DestroyedError",
    "Executor",
    "ExecutorGroup",
    "Future",
    "InvalidNameError",
    "InvalidQoSError",
    "ManualClock",
    "NoBusError",
    "Node",
    "NodeOverrides",
    "Parameter",
    "Publisher",
    "RosTime",
    "ServiceChannel",
    "ServiceClient",
    "ServiceServer",
    "ServiceTimeoutError",
    "Subscription",
    "SystemClock",
    "Timer",
    "Topic",
    "TopicTypeError",
    "UnknownNodeError",
    "UnknownServiceError",
    "UnknownTopicError",
    "current_bus",
    "is_hidden",
    "resolve_topic_name",
    "validate_namespace",
    "validate_node_name",
    "validate_topic_name",
]
