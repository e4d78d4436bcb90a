"""The keyboard device: key events from browser tabs (or tests), fanned out to keyboard nodes.

It tracks which keys each source holds, so a source that goes away (a closed tab, a blurred
window, a silent connection) can have its keys released: no stuck keys.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

log = logging.getLogger("devices.keyboard")


@dataclass(frozen=True)
class KeyEvent:
    kind: Literal["keydown", "keyup"]
    code: int
    modifiers: int
    source: str
    repeat: bool = False  # a keydown for a key this source already holds


Listener = Callable[[KeyEvent], None]


class KeyboardDevice:
    def __init__(self) -> None:
        self._listeners: list[Listener] = []
        self._held: dict[str, dict[int, int]] = {}

    def add_listener(self, listener: Listener) -> None:
        self._listeners.append(listener)

    def remove_listener(self, listener: Listener) -> None:
        if listener in self._listeners:
            self._listeners.remove(listener)

    def held(self, source: str | None = None) -> set[int]:
        if source is not None:
            return set(self._held.get(source, {}))
        return {code for keys in self._held.values() for code in keys}

    def key_down(self, code: int, modifiers: int, source: str) -> KeyEvent:
        keys = self._held.setdefault(source, {})
        event = KeyEvent("keydown", code, modifiers, source, repeat=code in keys)
        keys[code] = modifiers
        self._emit(event)
        return event

    def key_up(self, code: int, modifiers: int, source: str) -> KeyEvent | None:
        """Release a key; a key this source does not hold is ignored (returns None)."""
        keys = self._held.get(source, {})
        if code not in keys:
            return None
        del keys[code]
        event = KeyEvent("keyup", code, modifiers, source)
        self._emit(event)
        return event

    def release_all(self, source: str) -> list[KeyEvent]:
        """Key-up every key ``source`` holds (blur, hidden tab, closed or silent channel)."""
        keys = self._held.pop(source, {})
        events = [KeyEvent("keyup", code, mods, source) for code, mods in keys.items()]
        for event in events:
            self._emit(event)
        return events

    def _emit(self, event: KeyEvent) -> None:
        for listener in list(self._listeners):
            try:
                listener(event)
            except Exception:  # a listener's fault must not lose the key for the others
                log.exception("keyboard listener failed on %s", event)
