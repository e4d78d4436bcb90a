"""The page's TypeScript types are generated from the Python declarations of what the page and
the server exchange, and are current with them; the server's answers keep to those declarations."""

from __future__ import annotations

import json
from typing import Any

import pytest
from labclient import LabClient, receive_json_within
from pydantic import TypeAdapter

from api.protocol.ts_types import UnsupportedSchema, declaration, ts_type
from api.typescript import OUTPUT, generated_text
from api.websockets.echo import EchoFrame
from api.websockets.keys import FRAME_FIELDS, KeyFrame, parse_frame
from server.peripherals.devices.keymap import MODIFIER_FLAG_NAMES
from server.peripherals.viewer.views import FollowJson, PageViews, ViewJson


def test_generated_page_types_match_the_declarations() -> None:
    assert OUTPUT.read_text(encoding="utf-8") == generated_text(), (
        f"{OUTPUT.name} is stale: run `python -m api.typescript` after changing a declaration it lists"
    )


def test_ts_types_object_with_nullable_tuple_map_literal_and_reference() -> None:
    schema = {
        "type": "object",
        "properties": {
            "name": {"type": "string", "description": "a  name\n over lines"},
            "at": {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3},
            "tags": {"type": "object", "additionalProperties": {"type": "integer"}},
            "kind": {"enum": ["a", "b"]},
            "next": {"anyOf": [{"$ref": "#/$defs/Other"}, {"type": "null"}]},
            "items": {"type": "array", "items": {"anyOf": [{"type": "string"}, {"type": "null"}]}},
            "any": {},
        },
        "required": ["name", "at"],
    }

    text = declaration("Thing", schema)

    assert text == (
        "export interface Thing {\n"
        "  /** a name over lines */\n"
        "  name: string;\n"
        "  at: [number, number, number];\n"
        "  tags?: Record<string, number>;\n"
        '  kind?: "a" | "b";\n'
        "  next?: Other | null;\n"
        "  items?: (string | null)[];\n"
        "  any?: unknown;\n"
        "}\n"
    )


def test_ts_types_message_form_makes_every_field_present() -> None:
    schema = {"type": "object", "properties": {"x": {"type": "number"}}}
    assert ts_type(schema) == "{\n  x?: number;\n}"
    assert ts_type(schema, required_all=True) == "{\n  x: number;\n}"


@pytest.mark.parametrize("schema", [{"$ref": "https://example.org/x"}, {"type": "frobnicate"}])
def test_ts_types_unknown_construct_is_refused_by_name(schema: dict[str, Any]) -> None:
    with pytest.raises(UnsupportedSchema):
        ts_type(schema)


def test_key_frame_declares_every_field_the_server_takes() -> None:
    """The page's frame type and the server's check are one list: each modifier flag the server
    reads is declared, and a frame with every declared field passes the check."""
    assert set(MODIFIER_FLAG_NAMES) <= FRAME_FIELDS
    assert KeyFrame.__required_keys__ | KeyFrame.__optional_keys__ == FRAME_FIELDS
    full = {"type": "keydown", "key": "a", "code": "KeyA", "location": 0, "repeat": False, "t": 1.5}
    full |= dict.fromkeys(sorted(FRAME_FIELDS - set(full)), False)

    assert parse_frame(json.dumps(full)) == full


def test_echo_frame_from_the_server_has_the_declared_fields(counting_lab: LabClient) -> None:
    with counting_lab.http.websocket_connect("/ws/topics/countdown") as ws:
        frame = receive_json_within(ws)

    assert TypeAdapter(EchoFrame).validate_python(frame) == frame  # every required field, typed
    assert set(frame) <= set(EchoFrame.__annotations__)
    assert frame["topic"] == "/countdown" and frame["type"] == "std_msgs/msg/Int64"


def test_page_views_answer_has_the_declared_fields(make_lab: Any) -> None:
    lab: LabClient = make_lab(viewer=True)

    answer = lab.http.get("/page/views").json()

    assert set(answer) == set(PageViews.__annotations__)
    assert answer["views"], "a lab with a viewer has camera views"
    for view in answer["views"]:
        assert set(view) == set(ViewJson.__annotations__)
        if view["follow"] is not None:
            assert set(view["follow"]) == set(FollowJson.__annotations__)
