"""The lab's message types: ROS 2 names, field names and types, and every keyboard_msgs/Key constant."""

from __future__ import annotations

import json

import pytest

from node_runtime.msgs import (
    KEY_CONSTANTS,
    Bool,
    Float64,
    Header,
    Int64,
    Key,
    Log,
    Message,
    Point,
    Pose,
    PoseStamped,
    Quaternion,
    String,
    Time,
    Twist,
    TwistStamped,
    Vector3,
    get_type,
)
from node_runtime.msgs.types import ALL_TYPES

ROS_NAMES = [
    (Time, "builtin_interfaces/msg/Time"),
    (Header, "std_msgs/msg/Header"),
    (Bool, "std_msgs/msg/Bool"),
    (Int64, "std_msgs/msg/Int64"),
    (Float64, "std_msgs/msg/Float64"),
    (String, "std_msgs/msg/String"),
    (Vector3, "geometry_msgs/msg/Vector3"),
    (Point, "geometry_msgs/msg/Point"),
    (Quaternion, "geometry_msgs/msg/Quaternion"),
    (Pose, "geometry_msgs/msg/Pose"),
    (PoseStamped, "geometry_msgs/msg/PoseStamped"),
    (Twist, "geometry_msgs/msg/Twist"),
    (TwistStamped, "geometry_msgs/msg/TwistStamped"),
    (Key, "keyboard_msgs/msg/Key"),
    (Log, "rcl_interfaces/msg/Log"),
]

FIELDS = [
    (Time, {"sec": "int32", "nanosec": "uint32"}),
    (Header, {"stamp": "builtin_interfaces/msg/Time", "frame_id": "string"}),
    (Bool, {"data": "bool"}),
    (Int64, {"data": "int64"}),
    (Float64, {"data": "float64"}),
    (String, {"data": "string"}),
    (Vector3, {"x": "float64", "y": "float64", "z": "float64"}),
    (Quaternion, {"x": "float64", "y": "float64", "z": "float64", "w": "float64"}),
    (Pose, {"position": "geometry_msgs/msg/Point", "orientation": "geometry_msgs/msg/Quaternion"}),
    (PoseStamped, {"header": "std_msgs/msg/Header", "pose": "geometry_msgs/msg/Pose"}),
    (Twist, {"linear": "geometry_msgs/msg/Vector3", "angular": "geometry_msgs/msg/Vector3"}),
    (Key, {"header": "std_msgs/msg/Header", "code": "uint16", "modifiers": "uint16"}),
]

# ref §2.2, spot-checked across every range of the table.
KEY_VALUES = {
    "KEY_UNKNOWN": 0,
    "KEY_FIRST": 0,
    "KEY_BACKSPACE": 8,
    "KEY_TAB": 9,
    "KEY_CLEAR": 12,
    "KEY_RETURN": 13,
    "KEY_PAUSE": 19,
    "KEY_ESCAPE": 27,
    "KEY_SPACE": 32,
    "KEY_EXCLAIM": 33,
    "KEY_QUOTEDBL": 34,
    "KEY_HASH": 35,
    "KEY_DOLLAR": 36,
    "KEY_AMPERSAND": 38,
    "KEY_QUOTE": 39,
    "KEY_LEFTPAREN": 40,
    "KEY_RIGHTPAREN": 41,
    "KEY_ASTERISK": 42,
    "KEY_PLUS": 43,
    "KEY_COMMA": 44,
    "KEY_MINUS": 45,
    "KEY_PERIOD": 46,
    "KEY_SLASH": 47,
    "KEY_0": 48,
    "KEY_5": 53,
    "KEY_9": 57,
    "KEY_COLON": 58,
    "KEY_SEMICOLON": 59,
    "KEY_LESS": 60,
    "KEY_EQUALS": 61,
    "KEY_GREATER": 62,
    "KEY_QUESTION": 63,
    "KEY_AT": 64,
    "KEY_LEFTBRACKET": 91,
    "KEY_BACKSLASH": 92,
    "KEY_RIGHTBRACKET": 93,
    "KEY_CARET": 94,
    "KEY_UNDERSCORE": 95,
    "KEY_BACKQUOTE": 96,
    "KEY_A": 97,
    "KEY_B": 98,
    "KEY_M": 109,
    "KEY_Z": 122,
    "KEY_DELETE": 127,
    "KEY_WORLD_0": 160,
    "KEY_WORLD_1": 161,
    "KEY_WORLD_47": 207,
    "KEY_WORLD_95": 255,
    "KEY_KP0": 256,
    "KEY_KP9": 265,
    "KEY_KP_PERIOD": 266,
    "KEY_KP_DIVIDE": 267,
    "KEY_KP_MULTIPLY": 268,
    "KEY_KP_MINUS": 269,
    "KEY_KP_PLUS": 270,
    "KEY_KP_ENTER": 271,
    "KEY_KP_EQUALS": 272,
    "KEY_UP": 273,
    "KEY_DOWN": 274,
    "KEY_RIGHT": 275,
    "KEY_LEFT": 276,
    "KEY_INSERT": 277,
    "KEY_HOME": 278,
    "KEY_END": 279,
    "KEY_PAGEUP": 280,
    "KEY_PAGEDOWN": 281,
    "KEY_F1": 282,
    "KEY_F2": 283,
    "KEY_F12": 293,
    "KEY_F15": 296,
    "KEY_NUMLOCK": 300,
    "KEY_CAPSLOCK": 301,
    "KEY_SCROLLOCK": 302,
    "KEY_RSHIFT": 303,
    "KEY_LSHIFT": 304,
    "KEY_RCTRL": 305,
    "KEY_LCTRL": 306,
    "KEY_RALT": 307,
    "KEY_LALT": 308,
    "KEY_RMETA": 309,
    "KEY_LMETA": 310,
    "KEY_LSUPER": 311,
    "KEY_RSUPER": 312,
    "KEY_MODE": 313,
    "KEY_COMPOSE": 314,
    "KEY_HELP": 315,
    "KEY_PRINT": 316,
    "KEY_SYSREQ": 317,
    "KEY_BREAK": 318,
    "KEY_MENU": 319,
    "KEY_POWER": 320,
    "KEY_EURO": 321,
    "KEY_UNDO": 322,
}
MODIFIER_VALUES = {
    "MODIFIER_NONE": 0,
    "MODIFIER_LSHIFT": 1,
    "MODIFIER_RSHIFT": 2,
    "MODIFIER_LCTRL": 64,
    "MODIFIER_RCTRL": 128,
    "MODIFIER_LALT": 256,
    "MODIFIER_RALT": 512,
    "MODIFIER_LMETA": 1024,
    "MODIFIER_RMETA": 2048,
    "MODIFIER_NUM": 4096,
    "MODIFIER_CAPS": 8192,
    "MODIFIER_MODE": 16384,
    "MODIFIER_RESERVED": 32768,
}


