"""Every JSON request body checked before any route sees it (api/protocol/json_codec.py ``loads``):
a bad number anywhere in any body is one 422 that names it and changes nothing."""

from __future__ import annotations

import json

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from api.errors import BodyTooLarge
from api.protocol.json_codec import JsonRejected, loads

_SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})


def _is_json(scope: Scope) -> bool:
    """What FastAPI would parse as JSON: no content type, or application/json or */*+json."""
    for key, value in scope.get("headers", []):
        if key == b"content-type":
            media = str(value, "latin-1").split(";", 1)[0].strip().lower()
            return media == "application/json" or (
                media.startswith("application/") and media.endswith("+json")
            )
    return True


class StrictJsonMiddleware:
    """Reads each JSON request body (already bounded by the guard), checks it with ``loads`` and
    answers 422 before the app runs; a good body is replayed to the app unchanged."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope["method"] in _SAFE_METHODS or not _is_json(scope):
            return await self.app(scope, receive, send)
        chunks: list[bytes] = []
        try:
            while True:
                message = await receive()
                if message["type"] != "http.request":
                    return  # the client left before sending its body
                chunks.append(message.get("body", b""))
                if not message.get("more_body", False):
                    break
        except BodyTooLarge as exc:  # the guard's bounded receive, on a body without Content-Length
            return await _error(send, exc.status_code, str(exc))
        body = b"".join(chunks)
        if body.strip():
            try:
                loads(body)
            except JsonRejected as exc:
                return await _error(send, 422, f"request body: {exc}")
        replayed = False

        async def replay() -> Message:
            nonlocal replayed
            if replayed:
                return await receive()
            replayed = True
            return {"type": "http.request", "body": body, "more_body": False}

        await self.app(scope, replay, send)


async def _error(send: Send, status: int, detail: str) -> None:
    payload = json.dumps({"detail": detail}).encode()
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(payload)).encode())]
    await send({"type": "http.response.start", "status": status, "headers": headers})
    await send({"type": "http.response.body", "body": payload})
