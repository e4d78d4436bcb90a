"""The executor: callbacks run only when it spins; a fault stays inside its node; the asyncio loop."""

from __future__ import annotations

import asyncio
import logging

import pytest

from node_runtime.bus import Bus, Executor, ManualClock, Node, SystemClock
from node_runtime.msgs import Int64, Log


class _Faulty(Node):
    """Counts timer ticks and raises on the third; also listens on /chatter."""

    def __init__(self, bus: Bus) -> None:
        super().__init__("Faulty", context=bus)
        self.ticks = 0
        self.heard: list[int] = []
        self.timer = self.create_timer(0.1, self.tick)
        self.create_subscription(Int64, "/chatter", lambda m: self.heard.append(m.data), 10)

    def tick(self) -> None:
        self.ticks += 1
        if self.ticks == 3:
            raise RuntimeError("boom")


class _Healthy(Node):
    """Publishes a counter on /chatter at 10 Hz and records what it hears there."""

    def __init__(self, bus: Bus) -> None:
        super().__init__("Healthy", context=bus)
        self.count = 0
        self.heard: list[int] = []
        self.pub = self.create_publisher(Int64, "/chatter", 10)
        self.create_subscription(Int64, "/chatter", lambda m: self.heard.append(m.data), 10)
        self.create_timer(0.1, self.tick)

    def tick(self) -> None:
        self.count += 1
        self.pub.publish(Int64(data=self.count))


@pytest.fixture
def crashed(
    bus: Bus, executor: Executor, caplog: pytest.LogCaptureFixture
) -> tuple[_Faulty, _Healthy, list[Log]]:
    """A faulty and a healthy node run for 1 s; the faulty one raises at t=0.3."""
    logs: list[Log] = []
    Node("rqt_console", context=bus).create_subscription(Log, "/rosout", logs.append, 1000)
    faulty, healthy = _Faulty(bus), _Healthy(bus)
    crashes: list[tuple[str, str]] = []
    bus.crash_handlers.append(lambda node, exc: crashes.append((node.get_name(), str(exc))))
    with caplog.at_level(logging.ERROR):
        executor.spin_until(1.0)
    assert crashes == [("Faulty", "boom")]
    return faulty, healthy, logs


def test_callback_raises_node_marked_crashed_with_reason(
    crashed: tuple[_Faulty, _Healthy, list[Log]],
) -> None:
    faulty, _, _ = crashed
    assert faulty.state == "crashed"
    assert faulty.crash_reason == "RuntimeError: boom"


def test_callback_raises_crashed_node_timers_and_subscriptions_stop(
    crashed: tuple[_Faulty, _Healthy, list[Log]],
) -> None:
    faulty, _, _ = crashed
    assert faulty.ticks == 3 and faulty.timer.call_count == 3
    assert faulty.heard == [1, 2]  # heard up to the crash at t=0.3, nothing after


def test_callback_raises_other_nodes_keep_running_and_receiving(
    crashed: tuple[_Faulty, _Healthy, list[Log]], executor: Executor
) -> None:
    faulty, healthy, _ = crashed
    assert healthy.count == 10 and healthy.state == "active"
    assert healthy.heard == list(range(1, 11))
    executor.spin_until(2.0)
    assert healthy.heard[-1] == 20 and faulty.ticks == 3


def test_callback_raises_error_logged_with_node_name(
    crashed: tuple[_Faulty, _Healthy, list[Log]], caplog: pytest.LogCaptureFixture
) -> None:
    errors = [r for r in caplog.get_records("setup") if r.levelno >= logging.ERROR]
    assert any("/Faulty" in r.getMessage() and "boom" in r.getMessage() for r in errors)
    assert not any("Healthy" in r.getMessage() for r in errors)


