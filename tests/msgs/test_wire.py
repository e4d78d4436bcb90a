"""Messages on the wire: RIHS01 hashes and CDR bytes, checked against references computed apart.

The hashes are checked against ROS 2's own values (std_msgs/msg/Char among them: rosidl hashes
char as uint8, rosbags does not), and for every
other type against REP-2016 computed here from the definitions by a separate implementation (its
own field table from rosbags' parser, its own JSON). CDR is checked byte for byte against an
encoder written here from the OMG rules, for every type with seeded random values.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import random
import re
import struct
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from ros_reference import ROS_REFERENCE_HASHES
from rosbags.interfaces import Nodetype
from rosbags.typesys import get_types_from_msg

from node_runtime.msgs import (
    Bool,
    Empty,
    Key,
    Message,
    PoseStamped,
    String,
    Vector3,
    get_service_type,
    get_type,
    type_names,
)
from node_runtime.msgs._base import define_message
from node_runtime.msgs.definitions import ROS_INTERFACES_DIR, lab_definitions, load_definitions
from node_runtime.msgs.wire import (
    WireError,
    build_typestore,
    dds_type_name,
    deserialize,
    ros_type_name,
    serialize,
    type_hash,
)

# -- REP-2016, written apart from node_runtime.msgs --------------------------------------------------
_TYPE_IDS = {
    "nested": 1,
    "int8": 2,
    "uint8": 3,
    "char": 3,
    "int16": 4,
    "uint16": 5,
    "int32": 6,
    "uint32": 7,
    "int64": 8,
    "uint64": 9,
    "float32": 10,
    "float64": 11,
    "bool": 15,
    "byte": 16,
    "string": 17,
    "wstring": 18,
}
_BOUNDED_STRING = {"string": 21, "wstring": 22}


def _field_type(desc: tuple) -> dict[str, Any]:  # type: ignore[type-arg]
    kind, detail = desc
    if kind in (Nodetype.BASE, Nodetype.NAME):
        base, strcap = (detail[0], detail[1]) if kind == Nodetype.BASE else ("nested", 0)
        type_id = _BOUNDED_STRING[base] if strcap and base in _BOUNDED_STRING else _TYPE_IDS[base]
        return {
            "type_id": type_id,
            "capacity": 0,
            "string_capacity": strcap,
            "nested_type_name": detail if kind == Nodetype.NAME else "",
        }
    inner, count = detail
    t = _field_type(inner)
    offset = 48 if kind == Nodetype.ARRAY else (96 if count else 144)
    return {**t, "type_id": t["type_id"] + offset, "capacity": count}


def _rosbags_fields(name: str, text: str) -> dict[str, list[tuple[str, Any]]]:
    return {n: f for n, (_, f) in get_types_from_msg(text, name).items()}


@functools.cache
def _all_descriptions() -> dict[str, list[tuple[str, Any]]]:
    """Every type's fields as rosbags parses them, services as rosidl expands them."""
    defs = lab_definitions()
    out: dict[str, list[tuple[str, Any]]] = {}
    for name, spec in defs.messages.items():
        out.update(_rosbags_fields(name, spec.text))
    for name, srv in defs.services.items():
        out.update(_service_fields(name, srv.request.text, srv.response.text))
    for name, action in defs.actions.items():
        out.update(_action_fields(name, action.text))
    return out


def _action_fields(name: str, text: str) -> dict[str, list[tuple[str, Any]]]:
    """An action's types expanded here from its ``.action`` text, as rosidl expands one (apart
    from node_runtime.msgs.action_spec): its parts, two services, feedback message and the action."""
    goal, result, feedback = re.split(r"^---[ \t]*$", text, flags=re.MULTILINE)
    uuid = "unique_identifier_msgs/UUID goal_id"
    out: dict[str, list[tuple[str, Any]]] = {}
    for suffix, part in (
        ("_Goal", goal),
        ("_Result", result),
        ("_Feedback", feedback),
        ("_FeedbackMessage", f"{uuid}\n{name}_Feedback feedback"),
    ):
        out.update(_rosbags_fields(name + suffix, part))
    out.update(
        _service_fields(
            f"{name}_SendGoal", f"{uuid}\n{name}_Goal goal", "bool accepted\nbuiltin_interfaces/Time stamp"
        )
    )
    out.update(_service_fields(f"{name}_GetResult", uuid, f"int8 status\n{name}_Result result"))
    members = (
        "_Goal goal",
        "_Result result",
        "_Feedback feedback",
        "_SendGoal send_goal_service",
        "_GetResult get_result_service",
        "_FeedbackMessage feedback_message",
    )
    out.update(_rosbags_fields(name, "\n".join(name + m for m in members)))
    return out


