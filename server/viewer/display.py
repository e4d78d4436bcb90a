"""The display device: a viser server on loopback that the app proxies onto its own port."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any

import viser

log = logging.getLogger("viewer")


class Display:
    """Owns the ViserServer; view nodes draw through ``scene`` and ``gui``.

    viser runs its own thread and event loop: GUI callbacks arrive there, so ``call_in_app``
    hands them back to the app's loop, where the bus lives.
    """

    def __init__(self, loop: asyncio.AbstractEventLoop | None = None) -> None:
        # Loopback and an ephemeral port: the browser only ever reaches it through the app.
        self.server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
        self.server.gui.configure_theme(show_share_button=False, control_layout="collapsible",
                                        control_width="medium", dark_mode=False)
        self.server.scene.set_up_direction("+z")
        self._loop = loop

    @property
    def port(self) -> int:
        return self.server.get_port()

    @property
    def scene(self) -> Any:
        return self.server.scene

    @property
    def gui(self) -> Any:
        return self.server.gui

    def call_in_app(self, fn: Callable[[], Any]) -> None:
        """Run ``fn`` on the app's loop (from a viser callback thread)."""
        if self._loop is None or self._loop.is_closed():
            return
        self._loop.call_soon_threadsafe(fn)

    def stop(self) -> None:
        self.server.stop()
