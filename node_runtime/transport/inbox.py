"""The one door from Zenoh's threads into the bus's executor: bounded, and it never blocks Zenoh.

Samples are kept per topic, newest last, in keep-last queues (a slow executor loses the oldest
samples of a busy topic, never memory); other events (graph tokens, service queries and replies)
share one bounded queue. The executor is woken once when the inbox goes from empty to not empty.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from typing import Any

MAX_EVENTS = 8192


class Inbox:
    def __init__(self, wake: Callable[[], None], max_events: int = MAX_EVENTS) -> None:
        self._wake = wake
        self._lock = threading.Lock()
        self._samples: dict[str, deque[Any]] = {}
        self._events: deque[Any] = deque(maxlen=max_events)
        self._pending = False
        self.dropped_samples = 0
        self.dropped_events = 0

    def put_sample(self, key: str, item: Any, keep: int) -> None:
        """Queue a sample for topic ``key``, keeping at most ``keep`` of that topic's newest."""
        with self._lock:
            queue = self._samples.get(key)
            if queue is None or queue.maxlen != keep:
                queue = self._samples[key] = deque(queue or (), maxlen=max(1, keep))
            if len(queue) == queue.maxlen:
                self.dropped_samples += 1
            queue.append(item)
            wake = not self._pending
            self._pending = True
        if wake:
            self._wake()

    def post(self, event: Any) -> None:
        with self._lock:
            if len(self._events) == self._events.maxlen:
                self.dropped_events += 1
            self._events.append(event)
            wake = not self._pending
            self._pending = True
        if wake:
            self._wake()

    def take(self, max_events: int | None = None) -> tuple[list[Any], dict[str, list[Any]]]:
        """What is queued so far: (events in order, at most ``max_events`` of them; samples by
        topic in order). Events left over stay queued, and the inbox stays pending: the caller
        takes them on its next pass (and asks for one, see ``left``)."""
        if not self._pending:  # read without the lock: a put that races it wakes the executor again
            return [], {}
        with self._lock:
            if max_events is None or len(self._events) <= max_events:
                events = list(self._events)
                self._events.clear()
            else:
                events = [self._events.popleft() for _ in range(max_events)]
            samples = {k: list(q) for k, q in self._samples.items() if q}
            for queue in self._samples.values():
                queue.clear()
            self._pending = bool(self._events)
        return events, samples

    def left(self) -> int:
        """Events still queued (a take that left some over)."""
        with self._lock:
            return len(self._events)

    def queued(self, key: str) -> int:
        """Samples of ``key`` waiting for the executor."""
        with self._lock:
            queue = self._samples.get(key)
            return len(queue) if queue is not None else 0

    def forget(self, key: str) -> None:
        with self._lock:
            self._samples.pop(key, None)
