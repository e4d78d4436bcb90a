"""The key channels' dead-man: a channel silent for ``timeout_s`` while holding keys has them
released by the server (the page sends a heartbeat every 200 ms; a frozen tab or a dead link
stops it).

It runs on the bus's clock: one hidden node ``_key_deadman`` holds a timer per open channel that
checks, every ``timeout_s / 5``, how long ago the channel's last frame came. A check that runs
late (the app's loop was busy) decides nothing, since the frames that would have reset the
silence may still be waiting to be read behind the stall; the next check on time does. Tests
step it with a ManualClock. The node exists only while a channel is watched.
"""

from __future__ import annotations

import logging

from node_runtime.bus import Bus, Node, Timer
from server.peripherals.devices.keyboard import KeyboardDevice

log = logging.getLogger("devices.deadman")
NODE_NAME = "_key_deadman"
CHECKS_PER_TIMEOUT = 5


class KeyDeadMan:
    def __init__(self, keyboard: KeyboardDevice, bus: Bus, timeout_s: float) -> None:
        if not 0 < timeout_s <= 3600:
            raise ValueError(f"the dead-man's timeout must be in (0, 3600] s, got {timeout_s!r}")
        self.keyboard = keyboard
        self.bus = bus
        self.timeout_s = timeout_s
        self.check_period_s = timeout_s / CHECKS_PER_TIMEOUT
        self._node: Node | None = None
        self._timers: dict[str, Timer] = {}
        self._last_frame_s: dict[str, float] = {}

    def watch(self, source: str) -> None:
        """Start watching a key source (a channel that just opened)."""
        if source in self._timers:
            raise ValueError(f"key source {source!r} is already watched")
        if self._node is None:
            self._node = Node(NODE_NAME, context=self.bus)
        self._last_frame_s[source] = self.bus.clock.now()
        self._timers[source] = self._node.create_timer(self.check_period_s, lambda: self._check(source))

    def feed(self, source: str) -> None:
        """The source sent a frame: its silence starts again from now."""
        if source in self._last_frame_s:
            self._last_frame_s[source] = self.bus.clock.now()

    def unwatch(self, source: str) -> None:
        """The channel closed (its keys are released by its handler); drop its timer, and the node
        with the last one."""
        timer = self._timers.pop(source, None)
        self._last_frame_s.pop(source, None)
        if timer is not None and self._node is not None:
            self._node.destroy_timer(timer)
        if not self._timers and self._node is not None:
            self._node.destroy_node()
            self._node = None

    @property
    def watched(self) -> frozenset[str]:
        return frozenset(self._timers)

    def _check(self, source: str) -> None:
        timer = self._timers[source]
        if timer.lateness_s and timer.lateness_s[-1] > self.check_period_s:
            return  # a stalled loop, not (yet) a silent channel
        silent_s = self.bus.clock.now() - self._last_frame_s[source]
        if silent_s >= self.timeout_s and self.keyboard.held(source):
            log.warning(
                "key channel %s silent for over %.0f ms with keys held: releasing them",
                source,
                self.timeout_s * 1000,
            )
            self.keyboard.release_all(source)
