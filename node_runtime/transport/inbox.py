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

    def take(self) -> tuple[list[Any], dict[str, list[Any]]]:
        """Everything queued so far: (events in order, samples by topic in order)."""
        if not self._pending:  # read without the lock: a put that races it wakes the executor again
            return [], {}
        with self._lock:
            events = list(self._events)
            self._events.clear()
            samples = {k: list(q) for k, q in self._samples.items() if q}
            for queue in self._samples.values():
                queue.clear()
            self._pending = False
        return events, samples

    def queued(self, key: str) -> int:
        """Samples of ``key`` waiting for the executor."""
        with self._lock:
            queue = self._samples.get(key)
            return len(queue) if queue is not None else 0

    def forget(self, key: str) -> None:
        with self._lock:
            self._samples.pop(key, None)
