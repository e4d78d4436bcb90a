"""Message values: fields checked on construction, assignment and from_dict; JSON by ROS field names."""

from __future__ import annotations

import json

import pytest

from node_runtime.msgs import (
    Bool,
    Float64,
    Header,
    Int64,
    Key,
    MessageError,
    Point,
    Pose,
    PoseStamped,
    Quaternion,
    String,
    Time,
    Twist,
)

INT64_MIN, INT64_MAX = -(2**63), 2**63 - 1


# -- integer fields ---------------------------------------------------------------------------
@pytest.mark.parametrize("value", [1.0, 2.5, float("nan")])
def test_int_field_float_value_raises_naming_field(value: float) -> None:
    with pytest.raises(MessageError) as err:
        Int64(data=value)
    assert err.value.path == "data"
    assert "int64" in str(err.value)


@pytest.mark.parametrize("value", [True, False])
def test_int_field_bool_value_raises(value: bool) -> None:
    with pytest.raises(MessageError):
        Int64(data=value)
    with pytest.raises(MessageError):
        Key(code=value)


@pytest.mark.parametrize("code", [0, 1, 97, 65535])
def test_uint16_field_in_range_value_is_kept(code: int) -> None:
    assert Key(code=code).code == code


@pytest.mark.parametrize("code", [-1, 65536, 2**20])
def test_uint16_field_out_of_range_value_raises(code: int) -> None:
    with pytest.raises(MessageError) as err:
        Key(code=code)
    assert err.value.path == "code"
    assert "uint16" in str(err.value) and "0..65535" in str(err.value)


@pytest.mark.parametrize("value", [INT64_MIN, -1, 0, INT64_MAX])
def test_int64_field_bounds_are_accepted(value: int) -> None:
    assert Int64(data=value).data == value


@pytest.mark.parametrize("value", [INT64_MIN - 1, INT64_MAX + 1, 2**64])
def test_int64_field_beyond_bounds_raises(value: int) -> None:
    with pytest.raises(MessageError, match="out of range for int64"):
        Int64(data=value)


def test_int_field_assignment_after_construction_is_checked_and_keeps_old_value() -> None:
    msg = Int64(data=3)
    with pytest.raises(MessageError):
        msg.data = 2.5
    assert msg.data == 3
    msg.data = -7
    assert msg.data == -7


# -- float, bool and string fields ------------------------------------------------------------
def test_float_field_int_value_is_stored_as_float() -> None:
    msg = Float64(data=3)
    assert msg.data == 3.0 and type(msg.data) is float
    msg.data = 5
    assert type(msg.data) is float
    assert type(Float64.from_dict({"data": 7}).data) is float


@pytest.mark.parametrize("value", [True, "1.0", None, [1.0]])
def test_float_field_non_number_raises(value: object) -> None:
    with pytest.raises(MessageError) as err:
        Float64(data=value)
    assert err.value.path == "data"


@pytest.mark.parametrize("value", [0, 1, "true", None])
def test_bool_field_non_bool_raises(value: object) -> None:
    with pytest.raises(MessageError):
        Bool(data=value)


def test_string_field_non_string_raises() -> None:
    with pytest.raises(MessageError):
        String(data=5)
    assert String(data="hi").data == "hi"


def test_message_unknown_attribute_assignment_raises() -> None:
    msg = Bool()
    with pytest.raises(AttributeError, match="no field 'dat'"):
        msg.dat = True


def test_message_constructor_unknown_keyword_raises() -> None:
    with pytest.raises(TypeError, match="foo"):
        Int64(foo=1)


# -- nested messages --------------------------------------------------------------------------
def test_nested_field_wrong_message_type_raises_naming_field() -> None:
    with pytest.raises(MessageError) as err:
        PoseStamped(pose=Point())
    assert err.value.path == "pose"
    msg = PoseStamped()
    with pytest.raises(MessageError):
        msg.header = Time()
    assert isinstance(msg.header, Header)


def test_nested_field_defaults_are_fresh_per_message() -> None:
    a, b = PoseStamped(), PoseStamped()
    a.pose.position.x = 1.0
    assert b.pose.position.x == 0.0


# -- JSON by ROS field names ------------------------------------------------------------------
def test_to_dict_nested_message_uses_ros_field_names() -> None:
    msg = PoseStamped()
    msg.header.frame_id = "world"
    msg.header.stamp.sec = 4
    msg.pose.position.z = 3.0
    assert msg.to_dict() == {
        "header": {"stamp": {"sec": 4, "nanosec": 0}, "frame_id": "world"},
        "pose": {
            "position": {"x": 0.0, "y": 0.0, "z": 3.0},
            "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0},
        },
    }


def test_key_json_round_trip_gives_equal_message() -> None:
    data = {
        "header": {"stamp": {"sec": 3, "nanosec": 250_000_000}, "frame_id": ""},
        "code": 97,
        "modifiers": 4096,
    }
    msg = Key.from_dict(json.loads(json.dumps(data)))
    assert (msg.code, msg.modifiers, msg.header.stamp.nanosec) == (97, 4096, 250_000_000)
    assert json.loads(json.dumps(msg.to_dict())) == data
    assert Key.from_dict(msg.to_dict()) == msg


def test_from_dict_missing_fields_keep_defaults() -> None:
    q = Quaternion.from_dict({"x": 0.5})
    assert (q.x, q.y, q.z, q.w) == (0.5, 0.0, 0.0, 1.0)
    assert Twist.from_dict({}) == Twist()


def test_from_dict_unknown_nested_field_raises_naming_path() -> None:
    with pytest.raises(MessageError) as err:
        PoseStamped.from_dict({"pose": {"position": {"q": 1.0}}})
    assert err.value.path == "pose.position.q"
    assert str(err.value).startswith("pose.position.q:")


def test_from_dict_nested_non_object_raises_naming_path() -> None:
    with pytest.raises(MessageError) as err:
        PoseStamped.from_dict({"pose": 5})
    assert err.value.path == "pose"
    with pytest.raises(MessageError) as err:
        PoseStamped.from_dict({"header": {"stamp": [1, 2]}})
    assert err.value.path == "header.stamp"


def test_from_dict_nested_bad_primitive_raises_naming_path() -> None:
    with pytest.raises(MessageError) as err:
        Key.from_dict({"header": {"stamp": {"sec": 1.5}}})
    assert err.value.path == "header.stamp.sec"
    with pytest.raises(MessageError) as err:
        Pose.from_dict({"orientation": {"w": True}})
    assert err.value.path == "orientation.w"
    with pytest.raises(MessageError) as err:
        Key.from_dict({"modifiers": 70000})
    assert err.value.path == "modifiers"


def test_from_dict_non_mapping_raises() -> None:
    with pytest.raises(MessageError, match="expected an object"):
        Bool.from_dict([True])


# -- copies and equality ----------------------------------------------------------------------
def test_copy_mutating_nested_field_of_copy_leaves_original() -> None:
    original = PoseStamped()
    original.pose.position.x = 1.0
    copy = original.copy()
    assert copy == original and copy is not original
    copy.pose.position.x = 9.0
    copy.header.frame_id = "map"
    assert original.pose.position.x == 1.0
    assert original.header.frame_id == ""


def test_equality_compares_values_and_type() -> None:
    assert Int64(data=1) == Int64(data=1)
    assert Int64(data=1) != Int64(data=2)
    assert Float64(data=1.0) != Int64(data=1)
