"""viser's own client page, served by the app with our key script injected, and the WebSocket
proxy that carries it to the viser server on loopback: one port for everything."""

from __future__ import annotations

import asyncio
import contextlib
from functools import cache
from pathlib import Path

import viser
import websockets
from fastapi import APIRouter, WebSocket
from fastapi.responses import HTMLResponse

router = APIRouter(include_in_schema=False)
VISER_INDEX = Path(viser.__file__).parent / "client" / "build" / "index.html"
INJECT_STYLES = ("page.css",)
INJECT_SCRIPTS = ("keys.js", "hud.js", "nav.js")  # key capture first: it must see keys before viser does
INJECT = "".join(f'<link rel="stylesheet" href="/static/{name}">' for name in INJECT_STYLES) + "".join(
    f'<script src="/static/{name}"></script>' for name in INJECT_SCRIPTS
)
PROXY_MAX_FRAME_BYTES = 1 << 20  # browser → viser: camera moves and GUI clicks, all small


@cache
def index_html() -> str:
    html = VISER_INDEX.read_text(encoding="utf-8")
    if "</head>" not in html:
        raise RuntimeError(f"viser's page at {VISER_INDEX} changed shape; pin viser==1.1.1")
    return html.replace("</head>", INJECT + "</head>", 1)


@router.get("/")
async def index() -> HTMLResponse:
    return HTMLResponse(index_html(), headers={"Cache-Control": "no-cache"})


@router.websocket("/")
async def viser_proxy(websocket: WebSocket) -> None:
    display = websocket.app.state.lab.display
    if display is None:
        await websocket.close(1013, "the 3D view is not running")
        return
    subprotocols = websocket.scope.get("subprotocols", [])
    async with websockets.connect(
        f"ws://127.0.0.1:{display.port}", subprotocols=subprotocols, max_size=None, compression=None
    ) as upstream:
        await websocket.accept(subprotocol=upstream.subprotocol)

        async def client_to_viser() -> None:
            while (message := await websocket.receive())["type"] != "websocket.disconnect":
                data = message.get("bytes") if message.get("bytes") is not None else message.get("text")
                if data is None or len(data) > PROXY_MAX_FRAME_BYTES:
                    return
                await upstream.send(data)

        async def viser_to_client() -> None:
            async for data in upstream:
                if isinstance(data, bytes):
                    await websocket.send_bytes(data)
                else:
                    await websocket.send_text(data)

        tasks = [asyncio.create_task(client_to_viser()), asyncio.create_task(viser_to_client())]
        try:
            await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
        finally:
            for task in tasks:
                task.cancel()
            for task in tasks:
                with contextlib.suppress(BaseException):
                    await task
