"""The key channel wires the dead-man: keys held by a silent /ws/keys channel are released by the
server. The timing itself is tested on a ManualClock in tests/devices/test_deadman.py; this one
checks, through the real app, that a channel is watched while open and forgotten when closed."""

from __future__ import annotations

import json
from typing import Any

from fastapi.testclient import TestClient
from labclient import rocket_settings, wait_until

from node_runtime.msgs import Key
from server.app import create_app

SETTINGS = rocket_settings(deadman_s=0.3)


def keyups(lab: Any) -> int:
    return int(lab.bus.topics["/keyup"].publish_count)


def test_silent_channel_with_key_held_gets_keyup_from_server_and_leaves_no_timer() -> None:
    with TestClient(create_app(SETTINGS)) as client:
        lab = client.app.state.lab  # type: ignore[attr-defined]
        with client.websocket_connect("/ws/keys") as ws:
            ws.send_text(json.dumps({"type": "keydown", "key": "ArrowRight"}))
            wait_until(lambda: lab.keyboard.held() == {Key.KEY_RIGHT}, "the key held")
            assert len(lab.key_deadman.watched) == 1
            wait_until(lambda: keyups(lab) == 1, "the server's release of the silent channel's key")
            assert lab.bus.topics["/keyup"].latest.code == Key.KEY_RIGHT
            assert lab.keyboard.held() == set()
        wait_until(lambda: not lab.key_deadman.watched, "the closed channel forgotten")
        assert "/_key_deadman" not in {n.fully_qualified_name for n in lab.bus.nodes}
