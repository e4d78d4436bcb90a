"""tf2_ros' Buffer: a BufferCore a listener fills, with waiting lookups.

``lookup_transform(target, source, time, timeout=...)`` waits up to ``timeout`` for the transform
to become possible (blocking the calling thread, as tf2_ros does: from a callback that needs a
MultiThreadedExecutor or ``wait_for_transform_async``), then looks it up or raises tf2's exception.
"""

from __future__ import annotations

import threading
import time as _time
from collections.abc import Callable
from typing import Any

import rclpy.logging
from geometry_msgs.msg import TransformStamped
from rclpy.duration import Duration
from rclpy.task import Future
from tf2_msgs.srv import FrameGraph

from tf2_ros._buffer_core import BufferCore
from tf2_ros._time_cache import NS_PER_S
from tf2_ros.buffer_interface import NO_WAIT, BufferInterface


def _timeout_s(timeout: Any) -> float:
    if not hasattr(timeout, "nanoseconds"):
        raise TypeError(
            f"timeout must be an rclpy.duration.Duration (e.g. Duration(seconds=1.0)), got {timeout!r}"
        )
    return int(timeout.nanoseconds) / NS_PER_S


class Buffer(BufferCore, BufferInterface):
    """Known frames over the last ``cache_time`` (an rclpy Duration; 10 s unless given). With a
    ``node``, the node serves ``tf2_frames`` (tf2_msgs/srv/FrameGraph: the frames as YAML)."""

    def __init__(self, cache_time: Duration | None = None, node: Any = None) -> None:
        BufferCore.__init__(self, cache_time)
        BufferInterface.__init__(self)
        logger = rclpy.logging.get_logger("tf2_buffer")
        self.log_error, self.log_warning = logger.error, logger.warning
        self._new_data = threading.Condition()
        self._new_data_callbacks: list[Callable[[], None]] = []
        self.clock = node.get_clock() if node is not None else None
        if node is not None:  # as tf2_ros: the frames as YAML for whoever asks the node
            self.srv = node.create_service(FrameGraph, "tf2_frames", self._get_frames)
        self.monotonic: Callable[[], float] = _time.monotonic  # the clock a wait's timeout runs on

    def _get_frames(self, _request: Any, _response: Any) -> Any:
        return FrameGraph.Response(frame_yaml=self.all_frames_as_yaml())

    # -- storing, and telling whoever waits ---------------------------------------------------
    def set_transform(self, transform: TransformStamped, authority: str) -> bool:
        stored = super().set_transform(transform, authority)
        self._call_new_data_callbacks()
        return stored

    def set_transform_static(self, transform: TransformStamped, authority: str) -> bool:
        stored = super().set_transform_static(transform, authority)
        self._call_new_data_callbacks()
        return stored

    def _call_new_data_callbacks(self) -> None:
        with self._new_data:
            callbacks = list(self._new_data_callbacks)
            self._new_data.notify_all()
        for callback in callbacks:
            callback()

    def _wait(self, possible: Callable[[], bool], timeout: Any) -> None:
        """Until ``possible()`` or ``timeout`` has passed (no wait for a zero timeout)."""
        deadline = self.monotonic() + _timeout_s(timeout)
        with self._new_data:
            while not possible():
                left = deadline - self.monotonic()
                if left <= 0:
                    return
                self._new_data.wait(left)

    # -- the simple API ------------------------------------------------------------------------
    def lookup_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Duration = NO_WAIT
    ) -> TransformStamped:
        """``source_frame``'s pose in ``target_frame`` at ``time`` (``Time()``: the latest)."""
        self.can_transform(target_frame, source_frame, time, timeout)
        return self.lookup_transform_core(target_frame, source_frame, time)

    async def lookup_transform_async(
        self, target_frame: str, source_frame: str, time: Any
    ) -> TransformStamped:
        """Await it in an ``async def`` callback: the callback waits, the executor does not."""
        waiting: Any = self.wait_for_transform_async(target_frame, source_frame, time)
        await waiting
        return self.lookup_transform_core(target_frame, source_frame, time)

    def can_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: Any,
        timeout: Duration = NO_WAIT,
        return_debug_tuple: bool = False,
    ) -> Any:
        """Whether the lookup is possible (waiting up to ``timeout`` for it); with
        ``return_debug_tuple``, (possible, tf2's reason when not)."""
        self._wait(lambda: self.can_transform_core(target_frame, source_frame, time)[0], timeout)
        result = self.can_transform_core(target_frame, source_frame, time)
        return result if return_debug_tuple else result[0]

    def wait_for_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Future[Any]:
        """A future that completes with the transform once it is possible."""
        return self._future(
            lambda: self.can_transform_core(target_frame, source_frame, time)[0],
            lambda: self.lookup_transform_core(target_frame, source_frame, time),
        )

    # -- the advanced API: through a frame fixed over time -------------------------------------
    def lookup_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
    ) -> TransformStamped:
        self.can_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
        return self.lookup_transform_full_core(
            target_frame, target_time, source_frame, source_time, fixed_frame
        )

    async def lookup_transform_full_async(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> TransformStamped:
        waiting: Any = self.wait_for_transform_full_async(
            target_frame, target_time, source_frame, source_time, fixed_frame
        )
        await waiting
        return self.lookup_transform_full_core(
            target_frame, target_time, source_frame, source_time, fixed_frame
        )

    def can_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
        return_debug_tuple: bool = False,
    ) -> Any:
        args = (target_frame, target_time, source_frame, source_time, fixed_frame)
        self._wait(lambda: self.can_transform_full_core(*args)[0], timeout)
        result = self.can_transform_full_core(*args)
        return result if return_debug_tuple else result[0]

    def wait_for_transform_full_async(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> Future[Any]:
        args = (target_frame, target_time, source_frame, source_time, fixed_frame)
        return self._future(
            lambda: self.can_transform_full_core(*args)[0], lambda: self.lookup_transform_full_core(*args)
        )

    def _future(self, possible: Callable[[], bool], lookup: Callable[[], TransformStamped]) -> Future[Any]:
        future: Future[Any] = Future()
        if possible():
            future.set_result(lookup())
            return future

        def on_new_data() -> None:
            if future.done():
                return
            try:
                if possible():
                    future.set_result(lookup())
            except Exception as exc:  # the transform went again between the check and the lookup
                future.set_exception(exc)

        with self._new_data:
            self._new_data_callbacks.append(on_new_data)
        future.add_done_callback(lambda _f: self._forget(on_new_data))
        on_new_data()  # data may have come between the first check and the registration
        return future

    def _forget(self, callback: Callable[[], None]) -> None:
        with self._new_data:
            if callback in self._new_data_callbacks:
                self._new_data_callbacks.remove(callback)


__all__ = ["Buffer"]