def _service_fields(name: str, request: str, response: str) -> dict[str, list[tuple[str, Any]]]:
    out: dict[str, list[tuple[str, Any]]] = {}
    event = (
        f"service_msgs/msg/ServiceEventInfo info\n{name}_Request[<=1] request\n{name}_Response[<=1] response"
    )
    whole = f"{name}_Request request_message\n{name}_Response response_message\n{name}_Event event_message"
    parts = (
        ("_Request", request),
        ("_Response", response),
        ("_Event", event),
        ("", whole),
    )
    own = {f"{name}{suffix}" for suffix, _ in parts}

    def fix(match: re.Match[str], own: set[str] = own) -> str:  # a part, or a message of the package
        part = f"{match[1]}/srv/{match[2]}"
        return part if part in own else f"{match[1]}/msg/{match[2]}"

    for suffix, text in parts:
        for n, f in _rosbags_fields(f"{name}{suffix}", text).items():
            fixed = json.loads(re.sub(r"(\w+)/srv/msg/(\w+)", fix, json.dumps(f)))
            out[n.replace("/srv/msg/", "/srv/")] = [(fn, _tuples(fd)) for fn, fd in fixed]
    return out


def _tuples(value: Any) -> Any:
    if isinstance(value, list):
        items = tuple(_tuples(v) for v in value)
        return (Nodetype(items[0]), items[1]) if len(items) == 2 and isinstance(items[0], int) else items
    return value


def _description(name: str, fields: list[tuple[str, Any]]) -> dict[str, Any]:
    if not fields:
        fields = [("structure_needs_at_least_one_member", (Nodetype.BASE, ("uint8", 0)))]
    return {"type_name": name, "fields": [{"name": n, "type": _field_type(d)} for n, d in fields]}


def rep2016_hash(name: str) -> str:
    table = _all_descriptions()
    referenced: dict[str, dict[str, Any]] = {}

    def visit(type_name: str) -> None:
        for _, desc in table[type_name]:
            inner = desc if desc[0] in (Nodetype.BASE, Nodetype.NAME) else desc[1][0]
            if inner[0] == Nodetype.NAME and inner[1] not in referenced:
                referenced[inner[1]] = _description(inner[1], table[inner[1]])
                visit(inner[1])

    visit(name)
    whole = {
        "type_description": _description(name, table[name]),
        "referenced_type_descriptions": [referenced[k] for k in sorted(referenced)],
    }
    text = json.dumps(whole, ensure_ascii=True, allow_nan=False, separators=(", ", ": "), sort_keys=False)
    return "RIHS01_" + hashlib.sha256(text.encode()).hexdigest()


# -- hashes ------------------------------------------------------------------------------------
@pytest.mark.parametrize(("name", "expected"), sorted(ROS_REFERENCE_HASHES.items()))
def test_type_hash_equals_ros_2_reference_value(name: str, expected: str) -> None:
    assert type_hash(name) == "RIHS01_" + expected


@pytest.mark.parametrize(("name", "expected"), sorted(ROS_REFERENCE_HASHES.items()))
def test_reference_hasher_here_agrees_with_ros_2_too(name: str, expected: str) -> None:
    assert rep2016_hash(name) == "RIHS01_" + expected


@pytest.mark.parametrize(
    "name",
    sorted(lab_definitions().messages)
    + sorted(lab_definitions().services)
    + sorted(lab_definitions().actions),
)
def test_type_hash_of_every_type_equals_rep2016_computed_apart(name: str) -> None:
    assert type_hash(name) == rep2016_hash(name)


def test_type_hash_of_every_ros_2_type_equals_the_one_rosidl_wrote_into_its_wheel() -> None:
    """The hashes ROS 2's own build computed (share/<pkg>/msg/<Type>.json in its PyPI wheels)."""
    ros = json.loads((ROS_INTERFACES_DIR / "type_hashes.json").read_text(encoding="utf-8"))
    assert len(ros) > 200 and "sensor_msgs/msg/PointCloud2" in ros
    assert {name: type_hash(name) for name in ros} == ros


