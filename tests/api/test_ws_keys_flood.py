"""A key channel that floods: over the lab's key-frame budget its keydowns are dropped (with one
error frame a second), while keyups and release_all always go through, so no key sticks. The lab
runs on a manual clock that stands still, so the budget does not refill during the test."""

from __future__ import annotations

from fastapi.testclient import TestClient
from labclient import receive_json_within, rocket_settings, wait_until

from node_runtime.bus import ManualClock
from server.app import create_app

BURST = 3
LETTERS = "bcdefg"  # keys no lab node reacts to


def test_keydowns_over_the_budget_are_dropped_and_keyups_never_are() -> None:
    settings = rocket_settings(key_frames_hz=1.0, key_frames_burst=BURST)
    with TestClient(create_app(settings, ManualClock(0.0))) as client:
        lab = client.app.state.lab  # type: ignore[attr-defined]
        with client.websocket_connect("/ws/keys") as ws:
            for key in LETTERS:
                ws.send_json({"type": "keydown", "key": key})
            error = receive_json_within(ws)
            assert error["type"] == "error" and "too many key frames" in error["error"]
            wait_until(lambda: len(lab.keyboard.held()) == BURST, f"the first {BURST} keys held")
            assert {chr(code) for code in lab.keyboard.held()} == set(LETTERS[:BURST])
            for key in LETTERS:
                ws.send_json({"type": "keyup", "key": key})
            wait_until(lambda: lab.keyboard.held() == set(), "every key released")
            ws.send_json({"type": "keydown", "key": "h"})  # still over budget: dropped too
            ws.send_json({"type": "release_all"})
            ws.send_json({"type": "heartbeat"})
        assert lab.keyboard.held() == set()
        assert lab.bus.topics["/keydown"].publish_count == BURST
