"""The lab's controls for the rocket: its view in the 3D scene, drawn while a launch runs the
rocket, and its reset (the page's button, ``POST /api/rocket/reset`` and the ROS service
``/rocket/reset``), which restarts the rocket launch's nodes as a student would."""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from node_runtime.bus import Bus, Node
from node_runtime.msgs import get_service_type

if TYPE_CHECKING:
    from server.peripherals.viewer.display import Display
    from server.peripherals.viewer.rocket_view import RocketViewNode

log = logging.getLogger("lab")
Trigger = get_service_type("std_srvs/srv/Trigger")
RESET_SERVICE = "/rocket/reset"
PACKAGE = "rocketship"
LAUNCH_FILE = "rocket.launch"


class _Action(Protocol):
    @property
    def pkg(self) -> str: ...


class LaunchEntry(Protocol):
    """A node a launch started (server/services/launch/launcher.py's ``LaunchedNode``): its action and file."""

    @property
    def action(self) -> _Action: ...

    @property
    def file(self) -> str: ...


class Restarter(Protocol):
    """What restarts launched nodes (server/services/launch/launcher.py's ``Launcher``)."""

    def restart(self, predicate: Callable[[Any], bool]) -> Sequence[object]: ...


def is_rocket_node(entry: LaunchEntry) -> bool:
    """A node of the rocket's own launch file (not a rocketship node another launch started)."""
    return Path(entry.file).name == LAUNCH_FILE and entry.action.pkg == PACKAGE


class RocketControls:
    """The rocket's view and reset for one lab; the view exists once a launch has run the rocket."""

    def __init__(self, launcher: Restarter) -> None:
        self._launcher = launcher
        self.view: RocketViewNode | None = None

    def start_view(self, bus: Bus, display: Display | None, launched: Iterable[LaunchEntry]) -> None:
        """The rocket's view (a hidden node, drawing in ``display`` if there is one) if any of
        ``launched`` is a node of the rocket's package."""
        if any(entry.action.pkg == PACKAGE for entry in launched):
            from server.peripherals.viewer.rocket_view import RocketViewNode  # viser loads only when it draws

            with bus.activate():
                self.view = RocketViewNode(display, self.reset)

    def serve(self, node: Node) -> None:
        """Serve the reset as ``/rocket/reset`` (std_srvs/srv/Trigger) on ``node``."""
        node.create_service(Trigger, RESET_SERVICE, self._on_reset)

    def _on_reset(self, request: Any, response: Any) -> Any:
        response.success = self.reset()
        response.message = "rocket back on the pad" if response.success else "no rocket in this launch"
        return response

    def reset(self) -> bool:
        """Put the rocket back on the pad: restart the rocket launch's nodes, as a student would.
        Returns whether there was a rocket to reset."""
        restarted = self._launcher.restart(is_rocket_node)
        if self.view is not None:
            self.view.reset()
        log.info("rocket reset: back on the pad, countdown restarted")
        return bool(restarted)
