"""One rule for a refused WebSocket: the handshake completes, then the socket closes at once with a
close code that names why (api/errors.py ``CloseCode``: 4401 no valid token, 4403 not yours or
another site's page, 4421 not a name of this server, ...) and a reason. Nothing else is sent first.

ASGI servers answer a close sent before the accept with a bare HTTP 403, which a browser's script
cannot even see (its WebSocket reports 1006): the code and the reason would be lost. So this
middleware, outermost, turns such a close into accept-then-close, whatever sent it (a route, a
dependency, the guard, the error net).
"""

from __future__ import annotations

from starlette.types import ASGIApp, Message, Receive, Scope, Send


class WebSocketRefusalMiddleware:
    """A WebSocket closed before it was accepted is accepted first, so its close code arrives."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "websocket":
            return await self.app(scope, receive, send)
        connected = accepted = False

        async def tracking_receive() -> Message:
            nonlocal connected
            message = await receive()
            connected = connected or message["type"] == "websocket.connect"
            return message

        async def refusing_send(message: Message) -> None:
            nonlocal accepted
            if message["type"] == "websocket.close" and not accepted:
                if not connected:
                    await tracking_receive()  # the client's websocket.connect, which comes first
                requested = scope.get("subprotocols") or []
                # A client that asked for subprotocols gets one back, so none fails the handshake
                # before it reads the close.
                await send({"type": "websocket.accept", "subprotocol": requested[0] if requested else None})
                accepted = True
            elif message["type"] in ("websocket.accept", "websocket.http.response.start"):
                accepted = True
            await send(message)

        await self.app(scope, tracking_receive, refusing_send)
