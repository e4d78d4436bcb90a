"""What route handlers take from the running app."""

from __future__ import annotations

from typing import Annotated, cast

from fastapi import Depends, Request, WebSocket

from server.lab import Lab


def _lab(request: Request) -> Lab:
    return cast(Lab, request.app.state.lab)


def _ws_lab(websocket: WebSocket) -> Lab:
    return cast(Lab, websocket.app.state.lab)


LabDep = Annotated[Lab, Depends(_lab)]
WsLabDep = Annotated[Lab, Depends(_ws_lab)]
