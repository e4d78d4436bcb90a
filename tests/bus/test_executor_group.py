"""One task runs many buses' executors (a class server's worlds): each world's timers keep their
own deadlines, what a world publishes stays in that world, a world that is removed never runs
again, and a world that floods itself or whose executor fails leaves the others on time.

Time is a ManualClock: the test moves it and wakes the group, then lets the loop run the group's
round (a few yields of the event loop, never a wall-clock wait)."""

from __future__ import annotations

import asyncio
import logging
import threading

import pytest

from node_runtime.bus import Bus, Executor, ExecutorGroup, ManualClock, Node
from node_runtime.msgs import Int64


class World:
    """A bus with a ticking node that publishes its count and a node that hears it."""

    def __init__(self, clock: ManualClock, name: str, period_s: float) -> None:
        self.bus = Bus(clock)
        self.executor = Executor(self.bus)
        self.ticks = 0
        self.heard: list[int] = []
        talker = Node(f"{name}_talker", context=self.bus)
        self.pub = talker.create_publisher(Int64, "/count", 10)
        talker.create_timer(period_s, self.tick)
        Node(f"{name}_listener", context=self.bus).create_subscription(
            Int64, "/count", lambda m: self.heard.append(m.data), 10
        )

    def tick(self) -> None:
        self.ticks += 1
        self.pub.publish(Int64(data=self.ticks))


async def settle() -> None:
    for _ in range(5):
        await asyncio.sleep(0)


def grouped(*worlds: World, cost: ManualClock | None = None) -> ExecutorGroup:
    """A group running ``worlds``' executors (call inside the event loop). Its cost clock is a
    ManualClock that only the test's callbacks move, so no turn is cut short by the machine's speed."""
    group = ExecutorGroup(cost_clock=(cost or ManualClock()).now)
    for world in worlds:
        group.add(world.executor)
    return group


async def close(group: ExecutorGroup, *worlds: World) -> None:
    for world in worlds:
        group.remove(world.executor)
    await group.close()


async def step(group: ExecutorGroup, clock: ManualClock, until_s: float, dt_s: float = 0.01) -> None:
    """Move the clock to ``until_s`` in steps of ``dt_s``, letting the group run a round at each."""
    while clock.now() < until_s:
        clock.set(min(clock.now() + dt_s, until_s))
        group.wake()
        await settle()


def test_each_world_keeps_its_own_timer_and_hears_only_its_own_messages() -> None:
    async def scenario() -> None:
        clock = ManualClock()
        a, b = World(clock, "a", 0.1), World(clock, "b", 0.25)
        group = grouped(a, b)
        await step(group, clock, 1.0)
        assert (a.ticks, b.ticks) == (10, 4)
        # Each tick's message was delivered in the round that published it, in its own world only.
        assert a.heard == list(range(1, 11))
        assert b.heard == [1, 2, 3, 4]
        await close(group, a, b)

    asyncio.run(scenario())


def test_a_removed_world_never_runs_again_and_the_others_go_on() -> None:
    async def scenario() -> None:
        clock = ManualClock()
        a, b = World(clock, "a", 0.1), World(clock, "b", 0.1)
        group = grouped(a, b)
        await step(group, clock, 0.5)
        group.remove(b.executor)
        assert len(group) == 1
        await step(group, clock, 1.0)
        assert (a.ticks, b.ticks) == (10, 5)
        assert b.bus.threadsafe_waker is None  # the group let go of the bus
        await close(group, a)

    asyncio.run(scenario())


def test_a_world_flooding_itself_leaves_the_others_timers_on_time() -> None:
    """A node that answers every message with another keeps its world busy for ever; each round
    gives it one turn, and the quiet world's timer still runs at every deadline, as does the
    flooding world's own."""

    async def scenario() -> None:
        clock, cost = ManualClock(), ManualClock()
        quiet, noisy = World(clock, "quiet", 0.1), World(clock, "noisy", 0.1)
        echo = Node("echo", context=noisy.bus)
        loop_pub = echo.create_publisher(Int64, "/loop", 10)
        echoed: list[int] = []

        def again(msg: Int64) -> None:
            cost.advance(0.0001)  # each echo takes 0.1 ms of the loop
            echoed.append(msg.data)
            loop_pub.publish(Int64(data=msg.data + 1))

        echo.create_subscription(Int64, "/loop", again, 10)
        group = grouped(noisy, quiet, cost=cost)
        loop_pub.publish(Int64(data=0))
        await step(group, clock, 1.0, dt_s=0.1)
        assert quiet.ticks == 10
        assert quiet.heard == list(range(1, 11))
        assert noisy.ticks == 10  # its own timer too: a turn runs a due timer however full its queue
        per_turn = round(group.turn_s / 0.0001) + 1
        assert len(echoed) > 3 * per_turn  # the flood went on over several rounds
        await close(group, noisy, quiet)

    asyncio.run(scenario())


def test_a_world_whose_executor_fails_stops_alone(caplog: pytest.LogCaptureFixture) -> None:
    async def scenario() -> None:
        clock = ManualClock()
        broken, healthy = World(clock, "broken", 0.1), World(clock, "healthy", 0.1)

        def fail() -> None:
            if clock.now() >= 0.3:
                raise RuntimeError("inbox torn")

        broken.bus.pollers.append(fail)
        group = grouped(broken, healthy)
        with caplog.at_level(logging.ERROR):
            await step(group, clock, 1.0)
        assert healthy.ticks == 10
        assert broken.ticks == 2  # it ran until its executor failed at 0.3 s, then never again
        assert len(group) == 1
        assert "a world's executor failed" in caplog.text and "inbox torn" in caplog.text
        await close(group, healthy)

    asyncio.run(scenario())


def test_news_handed_in_from_another_thread_runs_that_worlds_pollers() -> None:
    """A Zenoh thread hands a sample in and wakes the bus; the group runs that world's pass."""

    async def scenario() -> None:
        clock = ManualClock()
        world = World(clock, "w", 1000.0)
        loop = asyncio.get_running_loop()
        polled: asyncio.Future[str] = loop.create_future()
        inbox: list[str] = []

        def poll() -> None:
            if inbox and not polled.done():
                polled.set_result(inbox.pop())

        world.bus.pollers.append(poll)
        group = grouped(world)
        await settle()  # the group is idle now: nothing due before t = 1000 s

        def hand_in() -> None:
            inbox.append("sample")
            world.bus.wake_threadsafe()

        thread = threading.Thread(target=hand_in)
        thread.start()
        thread.join(timeout=10)
        assert await asyncio.wait_for(polled, timeout=10) == "sample"
        await close(group, world)

    asyncio.run(scenario())