def test_dds_type_name_round_trips() -> None:
    assert dds_type_name("geometry_msgs/msg/Vector3") == "geometry_msgs::msg::dds_::Vector3_"
    assert dds_type_name("std_srvs/srv/Trigger") == "std_srvs::srv::dds_::Trigger_"
    assert ros_type_name("geometry_msgs::msg::dds_::Vector3_") == "geometry_msgs/msg/Vector3"
    assert ros_type_name("geometry_msgs::msg::Vector3") is None
    assert ros_type_name("nonsense") is None


# -- CDR, written apart ----------------------------------------------------------------------
_FORMATS = {
    "bool": "?",
    "byte": "B",
    "char": "B",
    "int8": "b",
    "uint8": "B",
    "int16": "h",
    "uint16": "H",
    "int32": "i",
    "uint32": "I",
    "int64": "q",
    "uint64": "Q",
    "float32": "f",
    "float64": "d",
}


class _Cdr:
    """Little-endian XCDR1 as the OMG spec lays it out: alignment counted after the 4-byte header."""

    def __init__(self) -> None:
        self.out = bytearray()

    def _align(self, n: int) -> None:
        self.out += b"\0" * (-len(self.out) % n)

    def prim(self, kind: str, value: Any) -> None:
        if kind in ("string", "wstring"):
            data = value.encode() + b"\0"
            self.prim("uint32", len(data))
            self.out += data
            return
        fmt = _FORMATS[kind]
        self._align(struct.calcsize(fmt))
        self.out += struct.pack("<" + fmt, value)

    def message(self, msg: Message) -> None:
        if not msg.FIELDS:
            self.prim("uint8", 0)
        for f in msg.FIELDS:
            value = getattr(msg, f.name)
            values = list(value) if f.array else [value]
            if f.array and f.size is None:
                self.prim("uint32", len(values))
            for v in values:
                if isinstance(f.kind, str):
                    self.prim(f.kind, v.item() if hasattr(v, "item") else v)
                else:
                    self.message(v)


def cdr_apart(msg: Message) -> bytes:
    cdr = _Cdr()
    cdr.message(msg)
    return b"\x00\x01\x00\x00" + bytes(cdr.out)


def _random_value(rng: random.Random, kind: str, string_bound: int | None) -> Any:
    if kind == "bool":
        return rng.random() < 0.5
    if kind in ("float32", "float64"):
        value = rng.uniform(-1e3, 1e3)
        return struct.unpack("<f", struct.pack("<f", value))[0] if kind == "float32" else value
    if kind in ("string", "wstring"):
        return "".join(rng.choice("abcxyz é→") for _ in range(rng.randint(0, string_bound or 12)))
    bits = {"byte": 8, "char": 8}.get(kind, int("".join(c for c in kind if c.isdigit()) or 8))
    lo, hi = (
        (0, 2**bits - 1)
        if kind.startswith(("u", "byte", "char"))
        else (-(2 ** (bits - 1)), 2 ** (bits - 1) - 1)
    )
    return rng.randint(lo, hi)


def random_message(cls: type[Message], rng: random.Random) -> Message:
    msg = cls()
    for f in cls.FIELDS:
        count = f.size if f.size is not None else rng.randint(0, min(f.bound or 4, 4))
        if isinstance(f.kind, str):
            items = [_random_value(rng, f.kind, f.string_bound) for _ in range(count if f.array else 1)]
        else:
            items = [random_message(f.kind, rng) for _ in range(count if f.array else 1)]
        setattr(msg, f.name, items if f.array else items[0])
    return msg


ALL_WIRE_TYPES = type_names() + [
    part.TYPE
    for name in (
        "std_srvs/srv/Trigger",
        "std_srvs/srv/SetBool",
        "std_srvs/srv/Empty",
        "example_interfaces/srv/AddTwoInts",
    )
    for part in (get_service_type(name).Request, get_service_type(name).Response)
]


def _cls(name: str) -> type[Message]:
    if "/srv/" in name:
        service = get_service_type(name.rsplit("_", 1)[0])
        return service.Request if name.endswith("_Request") else service.Response
    return get_type(name)


@pytest.mark.parametrize("name", ALL_WIRE_TYPES)
def test_serialize_every_type_matches_cdr_written_apart_and_round_trips(name: str) -> None:
    rng = random.Random(name)
    cls = _cls(name)
    for _ in range(5):
        msg = random_message(cls, rng)
        data = serialize(msg)
        assert data == cdr_apart(msg)
        assert deserialize(name, data) == msg


