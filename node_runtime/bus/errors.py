"""The bus's exceptions, one type per kind of mistake (the API maps each to a status code)."""

from __future__ import annotations


class BusError(Exception):
    """Base of every error the bus raises on purpose."""


class InvalidNameError(BusError, ValueError):
    """A topic, node or namespace name breaks the ROS 2 naming rules."""

    def __init__(self, kind: str, name: str, problem: str) -> None:
        self.kind = kind
        self.name = name
        self.problem = problem
        super().__init__(f"invalid {kind} name {name!r}: {problem}")


class TopicTypeError(BusError, TypeError):
    """A message or an endpoint's type conflicts with the topic's type."""


class UnknownTopicError(BusError, LookupError):
    def __init__(self, name: str) -> None:
        self.name = name
        super().__init__(f"unknown topic {name!r}")


class UnknownServiceError(BusError, LookupError):
    def __init__(self, name: str) -> None:
        self.name = name
        super().__init__(f"unknown service {name!r}")


class ServiceTimeoutError(BusError, TimeoutError):
    """A service call that got no answer in time (the server is gone, busy, or crashed)."""

    def __init__(self, name: str, timeout_s: float) -> None:
        self.name = name
        super().__init__(f"no answer from {name} within {timeout_s:g} s")


class UnknownNodeError(BusError, LookupError):
    def __init__(self, name: str) -> None:
        self.name = name
        super().__init__(f"unknown node {name!r}")


class InvalidQoSError(BusError, ValueError):
    """A queue depth out of range."""


class DestroyedError(BusError, RuntimeError):
    """A publisher, subscription or node was used after it was destroyed."""


class NoBusError(BusError, RuntimeError):
    """A node was created with no bus to join."""
