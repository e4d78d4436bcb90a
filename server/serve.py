"""Run the app under uvicorn: the one way both ``python -m server`` and a world worker serve."""

from __future__ import annotations

import contextlib
import logging
import socket
from collections.abc import Callable
from types import FrameType

import uvicorn
from fastapi import FastAPI

from node_runtime.console import access_log, quiet_uvicorn
from server.app import create_app
from server.base.collections_policy import keep_full_collections_short
from server.base.loop_priority import loop_priority
from server.host.settings import Settings

log = logging.getLogger("server")


def serve(
    settings: Settings,
    *,
    sock: socket.socket | None = None,
    announce: Callable[[FastAPI], None] | None = None,
) -> None:
    """Serve the app for ``settings`` until Ctrl-C or SIGTERM: on ``sock`` when given (a world worker
    binds its port first, to say where it listens), else on the settings' host and port, logging at
    the settings' level. ``announce`` runs once the app exists (the banner that says where to go)."""
    import rich

    # viser prints a box with its own loopback port; the page is served on ours, so that box would
    # send a student to a page without the lab's keys and HUD. The app prints nothing else through rich.
    rich.get_console().quiet = True
    keep_full_collections_short()  # a full collection would hold every world's ticks back
    with loop_priority(settings.loop_priority) as priority:  # this thread runs the worlds' loop
        # A class's console says what its worlds' loop got; a student's own lab keeps quiet about it.
        log.log(logging.INFO if settings.classroom is not None else logging.DEBUG, "%s", priority.line())
        _serve(settings, sock, announce)


def _serve(
    settings: Settings, sock: socket.socket | None, announce: Callable[[FastAPI], None] | None
) -> None:
    """``serve``'s app under uvicorn, on the calling thread."""
    app = create_app(settings)
    if announce is not None:
        announce(app)
    listen, level, classroom = settings.listen, settings.log_level, settings.classroom is not None
    config = uvicorn.Config(
        app,
        host=listen.host,
        port=listen.port,
        log_level=level,
        access_log=access_log(level, classroom=classroom),
        ws_max_size=listen.max_ws_frame_bytes * 64,
        timeout_graceful_shutdown=1,
        # No permessage-deflate: the page's pose stream (100 frames a second) spent about 30 %
        # of its cost deflating each small frame, and viser's frames are compressed already. Nor
        # does the server then inflate what a client sends.
        ws_per_message_deflate=False,
        lifespan="on",
    )
    quiet_uvicorn(level, classroom=classroom)
    with contextlib.suppress(KeyboardInterrupt):
        _Server(config).run(sockets=[sock] if sock is not None else None)


class _Server(uvicorn.Server):
    """uvicorn's server, save that a Ctrl-C while it stops (after a first Ctrl-C or a SIGTERM) does
    not force the quit. Forced, uvicorn skips the app's own stop (its worlds, its Zenoh session, a
    class's world workers) and then cancels it half done, and the threads those leave running kept
    the process alive for good after printing two tracebacks: a student who pressed Ctrl-C twice had
    to kill it. The stop is bounded without the force: open connections get
    ``timeout_graceful_shutdown``."""

    def handle_exit(self, sig: int, frame: FrameType | None) -> None:
        super().handle_exit(sig, frame)
        self.force_exit = False
