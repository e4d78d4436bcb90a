"""``type_schema``: every message type as a draft 2020-12 JSON Schema that its defaults satisfy."""

from __future__ import annotations

from typing import Any

import pytest

from node_runtime.msgs import Imu, Key, Vector3, get_type, type_names
from node_runtime.msgs._base import define_message
from node_runtime.msgs.idl import parse_message
from node_runtime.msgs.schema import JSON_SCHEMA_DIALECT, interface_text, type_schema

_JSON_TYPES: dict[str, Any] = {
    "object": (dict,),
    "integer": (int,),
    "number": (int, float),
    "boolean": (bool,),
    "string": (str,),
}


def _violations(schema: dict[str, Any], value: Any, path: str = "$") -> list[str]:
    """The few keywords type_schema uses, checked by hand (no jsonschema dependency for one test)."""
    kind = schema["type"]
    if kind == "array":
        if not isinstance(value, list):
            return [f"{path}: not array"]
        out = [f"{path}: too few items"] if len(value) < schema.get("minItems", 0) else []
        out += [f"{path}: too many items"] if len(value) > schema["maxItems"] else []
        return out + [
            v for i, item in enumerate(value) for v in _violations(schema["items"], item, f"{path}[{i}]")
        ]
    if not isinstance(value, _JSON_TYPES[kind]) or (kind != "boolean" and isinstance(value, bool)):
        return [f"{path}: not {kind}"]
    if kind == "object":
        extra = [f"{path}.{k}: not allowed" for k in value if k not in schema["properties"]]
        nested = [
            _violations(schema["properties"][k], v, f"{path}.{k}")
            for k, v in value.items()
            if k in schema["properties"]
        ]
        return extra + [v for vs in nested for v in vs]
    out = []
    if "minimum" in schema and value < schema["minimum"]:
        out.append(f"{path}: below minimum")
    if "maximum" in schema and value > schema["maximum"]:
        out.append(f"{path}: above maximum")
    if "maxLength" in schema and len(value) > schema["maxLength"]:
        out.append(f"{path}: too long")
    return out


def test_type_schema_vector3_has_three_float_properties_with_zero_defaults() -> None:
    schema = type_schema(Vector3)
    assert schema["$schema"] == JSON_SCHEMA_DIALECT
    assert (schema["title"], schema["type"], schema["additionalProperties"]) == (
        "geometry_msgs/msg/Vector3",
        "object",
        False,
    )
    assert schema["properties"] == {
        axis: {"type": "number", "description": "float64", "default": 0.0} for axis in "xyz"
    }
    assert schema["default"] == {"x": 0.0, "y": 0.0, "z": 0.0}


def test_type_schema_key_code_is_uint16_range_and_header_is_a_nested_object() -> None:
    props = type_schema(Key)["properties"]
    code = props["code"]
    assert (code["type"], code["minimum"], code["maximum"], code["default"]) == ("integer", 0, 65535, 0)
    header = props["header"]
    assert (header["title"], header["type"]) == ("std_msgs/msg/Header", "object")
    assert header["additionalProperties"] is False
    assert header["properties"]["stamp"]["properties"]["nanosec"]["maximum"] == 2**32 - 1


def test_type_schema_every_primitive_kind_maps_to_its_json_type_and_range() -> None:
    every = define_message(
        parse_message(
            "test_msgs/msg/Every", "bool flag true\nint8 small -1\nfloat32 ratio 0.5\nstring label 'x'\n"
        )
    )
    props = type_schema(every)["properties"]
    assert props["flag"] == {"type": "boolean", "description": "bool", "default": True}
    assert (props["small"]["minimum"], props["small"]["maximum"]) == (-128, 127)
    assert props["ratio"]["type"] == "number"
    assert props["ratio"]["maximum"] == pytest.approx(3.4028234663852886e38)
    assert props["label"] == {"type": "string", "maxLength": 65536, "description": "string", "default": "x"}


@pytest.mark.parametrize("name", type_names())
def test_type_schema_every_registered_type_accepts_its_default_message(name: str) -> None:
    msg_type = get_type(name)
    schema = type_schema(msg_type)
    default = msg_type().to_dict()
    assert schema["default"] == default
    assert _violations(schema, default) == []


def test_type_schema_checker_itself_rejects_out_of_range_and_unknown_fields() -> None:
    schema = type_schema(Key)
    found = _violations(schema, {"code": 70000, "extra": 1})
    assert found == ["$.extra: not allowed", "$.code: above maximum"]


def test_type_schema_arrays_carry_their_sizes_and_bounds() -> None:
    props = type_schema(Imu)["properties"]
    cov = props["orientation_covariance"]
    assert (cov["type"], cov["minItems"], cov["maxItems"], cov["items"]["type"]) == ("array", 9, 9, "number")
    bounded = define_message(parse_message("test_msgs/msg/Bounded", "int32[<=3] few\nstring<=4 tag\n"))
    props = type_schema(bounded)["properties"]
    assert (props["few"]["maxItems"], props["few"].get("minItems")) == (3, None)
    assert props["tag"]["maxLength"] == 4
    assert _violations(type_schema(bounded), {"few": [1, 2, 3, 4], "tag": "abcde"}) == [
        "$.few: too many items",
        "$.tag: too long",
    ]


def test_interface_text_nests_each_used_type_one_tab_in_as_ros2_interface_show() -> None:
    text = interface_text("geometry_msgs/msg/PoseStamped")
    lines = text.splitlines()
    assert "std_msgs/Header header" in lines
    assert "\tbuiltin_interfaces/Time stamp" in lines
    assert "\t\tint32 sec" in lines
    assert lines.index("Pose pose") < lines.index("\tPoint position") < lines.index("\t\tfloat64 x")


def test_interface_text_service_shows_request_separator_response() -> None:
    assert interface_text("example_interfaces/srv/AddTwoInts").splitlines() == [
        "int64 a",
        "int64 b",
        "---",
        "int64 sum",
    ]
