"""The /rosbridge WebSocket through the real app: named close codes for what is not rosbridge,
and the app's Origin and Host rules on both ways in (the app's port and rosbridge's own)."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator

import pytest
import websockets
from fastapi.testclient import TestClient
from handshake import READ_S, handshake_refusal
from starlette.websockets import WebSocketDisconnect
from support.ws import refusal
from websockets.exceptions import ConnectionClosed

from api.errors import CloseCode
from api.websockets.rosbridge import MAX_FRAME_BYTES
from server.app import create_app
from server.host.settings import LabSettings, Listening, Settings

from .conftest import RosbridgeServer


@pytest.fixture
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="rocket",
            launch_args={"start_delay": "3600"},
            viewer=False,
            bag_dir=tmp_path_factory.mktemp("bags"),
        ),
    )
    with TestClient(create_app(settings)) as client:
        yield client


@pytest.mark.parametrize(
    ("send", "code"),
    [
        (lambda ws: ws.send_bytes(b"\x00\x01"), CloseCode.UNSUPPORTED_DATA),
        (lambda ws: ws.send_text("{not json"), CloseCode.INVALID_PAYLOAD),
        (lambda ws: ws.send_text("[1, 2]"), CloseCode.INVALID_PAYLOAD),
        (
            lambda ws: ws.send_text('{"op": "publish", "pad": "' + "x" * MAX_FRAME_BYTES + '"}'),
            CloseCode.MESSAGE_TOO_BIG,
        ),
    ],
)
def test_what_is_not_rosbridge_closes_with_a_named_code(lab: TestClient, send: object, code: int) -> None:
    nodes = len(lab.app.state.lab.bus.nodes)  # type: ignore[attr-defined]
    with lab.websocket_connect("/rosbridge") as ws:
        send(ws)  # type: ignore[operator]
        with pytest.raises(WebSocketDisconnect) as closed:
            ws.receive_text()
    assert closed.value.code == code and closed.value.reason
    assert len(lab.app.state.lab.bus.nodes) == nodes  # type: ignore[attr-defined]  # its node is gone


def test_rosapi_over_the_endpoint(lab: TestClient) -> None:
    with lab.websocket_connect("/rosbridge") as ws:
        ws.send_json({"op": "call_service", "id": "c1", "service": "/rosapi/nodes", "type": "rosapi/Nodes"})
        reply = ws.receive_json()
        ws.send_json({"op": "call_service", "id": "c2", "service": "rosapi/get_time"})
        time_reply = ws.receive_json()
    assert reply["id"] == "c1" and reply["result"] is True
    assert {"/CountDownNode", "/MainControllerNode", "/KeyboardManager"} <= set(reply["values"]["nodes"])
    assert not any(n.split("/")[-1].startswith("_") for n in reply["values"]["nodes"])
    assert time_reply["values"]["time"]["sec"] > 1_600_000_000


def test_a_foreign_origin_is_refused_at_the_handshake(lab: TestClient) -> None:
    refused = refusal(lab, "/rosbridge", headers={"origin": "http://evil.example"})
    assert refused.code == CloseCode.FORBIDDEN and "cross-site" in refused.reason


@pytest.mark.parametrize("way", ["app", "port"])
def test_live_server_refuses_a_foreign_origin_on_both_ports(
    rosbridge_server: RosbridgeServer, way: str
) -> None:
    async def attempt() -> int | None:
        async with websockets.connect(rosbridge_server.urls[way], origin="http://evil.example") as ws:
            with pytest.raises(ConnectionClosed) as caught:
                await asyncio.wait_for(ws.recv(), READ_S)
        return caught.value.rcvd.code if caught.value.rcvd is not None else None

    assert asyncio.run(attempt()) == CloseCode.FORBIDDEN


@pytest.mark.parametrize(
    ("headers", "app_status", "port_status"),
    [
        ((("Host", "evil.example"),), CloseCode.MISDIRECTED, CloseCode.MISDIRECTED),  # a DNS-rebinding page
        (
            (("Host", "127.0.0.1"), ("Origin", "http://127.0.0.1"), ("Origin", "http://evil.example")),
            400,  # uvicorn itself refuses the second Origin
            400,
        ),
    ],
)
def test_live_server_refuses_rebinding_and_ambiguous_handshakes(
    rosbridge_server: RosbridgeServer, headers: tuple[tuple[str, str], ...], app_status: int, port_status: int
) -> None:
    app = asyncio.run(handshake_refusal(rosbridge_server.port, "/rosbridge", headers))
    port = asyncio.run(handshake_refusal(rosbridge_server.rosbridge_port, "/", headers))
    assert (app, port) == (app_status, port_status)