def test_serialize_known_bytes_bool_and_vector3() -> None:
    assert serialize(Bool(data=True)) == bytes.fromhex("0001000001")
    assert serialize(Vector3(x=1.0, y=2.0, z=3.0)) == bytes.fromhex("00010000") + struct.pack("<3d", 1, 2, 3)


def test_serialize_empty_message_is_header_and_one_byte() -> None:
    assert serialize(Empty()) == bytes.fromhex("0001000000")


def test_serialize_sends_no_trailing_padding() -> None:
    data = serialize(String(data="abc"))  # header, uint32 length 4, "abc\0": 12 bytes, not padded to 16
    assert data == bytes.fromhex("00010000") + struct.pack("<I", 4) + b"abc\0"


def test_deserialize_accepts_trailing_padding() -> None:
    key = Key(code=97, modifiers=1)
    assert deserialize("keyboard_msgs/msg/Key", serialize(key) + b"\0\0\0") == key


@pytest.mark.parametrize(
    "data",
    [b"", b"\x00\x01", bytes.fromhex("00000000") + b"\x01", b"\x00\x01\x00\x00\x05"],
    ids=["empty", "header-only", "big-endian-header", "truncated"],
)
def test_deserialize_bad_bytes_raise_wire_error(data: bytes) -> None:
    with pytest.raises(WireError):
        deserialize("geometry_msgs/msg/PoseStamped", data)


def test_deserialize_string_or_sequence_over_its_bound_is_refused(tmp_path: Path) -> None:
    folder = tmp_path / "demo_msgs" / "msg"
    folder.mkdir(parents=True)
    (folder / "Tags.msg").write_text("string<=3 tag\nint32[<=2] few\n")
    definitions = load_definitions(tmp_path)
    define_message(definitions.messages["demo_msgs/msg/Tags"])
    store = build_typestore(definitions)
    fits = SimpleNamespace(tag="abc", few=np.array([1, 2], dtype=np.int32))
    assert (
        deserialize("demo_msgs/msg/Tags", bytes(store.serialize_cdr(fits, "demo_msgs/msg/Tags")), store).tag
        == "abc"
    )
    # rosbags writes what it is given; a peer could send more than the bounds allow.
    for too_much in (
        SimpleNamespace(tag="abcd", few=fits.few),
        SimpleNamespace(tag="a", few=np.arange(3, dtype=np.int32)),
    ):
        data = bytes(store.serialize_cdr(too_much, "demo_msgs/msg/Tags"))
        with pytest.raises(WireError):
            deserialize("demo_msgs/msg/Tags", data, store)


def test_numeric_arrays_are_numpy_and_checked() -> None:
    imu = get_type("sensor_msgs/msg/Imu")()
    assert isinstance(imu.orientation_covariance, np.ndarray) and imu.orientation_covariance.shape == (9,)
    imu.orientation_covariance = [math.pi] * 9
    assert deserialize(imu.TYPE, serialize(imu)) == imu
    pose = PoseStamped()
    assert deserialize(pose.TYPE, serialize(pose)) == pose


def test_every_service_type_has_rosidls_event_message_beside_request_and_response() -> None:
    """``<Srv>.Event`` as rosidl generates it: the call's info, at most one request and one
    response; its name is the one whose hash ROS 2's wheels carry, and a call's event round-trips."""
    ros = json.loads((ROS_INTERFACES_DIR / "type_hashes.json").read_text(encoding="utf-8"))
    events = [name.removesuffix("_Event") for name in ros if name.endswith("_Event") and "/srv/" in name]
    assert "std_srvs/srv/SetBool" in events
    for name in events:
        srv = get_service_type(name)
        event = srv.Event
        assert event is srv.Event, name
        assert event.TYPE.endswith("_Event") and event.TYPE.removesuffix("_Event") == name, name
        assert [f.name for f in event.FIELDS] == ["info", "request", "response"], name
        assert type_hash(event.TYPE) == ros[event.TYPE], name
    set_bool = get_service_type("std_srvs/srv/SetBool")
    call = set_bool.Event(request=[set_bool.Request(data=True)])  # type: ignore[call-arg]
    back = deserialize(set_bool.Event.TYPE, serialize(call))
    assert [r.data for r in back.request] == [True] and list(back.response) == []
