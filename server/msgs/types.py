"""The message types the lab uses, with their ROS 2 names, fields and constants."""

from __future__ import annotations

from ._base import Field, Message, define

Time = define("builtin_interfaces/msg/Time", [Field("sec", "int32", 0), Field("nanosec", "uint32", 0)])

Header = define("std_msgs/msg/Header", [Field("stamp", Time), Field("frame_id", "string", "")])
Bool = define("std_msgs/msg/Bool", [Field("data", "bool", False)])
Int64 = define("std_msgs/msg/Int64", [Field("data", "int64", 0)])
Float64 = define("std_msgs/msg/Float64", [Field("data", "float64", 0.0)])
String = define("std_msgs/msg/String", [Field("data", "string", "")])

Vector3 = define("geometry_msgs/msg/Vector3", [Field(n, "float64", 0.0) for n in "xyz"])
Point = define("geometry_msgs/msg/Point", [Field(n, "float64", 0.0) for n in "xyz"])
Quaternion = define(
    "geometry_msgs/msg/Quaternion",
    [
        Field("x", "float64", 0.0),
        Field("y", "float64", 0.0),
        Field("z", "float64", 0.0),
        Field("w", "float64", 1.0),
    ],
)
Pose = define("geometry_msgs/msg/Pose", [Field("position", Point), Field("orientation", Quaternion)])
PoseStamped = define("geometry_msgs/msg/PoseStamped", [Field("header", Header), Field("pose", Pose)])
Twist = define("geometry_msgs/msg/Twist", [Field("linear", Vector3), Field("angular", Vector3)])
TwistStamped = define("geometry_msgs/msg/TwistStamped", [Field("header", Header), Field("twist", Twist)])

Log = define(
    "rcl_interfaces/msg/Log",
    [
        Field("stamp", Time),
        Field("level", "uint8", 20),
        Field("name", "string", ""),
        Field("msg", "string", ""),
        Field("file", "string", ""),
        Field("function", "string", ""),
        Field("line", "uint32", 0),
    ],
    {"DEBUG": 10, "INFO": 20, "WARN": 30, "ERROR": 40, "FATAL": 50},
)


def _key_constants() -> dict[str, int]:
    """Every KEY_* and MODIFIER_* constant of keyboard_msgs/msg/Key (cmower/ros2-keyboard)."""
    named = {
        "UNKNOWN": 0, "FIRST": 0, "BACKSPACE": 8, "TAB": 9, "CLEAR": 12, "RETURN": 13, "PAUSE": 19,
        "ESCAPE": 27, "SPACE": 32, "EXCLAIM": 33, "QUOTEDBL": 34, "HASH": 35, "DOLLAR": 36,
        "AMPERSAND": 38, "QUOTE": 39, "LEFTPAREN": 40, "RIGHTPAREN": 41, "ASTERISK": 42, "PLUS": 43,
        "COMMA": 44, "MINUS": 45, "PERIOD": 46, "SLASH": 47, "COLON": 58, "SEMICOLON": 59, "LESS": 60,
        "EQUALS": 61, "GREATER": 62, "QUESTION": 63, "AT": 64, "LEFTBRACKET": 91, "BACKSLASH": 92,
        "RIGHTBRACKET": 93, "CARET": 94, "UNDERSCORE": 95, "BACKQUOTE": 96, "DELETE": 127,
        "KP_PERIOD": 266, "KP_DIVIDE": 267, "KP_MULTIPLY": 268, "KP_MINUS": 269, "KP_PLUS": 270,
        "KP_ENTER": 271, "KP_EQUALS": 272, "UP": 273, "DOWN": 274, "RIGHT": 275, "LEFT": 276,
        "INSERT": 277, "HOME": 278, "END": 279, "PAGEUP": 280, "PAGEDOWN": 281, "NUMLOCK": 300,
        "CAPSLOCK": 301, "SCROLLOCK": 302, "RSHIFT": 303, "LSHIFT": 304, "RCTRL": 305, "LCTRL": 306,
        "RALT": 307, "LALT": 308, "RMETA": 309, "LMETA": 310, "LSUPER": 311, "RSUPER": 312, "MODE": 313,
        "COMPOSE": 314, "HELP": 315, "PRINT": 316, "SYSREQ": 317, "BREAK": 318, "MENU": 319,
        "POWER": 320, "EURO": 321, "UNDO": 322,
    }  # fmt: skip
    consts = {f"KEY_{k}": v for k, v in named.items()}
    consts.update({f"KEY_{d}": 48 + d for d in range(10)})
    consts.update({f"KEY_{chr(65 + i)}": 97 + i for i in range(26)})
    consts.update({f"KEY_WORLD_{i}": 160 + i for i in range(96)})
    consts.update({f"KEY_KP{d}": 256 + d for d in range(10)})
    consts.update({f"KEY_F{i}": 281 + i for i in range(1, 16)})
    modifiers = {
        "NONE": 0, "LSHIFT": 1, "RSHIFT": 2, "LCTRL": 64, "RCTRL": 128, "LALT": 256, "RALT": 512,
        "LMETA": 1024, "RMETA": 2048, "NUM": 4096, "CAPS": 8192, "MODE": 16384, "RESERVED": 32768,
    }  # fmt: skip
    consts.update({f"MODIFIER_{k}": v for k, v in modifiers.items()})
    return consts


KEY_CONSTANTS = _key_constants()
Key = define(
    "keyboard_msgs/msg/Key",
    [Field("header", Header), Field("code", "uint16", 0), Field("modifiers", "uint16", 0)],
    dict(KEY_CONSTANTS),
)

ALL_TYPES: tuple[type[Message], ...] = (
    Time, Header, Bool, Int64, Float64, String, Vector3, Point, Quaternion, Pose, PoseStamped,
    Twist, TwistStamped, Key, Log,
)  # fmt: skip
