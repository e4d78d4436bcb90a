"""Every message class's written-out ``__init__`` and ``copy`` (msgs/compiled.py) give what Message's
generic loops over FIELDS give: the same defaults, the same checks, deep copies."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from node_runtime.msgs import Message, PoseStamped, Vector3
from node_runtime.msgs._base import message_classes
from node_runtime.msgs._field import MessageError

CLASSES = sorted(message_classes().items())


def generic_new(cls: type[Message], **kwargs: Any) -> Message:
    msg = object.__new__(cls)
    Message.__init__(msg, **kwargs)
    return msg


@pytest.mark.parametrize(("name", "cls"), CLASSES, ids=[n for n, _ in CLASSES])
def test_compiled_defaults_and_copy_equal_the_generic_ones(name: str, cls: type[Message]) -> None:
    made, generic = cls(), generic_new(cls)
    assert made == generic
    assert made.to_dict() == generic.to_dict()
    copied = made.copy()
    assert type(copied) is cls
    assert copied == Message.copy(made) == made
    for f in cls.FIELDS:
        value = getattr(made, f.name)
        if f.array or not isinstance(f.kind, str):  # mutable values are copied, not shared
            assert getattr(copied, f.name) is not value, f.name


def test_compiled_init_checks_values_as_setattr_does() -> None:
    v = Vector3(x=1, y=np.float32(2.5), z=3.0)
    assert (v.x, v.y, v.z) == (1.0, 2.5, 3.0)
    assert all(type(c) is float for c in (v.x, v.y, v.z))
    with pytest.raises(MessageError, match=r"^x: expected a number"):
        Vector3(x="1")
    with pytest.raises(MessageError, match=r"^pose: expected geometry_msgs/msg/Pose"):
        PoseStamped(pose=Vector3())
    with pytest.raises(TypeError, match=r"has no field\(s\) a, w"):
        Vector3(w=1.0, a=2.0)
    with pytest.raises(TypeError):
        Vector3(1.0)  # type: ignore[misc]


def test_compiled_copy_is_deep() -> None:
    msg = PoseStamped()
    msg.pose.position.x = 1.0
    copied = msg.copy()
    msg.pose.position.x = 2.0
    msg.header.stamp.sec = 5
    assert copied.pose.position.x == 1.0
    assert copied.header.stamp.sec == 0
