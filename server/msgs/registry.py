"""Look message and service types up by their ROS name; ``std_msgs/Bool`` and ``std_msgs/msg/Bool`` both work."""

from __future__ import annotations

from . import generated as _generated  # declares every class
from ._action import Action, action_class, action_classes
from ._base import Message, Service, message_classes
from .idl import lab_definitions

# Every service any package declares (std_srvs, example_interfaces, rosapi_msgs ...).
_SERVICES: dict[str, type[Service]] = {
    s.TYPE: s
    for module_name in _generated.__all__
    for s in vars(getattr(_generated, module_name)).values()
    if isinstance(s, type) and issubclass(s, Service) and s is not Service
}


class UnknownTypeError(LookupError):
    """No message (or service) type of that name."""

    def __init__(self, name: str, kind: str = "message") -> None:
        self.name = name
        known = {"message": type_names, "service": service_names, "action": action_names}[kind]()
        super().__init__(f"unknown {kind} type {name!r} (known: {', '.join(known)})")


def normalize_type_name(name: str, kind: str = "msg") -> str:
    """``pkg/Name`` → ``pkg/msg/Name`` (or ``pkg/srv/Name``, ``pkg/action/Name``), as ros2 accepts both."""
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
    """The message types (an action's own messages are found by name, not listed)."""
    return sorted(n for n in _messages() if "/msg/" in n)


def get_service_type(name: str) -> type[Service]:
    try:
        return _SERVICES[normalize_type_name(name, "srv")]
    except KeyError:
        raise UnknownTypeError(name, "service") from None


def service_names() -> list[str]:
    return sorted(n for n in _SERVICES if "/srv/" in n)


def get_action_type(name: str) -> type[Action]:
    """``pkg/action/Name`` (or ``pkg/Name``) → its action class."""
    try:
        return action_class(normalize_type_name(name, "action"))
    except KeyError:
        raise UnknownTypeError(name, "action") from None


def action_names() -> list[str]:
    return sorted(action_classes())
