"""Queue depths and timers: keep-last depth validation; timers at exact deadlines on the manual clock."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from node_runtime.bus import Bus, Executor, InvalidQoSError, ManualClock, Node
from node_runtime.msgs import Int64


# -- queue depth ------------------------------------------------------------------------------
@pytest.mark.parametrize("depth", [0, -1, 1.5, True, "10", None, 10_001])
def test_create_endpoint_invalid_depth_raises(bus: Bus, depth: object) -> None:
    node = Node("n", context=bus)
    with pytest.raises(InvalidQoSError) as err:
        node.create_subscription(Int64, "/x", lambda m: None, depth)
    assert isinstance(err.value, ValueError)
    with pytest.raises(InvalidQoSError):
        node.create_publisher(Int64, "/y", depth)
    assert "/x" not in bus.topics and "/y" not in bus.topics


@pytest.mark.parametrize("depth", [1, 10, 10_000])
def test_create_endpoint_valid_depth_is_kept(bus: Bus, depth: int) -> None:
    node = Node("n", context=bus)
    assert node.create_subscription(Int64, "/x", lambda m: None, depth).depth == depth
    assert node.create_publisher(Int64, "/x", depth).depth == depth


def test_create_subscription_qos_profile_with_depth_is_accepted(bus: Bus) -> None:
    node = Node("n", context=bus)
    sub = node.create_subscription(Int64, "/x", lambda m: None, SimpleNamespace(depth=3))
    assert sub.depth == 3 and sub.queue.maxlen == 3


# -- transient local --------------------------------------------------------------------------
def test_a_late_transient_local_subscription_gets_what_transient_local_publishers_kept(
    bus: Bus, executor: Executor
) -> None:
    latched, kept_last_two = SimpleNamespace(depth=5, durability=1), SimpleNamespace(depth=2, durability=1)
    node = Node("n", context=bus)
    node.create_publisher(Int64, "/map", kept_last_two).publish(Int64(data=1))
    latching = node.create_publisher(Int64, "/map", kept_last_two)
    for n in (2, 3, 4):
        latching.publish(Int64(data=n))
    node.create_publisher(Int64, "/map", 5).publish(Int64(data=99))  # volatile: keeps nothing
    late: list[int] = []
    node.create_subscription(Int64, "/map", lambda m: late.append(m.data), latched)
    volatile: list[int] = []
    node.create_subscription(Int64, "/map", lambda m: volatile.append(m.data), 5)
    executor.spin_some()
    assert late == [1, 3, 4] and volatile == []  # each publisher's last two, in its order
    latching.publish(Int64(data=5))  # the marker: from now on both hear alike
    executor.spin_some()
    assert late == [1, 3, 4, 5] and volatile == [5]


# -- timers -----------------------------------------------------------------------------------
def test_timer_10hz_over_10s_fires_100_times_at_exact_deadlines(
    bus: Bus, clock: ManualClock, executor: Executor
) -> None:
    times: list[float] = []
    timer = Node("n", context=bus).create_timer(0.1, lambda: times.append(clock.now()))
    executor.spin_until(10.0)
    assert len(times) == 100 and timer.call_count == 100
    assert times == pytest.approx([0.1 * k for k in range(1, 101)], abs=1e-9)
    assert clock.now() == 10.0


def test_timer_just_before_deadline_does_not_fire(bus: Bus, clock: ManualClock, executor: Executor) -> None:
    timer = Node("n", context=bus).create_timer(0.1, lambda: None)
    clock.set(0.0999)
    assert executor.spin_some() == 0
    clock.set(0.1)
    assert executor.spin_some() == 1 and timer.call_count == 1


def test_timer_created_later_keeps_its_own_phase(bus: Bus, clock: ManualClock, executor: Executor) -> None:
    clock.set(0.25)
    times: list[float] = []
    Node("n", context=bus).create_timer(1.0, lambda: times.append(clock.now()))
    executor.spin_until(3.5)
    assert times == pytest.approx([1.25, 2.25, 3.25])


def test_timer_clock_jumps_fires_once_then_keeps_phase(
    bus: Bus, clock: ManualClock, executor: Executor
) -> None:
    times: list[float] = []
    timer = Node("n", context=bus).create_timer(0.1, lambda: times.append(clock.now()))
    clock.set(0.95)  # nine deadlines missed at once
    assert executor.spin_some() == 1
    assert timer.next_deadline_s == pytest.approx(1.0)
    executor.spin_until(1.25)
    assert times == pytest.approx([0.95, 1.0, 1.1, 1.2])


def test_timer_calls_skipped_are_counted_on_the_bus(bus: Bus, clock: ManualClock, executor: Executor) -> None:
    fast = Node("n", context=bus).create_timer(0.1, lambda: None)
    Node("m", context=bus).create_timer(1.0, lambda: None)
    executor.spin_until(0.35)  # on time: 0.1, 0.2, 0.3
    assert (bus.timer_calls, bus.timer_calls_skipped) == (3, 0)
    clock.set(0.95)  # one call for 0.4, the calls due at 0.5 to 0.9 skipped
    executor.spin_some()
    assert (bus.timer_calls, bus.timer_calls_skipped) == (4, 5)
    executor.spin_until(1.25)  # 1.0 (both timers), 1.1, 1.2: on time again
    assert (bus.timer_calls, bus.timer_calls_skipped) == (8, 5)
    assert fast.call_count == 7


def test_timer_cancel_stops_calls(bus: Bus, clock: ManualClock, executor: Executor) -> None:
    calls: list[float] = []
    timer = Node("n", context=bus).create_timer(0.5, lambda: calls.append(clock.now()))
    executor.spin_until(1.2)
    timer.cancel()
    executor.spin_until(5.0)
    assert calls == pytest.approx([0.5, 1.0])
    assert timer.is_canceled()


def test_timer_reset_restarts_period_from_now(bus: Bus, clock: ManualClock, executor: Executor) -> None:
    calls: list[float] = []
    timer = Node("n", context=bus).create_timer(1.0, lambda: calls.append(clock.now()))
    executor.spin_until(0.5)
    timer.reset()
    executor.spin_until(2.6)
    assert calls == pytest.approx([1.5, 2.5])


def test_timer_reset_after_cancel_resumes(bus: Bus, clock: ManualClock, executor: Executor) -> None:
    calls: list[float] = []
    timer = Node("n", context=bus).create_timer(1.0, lambda: calls.append(clock.now()))
    executor.spin_until(1.0)
    timer.cancel()
    executor.spin_until(3.0)
    timer.reset()
    assert not timer.is_canceled()
    executor.spin_until(5.0)
    assert calls == pytest.approx([1.0, 4.0, 5.0])


def test_timer_destroyed_never_fires_again(bus: Bus, clock: ManualClock, executor: Executor) -> None:
    node = Node("n", context=bus)
    calls: list[float] = []
    timer = node.create_timer(0.1, lambda: calls.append(clock.now()))
    executor.spin_until(0.35)
    timer.destroy()
    executor.spin_until(1.0)
    assert len(calls) == 3
    assert timer not in node.timers


@pytest.mark.parametrize("period", [0, -0.1, 1e8, "0.1"])
def test_create_timer_invalid_period_raises(bus: Bus, period: object) -> None:
    with pytest.raises(ValueError):
        Node("n", context=bus).create_timer(period, lambda: None)  # type: ignore[arg-type]


def test_timers_two_periods_interleave_in_deadline_order(
    bus: Bus, clock: ManualClock, executor: Executor
) -> None:
    order: list[tuple[str, float]] = []
    node = Node("n", context=bus)
    node.create_timer(0.3, lambda: order.append(("slow", clock.now())))
    node.create_timer(0.2, lambda: order.append(("fast", clock.now())))
    executor.spin_until(1.0)
    times = [t for _, t in order]
    assert times == sorted(times)
    assert times == pytest.approx([0.2, 0.3, 0.4, 0.6, 0.6, 0.8, 0.9, 1.0])
    assert [t for name, t in order if name == "slow"] == pytest.approx([0.3, 0.6, 0.9])


def test_spin_until_with_nothing_due_moves_clock_and_runs_nothing(
    bus: Bus, clock: ManualClock, executor: Executor
) -> None:
    Node("n", context=bus)
    assert executor.spin_until(7.0) == 0
    assert clock.now() == 7.0
    assert executor.spin_for(0.5) == 0
    assert clock.now() == 7.5
