"""``type_schema``: every message type as a draft 2020-12 JSON Schema that its defaults satisfy."""

from __future__ import annotations

from typing import Any

import pytest

from server.introspection import JSON_SCHEMA_DIALECT, type_schema
from server.msgs import Key, Vector3, get_type, type_names
from server.msgs._base import Field, define

_JSON_TYPES: dict[str, Any] = {
    "object": (dict,), "integer": (int,), "number": (int, float), "boolean": (bool,), "string": (str,),
}  # fmt: skip


def _violations(schema: dict[str, Any], value: Any, path: str = "$") -> list[str]:
    """The few keywords type_schema uses, checked by hand (no jsonschema dependency for one test)."""
    kind = schema["type"]
    if not isinstance(value, _JSON_TYPES[kind]) or (kind != "boolean" and isinstance(value, bool)):
        return [f"{path}: not {kind}"]
    if kind == "object":
        extra = [f"{path}.{k}: not allowed" for k in value if k not in schema["properties"]]
        nested = [_violations(schema["properties"][k], v, f"{path}.{k}") for k, v in value.items()
                  if k in schema["properties"]]  # fmt: skip
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
        "geometry_msgs/msg/Vector3", "object", False,
    )  # fmt: skip
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
    every = define("test_msgs/msg/Every", [
        Field("flag", "bool", True), Field("small", "int8", -1), Field("ratio", "float32", 0.5),
        Field("label", "string", "x"),
    ])  # fmt: skip
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
