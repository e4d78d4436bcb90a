"""Waiting for a transform: ``wait_for_transform_async``'s future, and ``lookup_transform`` with a
timeout, whose clock the test holds (the wait ends on new data or on that clock, never on a sleep)."""

from __future__ import annotations

import threading
from collections.abc import Callable

import pytest
from rclpy.duration import Duration
from rclpy.task import Future
from rclpy.time import Time
from tf2_ros import Buffer, ExtrapolationException, LookupException

from .frames import stamped, xyz

BOUND_S = 10.0  # only bounds a broken run: every wait here ends on data or on the held clock


def held_clock(on_second_read: Callable[[], None] | None = None, step_s: float = 0.0) -> Callable[[], float]:
    """A monotonic clock that moves ``step_s`` per read; its second read is the wait's first look
    at the time, made holding the buffer's lock: ``on_second_read`` runs there."""
    reads = [0]

    def now() -> float:
        reads[0] += 1
        if reads[0] == 2 and on_second_read is not None:
            on_second_read()
        return step_s * reads[0]

    return now


def test_wait_for_transform_async_completes_with_the_transform_once_it_arrives() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "base", 1.0), "test")
    future = buffer.wait_for_transform_async("world", "gripper", Time())
    assert not future.done()
    buffer.set_transform(stamped("world", "base", 2.0), "test")  # not yet what it waits for
    assert not future.done()
    buffer.set_transform_static(stamped("base", "gripper", 0.0, (0.0, 0.0, 0.3)), "test")
    assert future.done()
    found = future.result()
    assert found is not None and xyz(found) == (0.0, 0.0, 0.3) and found.header.stamp.sec == 2
    assert buffer._new_data_callbacks == []  # it stopped listening once done


def test_wait_for_transform_async_is_done_at_once_when_the_transform_is_there() -> None:
    buffer = Buffer()
    buffer.set_transform_static(stamped("world", "mast", 0.0, (0.0, 0.0, 3.0)), "test")
    future = buffer.wait_for_transform_async("world", "mast", Time())
    assert future.done() and xyz(future.result()) == (0.0, 0.0, 3.0)  # type: ignore[arg-type]


def test_lookup_transform_async_parks_its_coroutine_until_the_transform_arrives() -> None:
    buffer = Buffer()
    lookup = buffer.lookup_transform_async("world", "robot", Time())
    parked_on = lookup.send(None)  # as an executor's task would run it: it waits on this future
    assert isinstance(parked_on, Future) and not parked_on.done()
    buffer.set_transform(stamped("world", "robot", 3.0, (0.0, 4.0, 0.0)), "test")
    assert parked_on.done()
    with pytest.raises(StopIteration) as finished:
        lookup.send(None)
    assert xyz(finished.value.value) == (0.0, 4.0, 0.0)


def test_lookup_with_a_timeout_returns_when_the_transform_arrives_while_it_waits() -> None:
    buffer = Buffer()
    waiting = threading.Event()
    buffer.monotonic = held_clock(waiting.set)  # the time never moves: only new data ends the wait

    def broadcast() -> None:
        assert waiting.wait(BOUND_S)
        buffer.set_transform(stamped("world", "robot", 7.0, (1.0, 2.0, 3.0)), "other thread")

    sender = threading.Thread(target=broadcast)
    sender.start()
    found = buffer.lookup_transform("world", "robot", Time(), timeout=Duration(seconds=BOUND_S))
    sender.join(BOUND_S)
    assert xyz(found) == (1.0, 2.0, 3.0) and found.header.stamp.sec == 7


def test_lookup_with_a_timeout_that_passes_raises_tf2s_exception() -> None:
    buffer = Buffer()
    buffer.set_transform(stamped("world", "robot", 1.0), "test")
    buffer.monotonic = held_clock(step_s=60.0)  # each read a minute on: the 1 s timeout is gone at once
    with pytest.raises(LookupException, match='"ghost" passed to lookupTransform argument source_frame'):
        buffer.lookup_transform("world", "ghost", Time(), timeout=Duration(seconds=1.0))
    with pytest.raises(ExtrapolationException, match=r"at time 2\.000000, but only time 1\.000000"):
        buffer.lookup_transform("world", "robot", Time(seconds=2), timeout=Duration(seconds=1.0))
    assert buffer.can_transform("world", "robot", Time(seconds=2), timeout=Duration(seconds=1.0)) is False


def test_a_timeout_that_is_not_a_duration_is_refused_saying_what_to_pass() -> None:
    with pytest.raises(TypeError, match=r"timeout must be an rclpy\.duration\.Duration .*got 1\.0"):
        Buffer().lookup_transform("a", "b", Time(), timeout=1.0)  # type: ignore[arg-type]