def test_a_class_worlds_crash_is_logged_under_its_worlds_name(
    bus: Bus, executor: Executor, caplog: pytest.LogCaptureFixture
) -> None:
    bus.label = "ada"
    _Faulty(bus)
    with caplog.at_level(logging.ERROR):
        executor.spin_until(1.0)
    errors = {r.name: r.getMessage() for r in caplog.records if r.levelno >= logging.ERROR}
    assert errors.keys() == {
        "bus.executor",
        "world.ada.Faulty",
    }  # the traceback, and the node's own fatal line
    assert (
        errors["bus.executor"].startswith("[ada] node /Faulty crashed in")
        and "boom" in errors["bus.executor"]
    )


def test_callback_raises_fatal_log_on_rosout(crashed: tuple[_Faulty, _Healthy, list[Log]]) -> None:
    _, _, logs = crashed
    fatal = [m for m in logs if m.level == Log.FATAL]
    assert len(fatal) == 1
    assert fatal[0].name == "Faulty" and "RuntimeError: boom" in fatal[0].msg
    assert fatal[0].stamp.sec == 0 and fatal[0].stamp.nanosec == pytest.approx(300_000_000, abs=1)


def test_subscription_callback_raises_node_crashed_and_publisher_unaffected(
    bus: Bus, executor: Executor
) -> None:
    def explode(msg: Int64) -> None:
        raise ValueError(f"bad {msg.data}")

    listener = Node("listener", context=bus)
    listener.create_subscription(Int64, "/x", explode, 10)
    talker = Node("talker", context=bus)
    pub = talker.create_publisher(Int64, "/x", 10)
    pub.publish(Int64(data=1))
    pub.publish(Int64(data=2))
    assert executor.spin_some() == 1  # the second message died with the node
    assert listener.state == "crashed" and listener.crash_reason == "ValueError: bad 1"
    assert talker.state == "active"
    assert pub.publish(Int64(data=3)) == 0


def test_spin_same_instant_timers_later_one_sees_message_of_earlier(
    bus: Bus, clock: ManualClock, executor: Executor
) -> None:
    producer, consumer = Node("producer", context=bus), Node("consumer", context=bus)
    pub = producer.create_publisher(Int64, "/n", 10)
    ticks = iter(range(1, 100))
    producer.create_timer(0.1, lambda: pub.publish(Int64(data=next(ticks))))
    latest: list[int] = [0]
    consumer.create_subscription(Int64, "/n", lambda m: latest.__setitem__(0, m.data), 10)
    seen: list[int] = []
    consumer.create_timer(0.1, lambda: seen.append(latest[0]))
    executor.spin_until(0.35)
    assert seen == [1, 2, 3]  # fresh data, not last period's


def test_spin_until_system_clock_raises_type_error() -> None:
    with pytest.raises(TypeError, match="ManualClock"):
        Executor(Bus(SystemClock())).spin_until(1.0)


def test_spin_until_earlier_than_now_runs_due_work_and_keeps_time(
    bus: Bus, clock: ManualClock, executor: Executor
) -> None:
    clock.set(5.0)
    assert executor.spin_until(1.0) == 0
    assert clock.now() == 5.0


def test_spin_async_message_published_while_idle_wakes_callback() -> None:
    """The one test on the real clock: it awaits the callback's future, never a wall-clock time."""

    async def scenario() -> int:
        bus = Bus(SystemClock())
        executor = Executor(bus)
        loop = asyncio.get_running_loop()
        heard: asyncio.Future[int] = loop.create_future()
        node = Node("listener", context=bus)
        node.create_subscription(Int64, "/ping", lambda m: heard.done() or heard.set_result(m.data), 10)
        pub = Node("talker", context=bus).create_publisher(Int64, "/ping", 10)
        task = asyncio.create_task(executor.spin())
        await asyncio.sleep(0)  # let the executor go idle: no timers, nothing queued
        assert not heard.done()
        pub.publish(Int64(data=7))
        try:
            return await asyncio.wait_for(heard, timeout=10.0)
        finally:
            executor.stop()
            await asyncio.wait_for(task, timeout=10.0)

    assert asyncio.run(scenario()) == 7
