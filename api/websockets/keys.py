"""WebSocket key channel: ``/ws/keys`` turns browser key events into keyboard_msgs/Key messages.

Frames: ``{"type": "keydown"|"keyup", "key": <KeyboardEvent.key>}`` with optional ``code`` and
``location`` (as the browser reports them), ``repeat``, and modifier flags (``shift``, ``ctrl``,
``alt``, ``meta``, or sided: ``lshift``, ``rshift`` ...). ``{"type": "release_all"}`` releases
every key this connection holds (the page sends it on blur); ``{"type": "heartbeat"}`` keeps the
channel alive: if it is silent for ``deadman_s`` (500 ms) while keys are held, the server
releases them itself (server/peripherals/devices/deadman.py, on the bus's clock). Garbage, including JSON
nested deeper than a frame needs, closes the channel with a named code; an unknown key only
gets an error frame. When the channel closes, its held keys are released.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

from fastapi import APIRouter, WebSocket, WebSocketDisconnect

from api.deps import WsLabDep
from api.errors import CloseCode, close_reason
from api.protocol.frames import KeyChannelError, KeyFrame
from api.protocol.json_codec import JsonRejected, loads
from api.websockets.life import closed_when_lab_stops
from server.peripherals.devices.keymap import MODIFIER_FLAG_NAMES, UnknownKeyError, modifier_bits, sdl_code

router = APIRouter(tags=["websockets"])
FRAME_MAX_DEPTH = 2  # a frame is one flat object
_ids = itertools.count(1)
FRAME_FIELDS = KeyFrame.__required_keys__ | KeyFrame.__optional_keys__
MAX_KEY_CHARS = 32
FLOOD_ERROR = "too many key frames: at most {:g} keydowns a second; keydowns dropped"


class BadFrame(ValueError):
    """A frame that is not a key-channel frame at all."""


def parse_frame(text: str) -> dict[str, Any]:
    try:
        frame = loads(text, max_depth=FRAME_MAX_DEPTH)
    except JsonRejected as exc:
        raise BadFrame(str(exc)) from None
    if not isinstance(frame, dict):
        raise BadFrame("a frame must be a JSON object")
    unknown = set(frame) - FRAME_FIELDS
    if unknown:
        raise BadFrame(f"unknown field(s): {', '.join(sorted(unknown))}")
    kind = frame.get("type")
    if kind not in ("keydown", "keyup", "release_all", "heartbeat"):
        raise BadFrame(f"type must be keydown, keyup, release_all or heartbeat, got {kind!r}")
    if kind in ("keydown", "keyup"):
        key = frame.get("key")
        if not isinstance(key, str) or not 0 < len(key) <= MAX_KEY_CHARS:
            raise BadFrame("key must be a KeyboardEvent.key string")
        if not isinstance(frame.get("code", ""), str):
            raise BadFrame("code must be a KeyboardEvent.code string")
        location = frame.get("location", 0)
        if isinstance(location, bool) or not isinstance(location, int) or not 0 <= location <= 3:
            raise BadFrame("location must be 0, 1, 2 or 3")
    return frame


@router.websocket("/ws/keys")
async def keys(websocket: WebSocket, lab: WsLabDep) -> None:
    await websocket.accept()
    source = f"ws-keys-{next(_ids)}"
    lab.key_deadman.watch(source)
    try:
        async with closed_when_lab_stops(websocket, lab):
            await _key_loop(websocket, lab, source)
    except WebSocketDisconnect:
        return
    except RuntimeError:
        if not lab.stopped.is_set():  # a send racing the lab's stop finds the socket closed: fine
            raise
    finally:
        lab.key_deadman.unwatch(source)
        lab.keyboard.release_all(source)


async def _key_loop(websocket: WebSocket, lab: Any, source: str) -> None:
    """Frames until the client leaves or must be closed (then closed here, with a named code)."""
    limit = lab.settings.listen.max_ws_frame_bytes
    last_flood_notice = -math.inf
    while True:
        message = await websocket.receive()
        lab.key_deadman.feed(source)
        if message["type"] == "websocket.disconnect":
            return
        text = message.get("text")
        if text is None:
            await websocket.close(CloseCode.UNSUPPORTED_DATA, "the key channel takes JSON text frames")
            return
        if len(text) > limit:
            await websocket.close(CloseCode.MESSAGE_TOO_BIG, f"frame larger than {limit} bytes")
            return
        try:
            frame = parse_frame(text)
        except BadFrame as exc:
            await websocket.close(CloseCode.INVALID_PAYLOAD, close_reason(str(exc)))
            return
        if frame["type"] == "keydown" and not lab.key_frames.take():
            # A flood: drop the keydown (a keyup or release_all always goes through, so no key
            # sticks) and say so at most once a second.
            now = lab.bus.clock.now()
            if now - last_flood_notice >= 1.0:
                last_flood_notice = now
                flood: KeyChannelError = {
                    "type": "error",
                    "error": FLOOD_ERROR.format(lab.settings.limits.key_frames_hz),
                }
                await websocket.send_json(flood)
            continue
        error = handle_frame(lab, source, frame)
        if error is not None:
            refused: KeyChannelError = {"type": "error", "error": error}
            await websocket.send_json(refused)


def handle_frame(lab: Any, source: str, frame: dict[str, Any]) -> str | None:
    """Apply one valid frame; returns an error for the client, or None."""
    kind = frame["type"]
    if kind == "heartbeat":
        return None
    if kind == "release_all":
        lab.keyboard.release_all(source)
        return None
    try:
        code = sdl_code(frame["key"], frame.get("code"), frame.get("location"))
        mods = modifier_bits({k: v for k, v in frame.items() if k in MODIFIER_FLAG_NAMES})
    except (UnknownKeyError, ValueError) as exc:
        return str(exc)
    if kind == "keydown":
        lab.keyboard.key_down(code, mods, source)
    else:
        lab.keyboard.key_up(code, mods, source)
    return None
