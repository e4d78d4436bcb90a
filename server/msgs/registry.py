"""Look message and service types up by their ROS name; ``std_msgs/Bool`` and ``std_msgs/msg/Bool`` both work."""

from __future__ import annotations

from . import generated as _generated  # noqa: F401  (declares every class)
from ._base import Message, Service, message_classes
from .generated import example_interfaces, std_srvs
from .idl import lab_definitions

_SERVICES: dict[str, type[Service]] = {
    s.TYPE: s
    for module in (std_srvs, example_interfaces)
    for s in vars(module).values()
    if isinstance(s, type) and issubclass(s, Service) and s is not Service
}


class UnknownTypeError(LookupError):
    """No message (or service) type of that name."""

    def __init__(self, name: str, kind: str = "message") -> None:
        self.name = name
        known = type_names() if kind == "message" else service_names()
        super().__init__(f"unknown {kind} type {name!r} (known: {', '.join(known)})")


def normalize_type_name(name: str, kind: str = "msg") -> str:
    """``pkg/Name`` → ``pkg/msg/Name`` (or ``pkg/srv/Name``), as ros2 accepts both spellings."""
    parts = name.strip().split("/")
    if len(parts) == 2 and all(parts):
        return f"{parts[0]}/{kind}/{parts[1]}"
    return name.strip()


def _messages() -> dict[str, type[Message]]:
    classes = message_classes()
    return {n: classes[n] for n in lab_definitions().messages}


def get_type(name: str) -> type[Message]:
    try:
        return _messages()[normalize_type_name(name)]
    except KeyError:
        raise UnknownTypeError(name) from None


def type_names() -> list[str]:
    return sorted(_messages())


def get_service_type(name: str) -> type[Service]:
    try:
        return _SERVICES[normalize_type_name(name, "srv")]
    except KeyError:
        raise UnknownTypeError(name, "service") from None


def service_names() -> list[str]:
    return sorted(_SERVICES)