@pytest.mark.parametrize(("cls", "name"), ROS_NAMES, ids=[n for _, n in ROS_NAMES])
def test_message_type_ros_name_is_verbatim(cls: type[Message], name: str) -> None:
    assert name == cls.TYPE


@pytest.mark.parametrize(("cls", "fields"), FIELDS, ids=[c.TYPE for c, _ in FIELDS])
def test_message_type_fields_have_ros_names_and_types(cls: type[Message], fields: dict[str, str]) -> None:
    assert cls.get_fields_and_field_types() == fields


def test_message_defaults_are_ros_defaults() -> None:
    assert Quaternion().w == 1.0 and Quaternion().x == 0.0
    assert (Bool().data, Int64().data, Float64().data, String().data) == (False, 0, 0.0, "")
    assert (Key().code, Key().modifiers, Key().header.frame_id) == (0, 0, "")
    assert Log().level == 0 and (Log.DEBUG, Log.INFO, Log.FATAL) == (
        10,
        20,
        50,
    )  # rcl_interfaces/msg/Log: no default level


@pytest.mark.parametrize(("name", "value"), sorted(KEY_VALUES.items()))
def test_key_constant_has_ref_value(name: str, value: int) -> None:
    assert getattr(Key, name) == value
    assert KEY_CONSTANTS[name] == value


@pytest.mark.parametrize(("name", "value"), sorted(MODIFIER_VALUES.items()))
def test_key_modifier_constant_has_ref_value(name: str, value: int) -> None:
    assert getattr(Key, name) == value


def test_key_letter_constants_are_lower_case_ascii_a_to_z() -> None:
    for i in range(26):
        assert getattr(Key, f"KEY_{chr(65 + i)}") == ord("a") + i


def test_key_range_constants_cover_every_index() -> None:
    assert [getattr(Key, f"KEY_{d}") for d in range(10)] == list(range(48, 58))
    assert [getattr(Key, f"KEY_WORLD_{i}") for i in range(96)] == list(range(160, 256))
    assert [getattr(Key, f"KEY_KP{d}") for d in range(10)] == list(range(256, 266))
    assert [getattr(Key, f"KEY_F{i}") for i in range(1, 16)] == list(range(282, 297))
    assert not hasattr(Key, "KEY_F16") and not hasattr(Key, "KEY_WORLD_96")


def test_key_constants_all_prefixed_uint16_and_on_instances() -> None:
    msg = Key()
    for name, value in KEY_CONSTANTS.items():
        assert name.startswith(("KEY_", "MODIFIER_")), name
        assert 0 <= value <= 65535, name
        assert getattr(msg, name) == value
    assert set(MODIFIER_VALUES) == {n for n in KEY_CONSTANTS if n.startswith("MODIFIER_")}


def test_key_modifier_bits_are_distinct_single_bits() -> None:
    bits = [v for n, v in MODIFIER_VALUES.items() if n != "MODIFIER_NONE"]
    assert all(b & (b - 1) == 0 for b in bits)
    assert len(set(bits)) == len(bits)


# -- a contract every message type keeps -----------------------------------------------------------
@pytest.mark.parametrize("cls", ALL_TYPES, ids=[t.TYPE for t in ALL_TYPES])
def test_message_type_default_json_round_trip_equal_and_registered(cls: type[Message]) -> None:
    msg = cls()
    data = json.loads(json.dumps(msg.to_dict()))
    assert set(data) == set(cls.get_fields_and_field_types())
    assert cls.from_dict(data) == msg
    copy = msg.copy()
    assert copy == msg and copy is not msg
    assert get_type(cls.TYPE) is cls
    pkg, _, name = cls.TYPE.split("/")
    assert repr(msg).startswith(f"{pkg}.msg.{name}(")
