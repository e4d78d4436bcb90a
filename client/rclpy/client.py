"""rclpy's Client: ``call_async`` (a Future), ``call`` (blocks this thread until the executor,
spinning in another, completes it) and ``wait_for_service``."""

from __future__ import annotations

import contextlib
import time
from typing import Any

from server.bus import Future, ServiceClient
from server.msgs import Message

WAIT_POLL_S = 0.02  # how often wait_for_service looks at the graph


class Client(ServiceClient):
    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """True once a server of this service is in the graph; False after ``timeout_sec``."""
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while True:
            self._refresh_graph()
            if self.service_is_ready():
                return True
            if end is not None and time.monotonic() >= end:
                return False
            time.sleep(WAIT_POLL_S)

    def _refresh_graph(self) -> None:
        """Take in what the graph said while no thread spins (rclpy learns it in the background;
        here the executor's pass does, and a constructor waits before any spin)."""
        core = getattr(getattr(self.node, "_rcl_context", None), "executor", None)
        if core is not None and core.spinning_threads:
            return  # the spinning thread keeps the graph current
        bus = self.node.bus
        with bus.lock if bus.lock is not None else contextlib.nullcontext():
            for poll in list(bus.pollers):
                poll()

    def call(self, request: Message, timeout_sec: float | None = None) -> Any:
        """The response; for a caller on another thread than the executor's, as in rclpy (on the
        spinning thread itself it would wait for ever). None if ``timeout_sec`` passes."""
        future = self.call_async(request)
        if not future.wait(timeout_sec):
            self.remove_pending_request(future)
            return None
        return future.result()

    def remove_pending_request(self, future: Future[Any]) -> None:
        future.cancel()


__all__ = ["Client"]
