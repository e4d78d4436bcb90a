"""The app factory: FastAPI with a lifespan that owns the lab (bus, sim loop, viser)."""

from __future__ import annotations

import asyncio
import re
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path

from fastapi import FastAPI
from fastapi.staticfiles import StaticFiles

from api.errors import ErrorMiddleware, register_error_handlers
from api.middleware.canonical_path import CanonicalPathMiddleware
from api.middleware.guard import GuardMiddleware
from api.middleware.socket_cap import SocketCapMiddleware
from api.middleware.socket_refusal import WebSocketRefusalMiddleware
from api.middleware.strict_json import StrictJsonMiddleware
from api.middleware.world_proxy import WorldProxyMiddleware
from api.openapi import use_token_security
from api.protocol.json_codec import SafeJSONResponse
from api.router import build_router
from api.routes.checkpoints import LARGE_BODIES
from api.routes.page import router as page_router
from api.routes.tools_page import router as tools_router
from api.routes.workspace import PREFIX as WORKSPACE_PREFIX
from node_runtime.bus import Clock
from server.classroom import Classroom, ClassServer, WorldWorker
from server.host.settings import Settings
from server.services.bridges.runner import run_bridges
from server.world.checkpoints.catalog import load as load_checkpoints
from server.world.checkpoints.store import SINGLE_LAB, ProgressStore
from server.world.lab import Lab

STATIC_DIR = Path(__file__).resolve().parent.parent / "static"


def _classroom(settings: Settings, clock: Clock | None) -> Classroom | None:
    """A class server, or on a world worker (server/world_worker.py) the worlds it hosts; None: one lab."""
    if settings.classroom is None:
        return None
    if settings.worker is not None:
        return WorldWorker(settings, clock, code=settings.classroom.code)
    return ClassServer(settings, clock, code=settings.classroom.code)


def create_app(settings: Settings | None = None, clock: Clock | None = None) -> FastAPI:
    settings = settings or Settings()

    classroom = _classroom(settings, clock)
    class_server = classroom is not None

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        if classroom is not None:  # worlds start as students join
            await classroom.open()
            try:
                yield
            finally:
                await classroom.stop()
            return
        # The checkpoints met and the answers, as the state folder keeps them across restarts.
        store = ProgressStore.in_state_dir(settings.lab.state_dir)
        progress = store.open(SINGLE_LAB, load_checkpoints(settings.lab.checkpoints))
        lab = Lab(settings, clock, progress=progress)
        app.state.lab = lab
        await lab.start()
        try:
            async with run_bridges(lab) as bridges:  # Foxglove, rosbridge's own port
                app.state.bridges = bridges
                yield
        finally:
            await lab.stop()
            await asyncio.to_thread(store.close)

    app = FastAPI(
        title="Teleop lab",
        summary="ROS 2 Lab 2 in the browser: topics, nodes, a rocket and a quadrotor.",
        version="0.1.0",
        lifespan=lifespan,
        default_response_class=SafeJSONResponse,
        # FastAPI's own OpenTelemetry off, whatever the environment says: with
        # FASTAPI_OTEL_AUTO_CONFIGURE=true it would send request traces to the OTLP endpoint the
        # environment names (off this machine), or, without the SDK, refuse to start the lab.
        telemetry={"auto_configure": False, "tracing": False, "metrics": False, "logs": False},
    )
    app.state.classroom = classroom
    app.state.settings = settings
    app.include_router(build_router(classroom=class_server))
    if class_server or settings.listen.token is not None:
        # the document says how to show the token, and where it is needed
        use_token_security(app, classroom=class_server)
    app.include_router(page_router)
    app.include_router(tools_router)
    app.mount("/static", StaticFiles(directory=STATIC_DIR), name="static")
    register_error_handlers(app)
    # Added innermost first: a request meets the error net, then the path check (as sent, never
    # normalised), then the guard, then strict JSON, then (on a class server) a student's cap of
    # WebSockets and the pass to the world worker that hosts the caller's world.
    app.add_middleware(WorldProxyMiddleware)
    app.add_middleware(SocketCapMiddleware)
    app.add_middleware(StrictJsonMiddleware)
    app.add_middleware(
        GuardMiddleware,
        accepted_hosts=settings.listen.accepted_hosts,
        allowed_origins=settings.listen.allowed_origins,
        max_body_bytes=settings.listen.max_body_bytes,
        larger=(
            *LARGE_BODIES,
            (
                re.compile(re.escape(WORKSPACE_PREFIX) + ".*"),
                max(settings.workspace.max_body_bytes, settings.listen.max_body_bytes),
            ),
        ),
    )
    app.add_middleware(CanonicalPathMiddleware)
    app.add_middleware(ErrorMiddleware)
    app.add_middleware(WebSocketRefusalMiddleware)  # outermost: every refused WebSocket gets its code
    return app
