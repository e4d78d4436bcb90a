"""The page's TypeScript types are generated from the Python declarations of what the page and
the server exchange, and are current with them; the server's answers keep to those declarations."""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path
from typing import Any

import pytest
from labclient import LabClient, receive_json_within
from pydantic import TypeAdapter

import api.typescript
from api.protocol.frames import EchoFrame, KeyFrame
from api.protocol.page import FollowJson, PageViews, ViewJson
from api.protocol.ts_types import UnsupportedSchema, declaration, ts_type
from api.typescript import OUTPUT, generated_text
from api.websockets.keys import FRAME_FIELDS, parse_frame
from server.peripherals.devices.keymap import MODIFIER_FLAG_NAMES

# ``interface X``, ``type X =`` or ``type X<T> =``, exported or not, at a line's start or after a
# ``declare`` / ``export``: every way a TypeScript file names a shape of its own.
TS_DECLARATION = re.compile(
    r"^[ \t]*(?:export[ \t]+)?(?:declare[ \t]+)?(?:interface[ \t]+([A-Za-z_$][\w$]*)"
    r"|type[ \t]+([A-Za-z_$][\w$]*)[ \t]*(?:<[^=\n]*>)?[ \t]*=)",
    re.MULTILINE,
)
PAGE_SOURCES = OUTPUT.parent


def ts_declarations(text: str) -> set[str]:
    """The names a TypeScript source declares as an interface or a type alias."""
    return {interface or alias for interface, alias in TS_DECLARATION.findall(text)}


def test_generated_page_types_match_the_declarations() -> None:
    assert OUTPUT.read_text(encoding="utf-8") == generated_text(), (
        f"{OUTPUT.name} is stale: run `python -m api.typescript` after changing a declaration it lists"
    )


def test_the_page_declares_no_shape_the_protocol_declares() -> None:
    """Every shape the page and the server exchange is written once, in Python: a page module
    that declared one of the generated names would be a second copy, free to drift."""
    generated = ts_declarations(OUTPUT.read_text(encoding="utf-8"))
    assert {"OutputFrame", "WorkspaceTree", "Checkpoints"} <= generated
    twice = {
        str(path.relative_to(PAGE_SOURCES)): sorted(
            ts_declarations(path.read_text(encoding="utf-8")) & generated
        )
        for path in sorted(PAGE_SOURCES.rglob("*.ts"))
        if path != OUTPUT
    }

    assert {path: names for path, names in twice.items() if names} == {}


def test_ts_declarations_finds_interfaces_and_aliases_however_written() -> None:
    source = (
        "interface A { x: number }\n"
        "export interface B<T> extends A { y: T }\n"
        "  export type C = A | B<string>;\n"
        "type D<T extends A> = T[];\n"
        "export declare interface E {}\n"
        "import type { F } from './f';\n"
        "export type { G } from './g';\n"
        "const typeH = 1; // type H = 2 is a comment's\n"
    )

    assert ts_declarations(source) == {"A", "B", "C", "D", "E"}


def test_the_typescript_writer_reads_the_protocol_only() -> None:
    """The page's types come from api/protocol/, never from a route module: a route's shapes live
    in the protocol, where the OpenAPI document and the page both take them."""
    tree = ast.parse(Path(api.typescript.__file__).read_text(encoding="utf-8"))
    modules = {node.module or "" for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    modules |= {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names}

    assert sorted(m for m in modules if m.startswith("api") and not m.startswith("api.protocol")) == []


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
