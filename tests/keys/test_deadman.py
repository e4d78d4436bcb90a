"""The key channel's dead-man: keys held by a silent channel are released by the server."""

from __future__ import annotations

import json
import time

from fastapi.testclient import TestClient

from server.app import create_app
from server.msgs import Key
from server.settings import Settings

SETTINGS = Settings(
    launch="rocket",
    launch_args={"start_delay": "3600"},
    viewer=False,
    allowed_hosts=("testserver",),
    deadman_s=0.3,
)


def wait_for(check, timeout_s: float = 5.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if check():
            return True
        time.sleep(0.02)
    return False


def keyups(lab) -> int:
    topic = lab.bus.topics["/keyup"]
    return topic.publish_count


def test_silent_channel_with_key_held_gets_keyup_from_server() -> None:
    with TestClient(create_app(SETTINGS)) as client:
        lab = client.app.state.lab
        with client.websocket_connect("/ws/keys") as ws:
            ws.send_text(json.dumps({"type": "keydown", "key": "ArrowRight"}))
            assert wait_for(lambda: lab.keyboard.held() == {Key.KEY_RIGHT})
            sent_at = time.monotonic()
            assert wait_for(lambda: keyups(lab) == 1), "the server released the silent channel's key"
            assert time.monotonic() - sent_at >= SETTINGS.deadman_s * 0.9
            assert lab.bus.topics["/keyup"].latest.code == Key.KEY_RIGHT
            assert lab.keyboard.held() == set()


def test_heartbeats_keep_a_held_key_held() -> None:
    with TestClient(create_app(SETTINGS)) as client:
        lab = client.app.state.lab
        with client.websocket_connect("/ws/keys") as ws:
            ws.send_text(json.dumps({"type": "keydown", "key": "a"}))
            end = time.monotonic() + 3 * SETTINGS.deadman_s
            while time.monotonic() < end:
                ws.send_text(json.dumps({"type": "heartbeat"}))
                time.sleep(SETTINGS.deadman_s / 4)
            assert lab.keyboard.held() == {Key.KEY_A}
            assert keyups(lab) == 0
            ws.send_text(json.dumps({"type": "keyup", "key": "a"}))
            assert wait_for(lambda: keyups(lab) == 1)


def test_release_all_frame_releases_every_held_key_once() -> None:
    with TestClient(create_app(SETTINGS)) as client:
        lab = client.app.state.lab
        with client.websocket_connect("/ws/keys") as ws:
            for key in ("ArrowUp", "ArrowLeft"):
                ws.send_text(json.dumps({"type": "keydown", "key": key}))
            ws.send_text(json.dumps({"type": "release_all"}))
            assert wait_for(lambda: keyups(lab) == 2)
            time.sleep(2 * SETTINGS.deadman_s)
            assert keyups(lab) == 2, "nothing left for the dead-man to release"
