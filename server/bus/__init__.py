"""A publish/subscribe bus with ROS 2 semantics, in-process: nodes, topics, timers, an executor."""

from .clock import Clock, ManualClock, RosTime, SystemClock
from .endpoints import Publisher, Subscription, Timer
from .errors import (
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
from .executor import Executor
from .executor_group import ExecutorGroup
from .graph import Bus, NodeOverrides, current_bus
from .names import is_hidden, resolve_topic_name, validate_namespace, validate_node_name, validate_topic_name
from .node import Node
from .parameters import Parameter
from .services import Future, ServiceChannel, ServiceClient, ServiceServer
from .topic import INTERNAL_TOPICS, Topic

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
