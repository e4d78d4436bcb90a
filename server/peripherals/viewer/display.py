"""The display device: a viser server on loopback that the app proxies onto its own port."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any

import viser

from server.peripherals.viewer.views import CameraView, Follow, Vec3, ViewRegistry
from server.peripherals.viewer.viser_guard import guarded_serve, new_token

log = logging.getLogger("viewer")

SKY_GROUND = (110, 110, 110)  # the hemisphere light's colour from below
SKY_INTENSITY = 2.0


class Display:
    """Owns the ViserServer; view nodes draw through ``scene`` and ``gui``.

    viser runs its own thread and event loop: GUI callbacks arrive there, so ``call_in_app``
    hands them back to the app's loop, where the bus lives.
    """

    def __init__(self, loop: asyncio.AbstractEventLoop | None = None) -> None:
        # Loopback, an ephemeral port, and a secret only the app's proxy sends: a browser reaches
        # viser only through the app and its guard (viser_guard.py).
        self.proxy_token = new_token()
        with guarded_serve(self.proxy_token):
            self.server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
        self.set_theme(dark=False)
        self.server.scene.set_up_direction("+z")
        self._loop = loop
        self.views = ViewRegistry()
        # Shadows cost a fixed depth pass per frame, which software WebGL pays in full; the labs
        # read fine without them.
        self.server.scene.configure_default_lights(enabled=True, cast_shadow=False)
        # No image-based light: viser's default HDRI is filtered into an environment map in the
        # page, which froze a software-WebGL page for about 6 s a few seconds after each load. A
        # hemisphere light (white sky, grey ground) lights the sides the HDRI lit, at no cost.
        self.server.scene.configure_environment_map(None)
        self.server.scene.add_light_hemisphere(
            "/lights/sky",
            sky_color=(255, 255, 255),
            ground_color=SKY_GROUND,
            intensity=SKY_INTENSITY,
            position=(0.0, 0.0, 1.0),
        )

    def add_view(
        self,
        name: str,
        position: Vec3,
        look_at: Vec3,
        *,
        initial: bool = False,
        follow: Follow | None = None,
        busy: Callable[[], bool] | None = None,
    ) -> None:
        """A camera view of one lab, switched in the page (web/src/lab/scene.ts); ``initial``: where
        viser's camera starts before the page picks its view."""
        self.views.add(CameraView(name, position, look_at, follow, busy))
        if initial or len(self.views) == 1:
            self.server.initial_camera.position = position
            self.server.initial_camera.look_at = look_at
            self.server.initial_camera.up = (0.0, 0.0, 1.0)

    def set_theme(self, *, dark: bool) -> None:
        # The share button would reach an outside tunnel host: never offer it.
        self.server.gui.configure_theme(show_share_button=False, control_width="medium", dark_mode=dark)

    @property
    def port(self) -> int:
        return self.server.get_port()

    @property
    def scene(self) -> Any:
        return self.server.scene

    @property
    def gui(self) -> Any:
        return self.server.gui

    def watched(self) -> bool:
        """Whether a page shows this display now. Views skip their updates while none does and send
        the latest on their next tick after one connects: with no page there is no one to draw for,
        and a world of a class server with no student looking costs that much less."""
        return bool(self.server.get_clients())

    def call_in_app(self, fn: Callable[[], Any]) -> None:
        """Run ``fn`` on the app's loop (from a viser callback thread)."""
        if self._loop is None or self._loop.is_closed():
            return
        self._loop.call_soon_threadsafe(fn)

    def stop(self) -> None:
        self.server.stop()
