"""The page: viser's own client with the key script injected, and the WebSocket proxy to viser."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from pathlib import Path

import pytest
import viser
import websockets
from labclient import LabClient, receive_within, refused, wait_until
from starlette.testclient import WebSocketTestSession
from support.http import HTTP

from api.routes.page import PROXY_MAX_FRAME_BYTES
from server.peripherals.viewer.viser_guard import PROXY_TOKEN_HEADER


def test_index_serves_viser_page_with_key_script_injected(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(viewer=True)

    response = lab.http.get("/")

    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    html = response.text
    head, _, body = html.partition("</head>")
    assert '<script src="/static/build/lab.js"></script>' in head
    assert '<div id="root"></div>' in body  # viser's client mounts here
    assert "<title>Teleop lab" in head and "<title>Viser" not in head  # the tab is titled after the lab
    script = lab.http.get("/static/build/lab.js")
    assert script.status_code == 200
    assert "/ws/keys" in script.text and "window.__teleop" in script.text


def test_index_and_pose_worker_are_cross_origin_isolated(make_lab: Callable[..., LabClient]) -> None:
    """The page shares a ring of poses with its worker: that takes both headers, on both."""
    lab = make_lab(viewer=True)

    page, worker = lab.http.get("/"), lab.http.get("/page/poses.worker.js")

    assert worker.status_code == 200
    assert worker.headers["content-type"].startswith("text/javascript")
    assert "SharedArrayBuffer" in lab.http.get("/static/build/lab.js").text
    for response in (page, worker):
        assert response.headers["cross-origin-opener-policy"] == "same-origin"
        assert response.headers["cross-origin-embedder-policy"] == "require-corp"


def test_pose_worker_not_built_is_404_naming_the_set_up(
    make_lab: Callable[..., LabClient], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    lab = make_lab(viewer=True)
    assert lab.http.get("/page/poses.worker.js").status_code == 200  # built at set-up
    monkeypatch.setattr("api.routes.page.POSES_WORKER", tmp_path / "poses.worker.js")

    response = lab.http.get("/page/poses.worker.js")

    assert response.status_code == 404 and "scripts/run.sh" in response.text


def test_viser_proxy_with_viser_subprotocol_receives_scene(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(viewer=True)
    subprotocol = f"viser-v{viser.__version__}"

    with lab.http.websocket_connect("/", subprotocols=[subprotocol]) as ws:
        first = receive_within(ws)

    assert ws.accepted_subprotocol == subprotocol
    assert first["type"] == "websocket.send"
    assert first.get("bytes")  # viser's msgpack messages


def test_viser_proxy_without_viewer_refused_try_again_later(rocket_lab: LabClient) -> None:
    refusal = refused(rocket_lab.http, "/", subprotocols=[f"viser-v{viser.__version__}"])

    assert refusal.code == 1013  # TRY_AGAIN_LATER
    assert "not running" in refusal.reason


def _close_after_scene(ws: WebSocketTestSession, max_messages: int = 10_000) -> tuple[int, str]:
    """Skip viser's scene messages until the close; (code, reason)."""
    for _ in range(max_messages):
        message = receive_within(ws)
        if message["type"] == "websocket.close":
            return int(message.get("code", 1000)), str(message.get("reason", ""))
    raise AssertionError(f"no close within {max_messages} messages")


def test_viser_proxy_wrong_subprotocol_closed_with_viser_reason(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(viewer=True)

    with lab.http.websocket_connect("/", subprotocols=["viser-v0.0.1"]) as ws:
        code, reason = _close_after_scene(ws)

    assert code == 1002  # viser's own: protocol error
    assert "Version mismatch" in reason
    assert lab.healthy()


def test_viser_proxy_oversized_frame_closed_1009(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(viewer=True)

    with lab.http.websocket_connect("/", subprotocols=[f"viser-v{viser.__version__}"]) as ws:
        ws.send_bytes(b"\x00" * (PROXY_MAX_FRAME_BYTES + 1))
        code, reason = _close_after_scene(ws)

    assert code == 1009
    assert f"larger than {PROXY_MAX_FRAME_BYTES} bytes" in reason
    assert lab.healthy()


def test_page_views_all_launch_opens_on_rocket_until_it_is_aborted_then_on_quadrotor(
    make_lab: Callable[..., LabClient],
) -> None:
    lab = make_lab(viewer=True, launch="all")

    before = lab.http.get("/page/views")
    lab.publish("/abort_takeoff", {"data": True})
    after = wait_until(
        lambda: (r := lab.http.get("/page/views").json())["suggested"] == "Quadrotor" and r,
        "the suggested view to move on from the aborted rocket",
    )

    assert before.status_code == 200
    assert before.json()["suggested"] == "Rocket"  # counting down to a start an hour away: under way
    views = {v["name"]: v for v in after["views"]}
    assert set(views) == {"Rocket", "Quadrotor"}
    assert views["Rocket"]["follow"] is None
    follow = views["Quadrotor"]["follow"]
    assert follow["node"] == "/drone_lab/drone" and follow["setpoint"] == "/drone_lab/setpoint"


def test_page_views_without_viewer_lists_none(rocket_lab: LabClient) -> None:
    response = rocket_lab.http.get("/page/views")

    assert response.status_code == 200
    assert response.json() == {"views": [], "suggested": None}


def _direct_to_viser(port: int, **headers: str) -> int:
    """Open a WebSocket straight to viser's own port, as another page or program could; returns
    the HTTP status of the refusal (101 would be a connection)."""

    async def attempt() -> int:
        try:
            async with websockets.connect(
                f"ws://127.0.0.1:{port}",
                subprotocols=[websockets.Subprotocol(f"viser-v{viser.__version__}")],
                additional_headers=headers,
                open_timeout=5,
            ):
                return 101
        except websockets.exceptions.InvalidStatus as exc:
            return exc.response.status_code

    return asyncio.run(attempt())


def test_viser_port_direct_connection_with_foreign_origin_refused(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(viewer=True)
    display = lab.http.app.state.lab.display  # type: ignore[attr-defined]

    assert _direct_to_viser(display.port, Origin="http://evil.example") == 403
    assert _direct_to_viser(display.port) == 403, "no Origin but no secret either: still not the proxy"
    token = {PROXY_TOKEN_HEADER: display.proxy_token}
    assert _direct_to_viser(display.port, Origin="http://evil.example", **token) == 403, "a browser never"
    assert _direct_to_viser(display.port, **token) == 101, "the proxy's own request is admitted"


def test_viser_port_plain_http_refused(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(viewer=True)
    port = lab.http.app.state.lab.display.port  # type: ignore[attr-defined]

    response = HTTP.get(f"http://127.0.0.1:{port}/", timeout=5)

    assert response.status_code == 403
    assert "proxy" in response.text
