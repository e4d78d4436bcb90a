"""tf2's BufferCore: the tree of frames over time, and transforms found by walking it.

Each frame but the roots has a cache of where it was in its parent (``_time_cache``). A lookup
from ``source`` to ``target`` at a time walks up from both to where their chains meet and composes
the links on the way; time 0 asks for the latest time at which every link on the way is known
(static links have no time, so they never hold it back). The exceptions and their messages are
tf2's, so ``except TransformException`` code and its printed reasons read as on a real ROS 2.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import numpy as np
from builtin_interfaces.msg import Time as TimeMsg
from geometry_msgs.msg import TransformStamped

from tf2_ros._exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TransformException,
)
from tf2_ros._time_cache import (
    DEFAULT_CACHE_TIME_NS,
    NS_PER_S,
    FrameCache,
    Record,
    StaticCache,
    TimeCache,
    seconds_text,
)
from tf2_ros._transform_math import RigidTransform

MAX_GRAPH_DEPTH = 1000  # tf2's: a longer chain of parents must be a loop
NORMALIZATION_TOLERANCE = 10e-3  # tf2's: |q|^2 this far from 1 is refused


def time_ns(time: Any) -> int:
    """Nanoseconds of an rclpy Time (or Duration), or of a builtin_interfaces Time message."""
    if hasattr(time, "sec") and hasattr(time, "nanosec"):
        return int(time.sec) * NS_PER_S + int(time.nanosec)
    if hasattr(time, "nanoseconds"):
        return int(time.nanoseconds)
    raise TypeError(f"time must have sec and nanosec, or nanoseconds, got {type(time).__name__}")


def _stamp(ns: int) -> TimeMsg:
    sec, nanosec = divmod(ns, NS_PER_S)
    return TimeMsg(sec=sec, nanosec=nanosec)


def _message(target: str, source: str, stamp_ns: int, transform: RigidTransform) -> TransformStamped:
    out = TransformStamped()
    out.header.stamp = _stamp(stamp_ns)
    out.header.frame_id = target
    out.child_frame_id = source
    t, q = (float(v) for v in transform.translation), (float(v) for v in transform.rotation)
    out.transform.translation.x, out.transform.translation.y, out.transform.translation.z = t
    r = out.transform.rotation
    r.x, r.y, r.z, r.w = q
    return out


def _link(transform: TransformStamped) -> RigidTransform:
    t, r = transform.transform.translation, transform.transform.rotation
    return RigidTransform(np.array([t.x, t.y, t.z], dtype=float), np.array([r.x, r.y, r.z, r.w], dtype=float))


class BufferCore:
    """Frames and their caches; thread-safe (the listener writes while a timer reads)."""

    def __init__(self, cache_time: Any = None) -> None:
        self.cache_time_ns = DEFAULT_CACHE_TIME_NS if cache_time is None else time_ns(cache_time)
        self._frames: dict[str, FrameCache] = {}
        self._known: set[str] = set()  # every frame named so far, parents included
        self._authority: dict[str, str] = {}
        self._lock = threading.RLock()
        self.log_error: Callable[[str], object] = lambda text: None
        self.log_warning: Callable[[str], object] = lambda text: None

    # -- storing -------------------------------------------------------------------------------
    def set_transform(self, transform: TransformStamped, authority: str) -> bool:
        return self._store(transform, authority, static=False)

    def set_transform_static(self, transform: TransformStamped, authority: str) -> bool:
        return self._store(transform, authority, static=True)

    def _refusal(self, transform: TransformStamped, authority: str, link: RigidTransform) -> str | None:
        parent, child = transform.header.frame_id.lstrip("/"), transform.child_frame_id.lstrip("/")
        values = [*link.translation, *link.rotation]
        if child == parent:
            return (
                f'TF_SELF_TRANSFORM: Ignoring transform from authority "{authority}" with frame_id and  '
                f'child_frame_id "{child}" because they are the same'
            )
        if not child:
            return f'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "{authority}" because child_frame_id not set '
        if not parent:
            return (
                f'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "{child}"  from authority '
                f'"{authority}" because frame_id not set'
            )
        if any(np.isnan(v) for v in values):
            return (
                f'TF_NAN_INPUT: Ignoring transform for child_frame_id "{child}" from authority "{authority}" '
                "because of a nan value in the transform ({:f} {:f} {:f}) ({:f} {:f} {:f} {:f})".format(
                    *values
                )
            )
        if abs(float(np.dot(link.rotation, link.rotation)) - 1.0) >= NORMALIZATION_TOLERANCE:
            return (
                f'TF_DENORMALIZED_QUATERNION: Ignoring transform for child_frame_id "{child}" from authority '
                '"{}" because of an invalid quaternion in the transform ({:f} {:f} {:f} {:f})'.format(
                    authority, *values[3:]
                )
            )
        return None

    def _store(self, transform: TransformStamped, authority: str, *, static: bool) -> bool:
        link = _link(transform)
        refusal = self._refusal(transform, authority, link)
        if refusal is not None:
            self.log_error(refusal)
            return False
        parent, child = transform.header.frame_id.lstrip("/"), transform.child_frame_id.lstrip("/")
        record = Record(time_ns(transform.header.stamp), parent, link)
        with self._lock:
            cache = self._frames.get(child)
            if static and not isinstance(cache, StaticCache):
                self._frames[child] = StaticCache(record)
            else:
                if not static and not isinstance(cache, TimeCache):
                    cache = self._frames[child] = TimeCache(self.cache_time_ns)
                assert cache is not None
                if not cache.insert(record):
                    self.log_warning(
                        f"TF_OLD_DATA ignoring data from the past for frame {child} at time "
                        f"{seconds_text(record.stamp_ns)} according to authority {authority}\n"
                        "Possible reasons are listed at http://wiki.ros.org/tf/Errors%20explained"
                    )
                    return False
            self._known.update((parent, child))
            self._authority[child] = authority
        return True

    def clear(self) -> None:
        """Forget every moving frame's history (static frames stay)."""
        with self._lock:
            for cache in self._frames.values():
                cache.clear()

    # -- looking up ----------------------------------------------------------------------------
    def _validate(self, where: str, frame: str) -> None:
        if not frame:
            raise InvalidArgumentException(
                f'Invalid argument "{frame}" passed to {where} - in tf2 frame_ids cannot be empty'
            )
        if frame.startswith("/"):
            raise InvalidArgumentException(
                f"Invalid argument \"{frame}\" passed to {where} - in tf2 frame_ids cannot start with a '/'"
            )
        if frame not in self._known:
            raise LookupException(f'"{frame}" passed to {where} does not exist. ')

    def _loop_error(self) -> LookupException:
        return LookupException(
            "The tf tree is invalid because it contains a loop.\n" + self.all_frames_as_string() + "\n"
        )

    def _latest_common_time(self, target: str, source: str) -> int:
        """The newest time every link between the two frames is known at (0: all static)."""
        source_chain: list[tuple[int, str]] = []
        frame, common = source, None
        while (cache := self._frames.get(frame)) is not None and (latest := cache.latest()) is not None:
            if latest[0]:
                common = latest[0] if common is None else min(common, latest[0])
            source_chain.append(latest)
            frame = latest[1]
            if frame == target:
                return common or 0
            if len(source_chain) > MAX_GRAPH_DEPTH:
                raise self._loop_error()
        parents = [parent for _stamp_ns, parent in source_chain]
        frame, common, depth, meeting = target, None, 0, None
        while (cache := self._frames.get(frame)) is not None and (latest := cache.latest()) is not None:
            if latest[0]:
                common = latest[0] if common is None else min(common, latest[0])
            if latest[1] in parents:
                meeting = latest[1]
                break
            frame = latest[1]
            if frame == source:
                return common or 0
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                raise self._loop_error()
        if meeting is None:
            raise self._no_connection(target, source)
        for stamp_ns, parent in source_chain:
            if stamp_ns:
                common = stamp_ns if common is None else min(common, stamp_ns)
            if parent == meeting:
                break
        return common or 0

    @staticmethod
    def _no_connection(target: str, source: str) -> ConnectivityException:
        return ConnectivityException(
            f"Could not find a connection between '{target}' and '{source}' because they are not part "
            "of the same tree.Tf has two or more unconnected trees."
        )

    def _walk(self, target: str, source: str, stamp_ns: int) -> tuple[RigidTransform, int]:
        """``source``'s place in ``target`` at ``stamp_ns`` (0: the latest common time), and the time."""
        if stamp_ns == 0:
            stamp_ns = self._latest_common_time(target, source)
        suffix = f", when looking up transform from frame [{source}] to frame [{target}]"
        # Up from the source, composing its links, until the target, a root or a gap in time.
        up_from_source, frame, missed = RigidTransform.identity(), source, None
        for _depth in range(MAX_GRAPH_DEPTH + 1):
            cache = self._frames.get(frame)
            if frame == target:
                return up_from_source, stamp_ns
            if cache is None:
                break
            try:
                record = cache.at(stamp_ns)
            except ExtrapolationException as exc:
                missed = exc  # the target's chain may still meet this one below the gap
                break
            up_from_source = record.transform @ up_from_source
            frame = record.parent
        else:
            raise self._loop_error()
        top = frame
        # Up from the target until it meets the source's chain at its top.
        up_from_target, frame = RigidTransform.identity(), target
        for _depth in range(MAX_GRAPH_DEPTH + 1):
            if frame == top:
                return up_from_target.inverse() @ up_from_source, stamp_ns
            if frame == source:
                return up_from_target.inverse(), stamp_ns
            cache = self._frames.get(frame)
            if cache is None:
                break
            try:
                record = cache.at(stamp_ns)
            except ExtrapolationException as exc:
                raise ExtrapolationException(f"{exc}{suffix}") from None
            up_from_target = record.transform @ up_from_target
            frame = record.parent
        else:
            raise self._loop_error()
        if missed is not None:
            raise ExtrapolationException(f"{missed}{suffix}")
        raise self._no_connection(target, source)

    def lookup_transform_core(self, target_frame: str, source_frame: str, time: Any) -> TransformStamped:
        """``source_frame``'s pose in ``target_frame`` at ``time`` (0: the latest common time), as
        a TransformStamped whose frame_id is the target and child_frame_id the source."""
        stamp_ns = time_ns(time)
        with self._lock:
            if target_frame == source_frame:
                cache = self._frames.get(target_frame)
                if stamp_ns == 0 and cache is not None:
                    stamp_ns = cache.newest_ns
                return _message(target_frame, source_frame, stamp_ns, RigidTransform.identity())
            self._validate("lookupTransform argument target_frame", target_frame)
            self._validate("lookupTransform argument source_frame", source_frame)
            transform, stamp_ns = self._walk(target_frame, source_frame, stamp_ns)
        return _message(target_frame, source_frame, stamp_ns, transform)

    def lookup_transform_full_core(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> TransformStamped:
        """The source at ``source_time`` seen from the target at ``target_time``, through a frame
        ``fixed_frame`` that stays put between the two times."""
        with self._lock:
            for where, frame in (("target", target_frame), ("source", source_frame), ("fixed", fixed_frame)):
                self._validate(f"lookupTransform argument {where}_frame", frame)
            fixed_from_source = self.lookup_transform_core(fixed_frame, source_frame, source_time)
            target_from_fixed = self.lookup_transform_core(target_frame, fixed_frame, target_time)
        transform = _link(target_from_fixed) @ _link(fixed_from_source)
        return _message(target_frame, source_frame, time_ns(target_from_fixed.header.stamp), transform)

    def can_transform_core(self, target_frame: str, source_frame: str, time: Any) -> tuple[bool, str]:
        """Whether the lookup would succeed now, and tf2's reason when not."""
        if target_frame == source_frame:
            return True, ""
        try:
            with self._lock:
                for where, frame in (("target", target_frame), ("source", source_frame)):
                    self._check_argument(f"canTransform argument {where}_frame", frame)
                self._walk(target_frame, source_frame, time_ns(time))
        except TransformException as exc:
            return False, str(exc)
        return True, ""

    def can_transform_full_core(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> tuple[bool, str]:
        for target, source, time in (
            (target_frame, fixed_frame, target_time),
            (fixed_frame, source_frame, source_time),
        ):
            ok, reason = self.can_transform_core(target, source, time)
            if not ok:
                return ok, reason
        return True, ""

    def _check_argument(self, where: str, frame: str) -> None:
        if not frame:
            rationale = "in tf2 frame_ids cannot be empty"
        elif frame.startswith("/"):
            rationale = "in tf2 frame_ids cannot start with a '/'"
        elif frame not in self._known:
            rationale = "frame does not exist"
        else:
            return
        raise LookupException(f'Invalid frame ID "{frame}" passed to {where} - {rationale}')

    def get_latest_common_time(self, target_frame: str, source_frame: str) -> Any:
        """The newest time both frames are known at, as an rclpy Time."""
        from rclpy.time import Time

        with self._lock:
            self._validate("get_latest_common_time", target_frame)
            self._validate("get_latest_common_time", source_frame)
            if target_frame == source_frame:
                cache = self._frames.get(source_frame)
                return Time(nanoseconds=cache.newest_ns if cache is not None else 0)
            return Time(nanoseconds=self._latest_common_time(target_frame, source_frame))

    # -- describing ----------------------------------------------------------------------------
    def _frame_names(self) -> list[str]:
        with self._lock:
            return sorted(self._known)

    def all_frames_as_string(self) -> str:
        with self._lock:
            return "".join(
                f"Frame {child} exists with parent {latest[1] if latest else 'NO_PARENT'}.\n"
                for child, cache in self._frames.items()
                for latest in (cache.latest(),)
            )

    def all_frames_as_yaml(self) -> str:
        """Each frame with data: its parent, broadcaster, rate (Hz) and the times it holds."""
        lines: list[str] = []
        with self._lock:
            for child, cache in self._frames.items():
                latest = cache.latest()
                if latest is None:
                    continue
                span_ns = cache.newest_ns - cache.oldest_ns
                rate = len(cache) * 1e9 / max(span_ns, 100_000)
                lines += [
                    f"{child}: ",
                    f"  parent: '{latest[1]}'",
                    f"  broadcaster: '{self._authority.get(child, 'no recorded authority')}'",
                    f"  rate: {rate:.3f}",
                    f"  most_recent_transform: {seconds_text(cache.newest_ns)}",
                    f"  oldest_transform: {seconds_text(cache.oldest_ns)}",
                    f"  buffer_length: {span_ns / NS_PER_S:.3f}",
                ]
        return "\n".join(lines) + "\n" if lines else "[]"
