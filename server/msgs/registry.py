"""Look message types up by their ROS name; ``std_msgs/Bool`` and ``std_msgs/msg/Bool`` both work."""

from __future__ import annotations

from ._base import Message
from .types import ALL_TYPES

_BY_NAME: dict[str, type[Message]] = {t.TYPE: t for t in ALL_TYPES}


class UnknownTypeError(LookupError):
    """No message type of that name."""

    def __init__(self, name: str) -> None:
        self.name = name
        super().__init__(f"unknown message type {name!r} (known: {', '.join(sorted(_BY_NAME))})")


def normalize_type_name(name: str) -> str:
    """``pkg/Name`` → ``pkg/msg/Name``, as ros2 accepts both spellings."""
    parts = name.strip().split("/")
    if len(parts) == 2 and all(parts):
        return f"{parts[0]}/msg/{parts[1]}"
    return name.strip()


def get_type(name: str) -> type[Message]:
    try:
        return _BY_NAME[normalize_type_name(name)]
    except KeyError:
        raise UnknownTypeError(name) from None


def type_names() -> list[str]:
    return sorted(_BY_NAME)
