"""/ws/keys: browser key events become keyboard_msgs/Key messages on /keydown and /keyup.

The frames are the ones web/src/lab/keys.ts sends. Garbage closes the channel with a named code;
an unknown key only gets an error frame; a channel that goes away releases its keys.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest
from labclient import LabClient, close_within, receive_json_within, wait_until

from api.errors import CloseCode

KEY_A = 97
ARROWS = [
    ("ArrowUp", "ArrowUp", 273),
    ("ArrowDown", "ArrowDown", 274),
    ("ArrowRight", "ArrowRight", 275),
    ("ArrowLeft", "ArrowLeft", 276),
]
LSHIFT, RSHIFT, LCTRL = 1, 2, 64  # keyboard_msgs/Key MODIFIER_* bits
FRAME_LIMIT = 16 * 1024  # Listening.max_ws_frame_bytes


def down(key: str, **extra: Any) -> dict[str, Any]:
    return {"type": "keydown", "key": key, **extra}


def up(key: str, **extra: Any) -> dict[str, Any]:
    return {"type": "keyup", "key": key, **extra}


def is_key(code: int, modifiers: int | None = None) -> Callable[[dict[str, Any]], bool]:
    return lambda m: m["code"] == code and (modifiers is None or m["modifiers"] == modifiers)


def test_keydown_a_publishes_key_97_then_abort_takeoff_true(rocket_lab: LabClient) -> None:
    with rocket_lab.http.websocket_connect("/ws/keys") as ws:
        ws.send_json(down("a", code="KeyA", location=0))
        key = rocket_lab.wait_latest("/keydown", is_key(KEY_A), "carries 'a'")
        rocket_lab.wait_latest("/abort_takeoff", lambda m: m["data"] is True, "is true")

    assert key["modifiers"] == 0
    assert set(key["header"]["stamp"]) == {"sec", "nanosec"}


def test_arrow_keys_publish_sdl_codes_273_to_276(rocket_lab: LabClient) -> None:
    with rocket_lab.http.websocket_connect("/ws/keys") as ws:
        for key, code_name, sdl in ARROWS:
            ws.send_json(down(key, code=code_name))
            rocket_lab.wait_latest("/keydown", is_key(sdl), f"carries {key}")
            ws.send_json(up(key, code=code_name))
            rocket_lab.wait_latest("/keyup", is_key(sdl), f"carries {key}")

    assert rocket_lab.publish_count("/keydown") == 4
    assert rocket_lab.publish_count("/keyup") == 4


@pytest.mark.parametrize(
    ("frame", "code", "modifiers"),
    [
        (down("A", code="KeyA", shift=True), KEY_A, LSHIFT),
        (down("A", code="KeyA", lshift=False, rshift=True), KEY_A, RSHIFT),
        (down("A", code="KeyA", ctrl=True, shift=True), KEY_A, LSHIFT | LCTRL),
        (down("Shift", code="ShiftLeft", location=1, lshift=True), 304, LSHIFT),
        (down("Shift", code="ShiftRight", location=2, rshift=True), 303, RSHIFT),
    ],
    ids=["shift-A", "rshift-A", "ctrl-shift-A", "left-shift-key", "right-shift-key"],
)
def test_shift_flags_set_modifier_bits(
    rocket_lab: LabClient, frame: dict[str, Any], code: int, modifiers: int
) -> None:
    with rocket_lab.http.websocket_connect("/ws/keys") as ws:
        ws.send_json(frame)
        rocket_lab.wait_latest(
            "/keydown", is_key(code, modifiers), f"carries {code} with modifiers {modifiers}"
        )


def test_keydown_held_key_again_is_not_republished(rocket_lab: LabClient) -> None:
    with rocket_lab.http.websocket_connect("/ws/keys") as ws:
        ws.send_json(down("ArrowUp"))
        ws.send_json(down("ArrowUp", repeat=True))  # the OS's auto-repeat
        ws.send_json(down("ArrowDown"))
        rocket_lab.wait_latest("/keydown", is_key(274), "carries ArrowDown")

    assert rocket_lab.publish_count("/keydown") == 2


def test_release_all_frame_releases_every_held_key(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(deadman_s=60.0)  # only the frame may release them
    with lab.http.websocket_connect("/ws/keys") as ws:
        ws.send_json(down("a"))
        ws.send_json(down("ArrowUp"))
        lab.wait_latest("/keydown", is_key(273), "carries ArrowUp")
        ws.send_json({"type": "release_all"})
        wait_until(lambda: lab.publish_count("/keyup") == 2, "two keyups")


def test_disconnect_while_holding_key_publishes_keyup(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(deadman_s=60.0)  # so the keyup can only come from the disconnect
    with lab.http.websocket_connect("/ws/keys") as ws:
        ws.send_json(down("ArrowLeft"))
        lab.wait_latest("/keydown", is_key(276), "carries ArrowLeft")
        assert lab.publish_count("/keyup") == 0

    lab.wait_latest("/keyup", is_key(276), "carries the released ArrowLeft")


def test_silent_channel_holding_key_gets_it_released(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(deadman_s=0.2)
    with lab.http.websocket_connect("/ws/keys") as ws:
        ws.send_json(down("ArrowRight"))
        lab.wait_latest("/keydown", is_key(275), "carries ArrowRight")
        lab.wait_latest("/keyup", is_key(275), "released by the dead man while the channel is open")
        ws.send_json(down("a"))  # the channel itself stays usable
        lab.wait_latest("/keydown", is_key(KEY_A), "carries 'a'")


@pytest.mark.parametrize(
    ("frame", "error_names"),
    [
        (down("Unidentified"), "unknown key 'Unidentified'"),
        (down("😀"), "unknown key"),
        (down("a", shift="yes"), "modifier flag 'shift'"),
    ],
    ids=["unidentified", "emoji", "flag-not-bool"],
)
def test_unknown_key_gets_error_frame_and_channel_stays_open(
    rocket_lab: LabClient, frame: dict[str, Any], error_names: str
) -> None:
    with rocket_lab.http.websocket_connect("/ws/keys") as ws:
        ws.send_json(frame)
        error = receive_json_within(ws)
        assert rocket_lab.publish_count("/keydown") == 0
        ws.send_json(down("a"))
        rocket_lab.wait_latest("/keydown", is_key(KEY_A), "carries 'a' after the error")

    assert error["type"] == "error"
    assert error_names in error["error"]


@pytest.mark.parametrize(
    ("message", "code", "reason_names"),
    [
        ({"text": '{"type": "keydown", "key": '}, CloseCode.INVALID_PAYLOAD, "malformed JSON"),
        ({"text": '["keydown", "a"]'}, CloseCode.INVALID_PAYLOAD, "JSON object"),
        ({"text": '{"type": "keypress", "key": "a"}'}, CloseCode.INVALID_PAYLOAD, "type must be"),
        ({"text": '{"type": "keydown"}'}, CloseCode.INVALID_PAYLOAD, "key must be"),
        ({"text": '{"type": "keydown", "key": "a", "location": 7}'}, CloseCode.INVALID_PAYLOAD, "location"),
        ({"text": '{"type": "keydown", "key": "a", "pressure": 1}'}, CloseCode.INVALID_PAYLOAD, "pressure"),
        ({"bytes": b'{"type": "keydown", "key": "a"}'}, CloseCode.UNSUPPORTED_DATA, "text frames"),
        ({"text": "x" * (FRAME_LIMIT + 1)}, CloseCode.MESSAGE_TOO_BIG, f"larger than {FRAME_LIMIT} bytes"),
    ],
    ids=[
        "malformed-json",
        "not-an-object",
        "unknown-type",
        "no-key",
        "bad-location",
        "unknown-field",
        "binary",
        "oversized",
    ],
)
def test_garbage_frame_closes_with_named_code_and_publishes_nothing(
    rocket_lab: LabClient, message: dict[str, Any], code: CloseCode, reason_names: str
) -> None:
    with rocket_lab.http.websocket_connect("/ws/keys") as ws:
        ws.send({"type": "websocket.receive", **message})
        closed = close_within(ws)

    assert closed[0] == code
    assert reason_names in closed[1]
    assert rocket_lab.publish_count("/keydown") == 0
    assert rocket_lab.healthy()
