"""Look message, service and action types up by their ROS name; ``std_msgs/Bool`` and
``std_msgs/msg/Bool`` both work.

The names are the lab's own types and those added at run time (node_runtime.msgs.catalog); a name not
known yet asks the catalog to refresh (a package a student just wrote) before it is refused.
"""

from __future__ import annotations

from node_runtime.msgs import catalog
from node_runtime.msgs._action import Action, action_class, action_classes
from node_runtime.msgs._base import Message, Service, message_class, service_class


class UnknownTypeError(LookupError):
    """No message (or service, or action) type of that name."""

    def __init__(self, name: str, kind: str = "message") -> None:
        self.name = name
        known = {"message": _message_names, "service": _service_names, "action": _action_names}[kind]()
        super().__init__(f"unknown {kind} type {name!r} (known: {', '.join(known)})")


def normalize_type_name(name: str, kind: str = "msg") -> str:
    """``pkg/Name`` → ``pkg/msg/Name`` (or ``pkg/srv/Name``, ``pkg/action/Name``), as ros2 accepts both."""
    parts = name.strip().split("/")
    if len(parts) == 2 and all(parts):
        return f"{parts[0]}/{kind}/{parts[1]}"
    return name.strip()


def _message(name: str) -> type[Message] | None:
    if name not in catalog.definitions().messages:
        return None
    try:
        return message_class(name)
    except KeyError:
        return None


def _service(name: str) -> type[Service] | None:
    if name not in catalog.definitions().services:
        return None
    try:
        return service_class(name)
    except KeyError:
        return None


def _action(name: str) -> type[Action] | None:
    try:
        return action_class(name)  # the catalog's, and any made straight from a text
    except KeyError:
        return None


def _message_names() -> list[str]:
    """The message types (an action's own messages are found by name, not listed)."""
    return sorted(n for n in catalog.definitions().messages if "/msg/" in n)


def _service_names() -> list[str]:
    return sorted(n for n in catalog.definitions().services if "/srv/" in n)


def _action_names() -> list[str]:
    return sorted(action_classes())


def get_type(name: str) -> type[Message]:
    full = normalize_type_name(name)
    found = _message(full)
    if found is None:
        catalog.refresh()
        found = _message(full)
    if found is None:
        raise UnknownTypeError(name)
    return found


def type_names() -> list[str]:
    """Every message type known now (refreshed first)."""
    catalog.refresh()
    return _message_names()


def get_service_type(name: str) -> type[Service]:
    full = normalize_type_name(name, "srv")
    found = _service(full)
    if found is None:
        catalog.refresh()
        found = _service(full)
    if found is None:
        raise UnknownTypeError(name, "service")
    return found


def service_names() -> list[str]:
    """Every service type known now (refreshed first)."""
    catalog.refresh()
    return _service_names()


def get_action_type(name: str) -> type[Action]:
    """``pkg/action/Name`` (or ``pkg/Name``) → its action class."""
    full = normalize_type_name(name, "action")
    found = _action(full)
    if found is None:
        catalog.refresh()
        found = _action(full)
    if found is None:
        raise UnknownTypeError(name, "action")
    return found


def action_names() -> list[str]:
    """Every action type known now (refreshed first)."""
    catalog.refresh()
    return _action_names()
