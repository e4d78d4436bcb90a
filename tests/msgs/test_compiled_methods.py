"""Every message class's written-out ``__init__``, ``copy`` and ``to_dict`` (msgs/compiled.py) give
what Message's generic loops over FIELDS give: the same defaults, the same checks, deep copies, the
same JSON."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from node_runtime.msgs import Message, PoseStamped, Vector3
from node_runtime.msgs._base import message_class, message_classes
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
    assert made.to_dict() == Message.to_dict(generic)  # a nested message's own is its class's case
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


def test_compiled_init_keeps_ints_and_strings_that_fit_and_refuses_the_rest_as_setattr_does() -> None:
    """Ints in their type's range and strings within their bound are kept as they are, inline; the
    rest go to Field.check, which refuses them or converts them as assigning them would."""
    time_class = message_class("builtin_interfaces/msg/Time")
    t = time_class(sec=-(2**31), nanosec=2**32 - 1)
    assert (t.sec, t.nanosec) == (-(2**31), 2**32 - 1)
    assert type(time_class(sec=np.int64(5)).sec) is int  # numpy's integer, converted as setattr does
    for bad, problem in (
        ({"sec": 2**31}, r"^sec: 2147483648 is out of range for int32"),
        ({"nanosec": -1}, r"^nanosec: -1 is out of range for uint32"),
        ({"sec": True}, r"^sec: expected an integer"),
        ({"sec": 1.0}, r"^sec: expected an integer"),
    ):
        with pytest.raises(MessageError, match=problem):
            time_class(**bad)
        key, value = next(iter(bad.items()))
        with pytest.raises(MessageError, match=problem):
            setattr(time_class(), key, value)

    field_type = message_class("type_description_interfaces/msg/FieldType")  # string<=255
    assert field_type(nested_type_name="n" * 255).nested_type_name == "n" * 255
    with pytest.raises(MessageError, match=r"^nested_type_name: string longer than 255"):
        field_type(nested_type_name="n" * 256)
    with pytest.raises(MessageError, match=r"^frame_id: expected a string"):
        message_class("std_msgs/msg/Header")(frame_id=b"world")


def test_compiled_copy_is_deep() -> None:
    msg = PoseStamped()
    msg.pose.position.x = 1.0
    copied = msg.copy()
    msg.pose.position.x = 2.0
    msg.header.stamp.sec = 5
    assert copied.pose.position.x == 1.0
    assert copied.header.stamp.sec == 0


def test_compiled_to_dict_puts_each_field_under_its_name_as_json_holds_it() -> None:
    """Values apart, so that a field under another's name shows; every kind of field: numbers, a
    string, nested messages, a fixed-size array (numpy), sequences of numbers and of strings
    (array.array, list) and of messages."""
    imu = message_class("sensor_msgs/msg/Imu").from_dict(
        {"header": {"frame_id": "imu"}, "orientation": {"x": 1.0, "y": 2.0, "z": 3.0, "w": 4.0}}
    )
    imu.linear_acceleration_covariance = [float(i) for i in range(9)]
    assert Message.to_dict(imu) == imu.to_dict()
    shown = imu.to_dict()
    assert shown["orientation"] == {"x": 1.0, "y": 2.0, "z": 3.0, "w": 4.0}
    assert shown["header"] == {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": "imu"}
    assert shown["linear_acceleration_covariance"] == [float(i) for i in range(9)]
    # numpy's array and numbers are not JSON's: a list of Python floats is
    assert type(shown["linear_acceleration_covariance"]) is list
    assert {type(v) for v in shown["linear_acceleration_covariance"]} == {float}

    joints = message_class("sensor_msgs/msg/JointState").from_dict(
        {"name": ["a", "b"], "position": [0.5, -0.5], "velocity": [1.0], "effort": []}
    )
    assert joints.to_dict() == Message.to_dict(joints)
    assert {k: joints.to_dict()[k] for k in ("name", "position", "velocity", "effort")} == {
        "name": ["a", "b"],
        "position": [0.5, -0.5],
        "velocity": [1.0],
        "effort": [],
    }
    assert type(joints.to_dict()["position"]) is list  # not array.array

    tf = message_class("tf2_msgs/msg/TFMessage").from_dict(
        {
            "transforms": [
                {"child_frame_id": "one"},
                {"child_frame_id": "two", "transform": {"translation": {"z": 7.0}}},
            ]
        }
    )
    shown_tf = tf.to_dict()
    assert shown_tf == Message.to_dict(tf)
    assert [t["child_frame_id"] for t in shown_tf["transforms"]] == ["one", "two"]
    assert shown_tf["transforms"][1]["transform"]["translation"] == {"x": 0.0, "y": 0.0, "z": 7.0}
