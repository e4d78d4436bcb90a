"""The group shares the loop out by world: each world is charged the time its callbacks take, a
round gives the least used world its turn first, and a turn ends after ``turn_s``, so a world's
backlog waits for its next turn instead of holding up another world's tick.

Two ManualClocks: the bus clock (when timers are due) and the cost clock (what callbacks take),
which only the test's callbacks move; nothing here reads the wall clock."""

from __future__ import annotations

import asyncio

import pytest

from node_runtime.bus import Bus, Executor, ExecutorGroup, ManualClock, Node
from node_runtime.msgs import Int64

TURN_S = 0.002
MESSAGE_COST_S = 0.001  # each of the busy world's messages takes 1 ms of the loop
TICK_COST_S = 0.0001


class Busy:
    """A world with a backlog: ``burst()`` queues messages that each take ``MESSAGE_COST_S``."""

    def __init__(self, clock: ManualClock, cost: ManualClock, name: str = "busy") -> None:
        self.bus = Bus(clock)
        self.bus.label = name
        self.executor = Executor(self.bus)
        self.handled = 0
        node = Node("worker", context=self.bus)
        self.pub = node.create_publisher(Int64, "/work", 10_000)

        def handle(_: Int64) -> None:
            cost.advance(MESSAGE_COST_S)
            self.handled += 1

        node.create_subscription(Int64, "/work", handle, 10_000)

    def burst(self, count: int) -> None:
        for i in range(count):
            self.pub.publish(Int64(data=i))


class Quiet:
    """A world with a 100 Hz tick that notes, on the cost clock, when each tick ran."""

    def __init__(self, clock: ManualClock, cost: ManualClock, name: str) -> None:
        self.bus = Bus(clock)
        self.bus.label = name
        self.executor = Executor(self.bus)
        self.ran_at: list[float] = []

        def tick() -> None:
            self.ran_at.append(cost.now())
            cost.advance(TICK_COST_S)

        Node("dynamics", context=self.bus).create_timer(0.01, tick)


async def settle() -> None:
    for _ in range(5):
        await asyncio.sleep(0)


def test_a_quiet_worlds_tick_waits_for_no_other_worlds_backlog() -> None:
    """The busy world is added first and has a second of work queued; at each of the quiet
    world's deadlines its tick runs before the busy world's next turn, while the busy world still
    gets a turn of about ``TURN_S`` a round and so works its backlog off."""

    async def scenario() -> None:
        clock, cost = ManualClock(), ManualClock()
        busy, quiet = Busy(clock, cost), Quiet(clock, cost, "quiet")
        group = ExecutorGroup(cost_clock=cost.now, turn_s=TURN_S)
        group.add(busy.executor)
        group.add(quiet.executor)
        busy.burst(1000)
        for k in range(1, 11):
            clock.set(k * 0.01)
            due_at = cost.now()  # the loop's time when the tick came due
            group.wake()
            await settle()
            assert len(quiet.ran_at) == k
            assert quiet.ran_at[-1] - due_at <= TURN_S + MESSAGE_COST_S
        # A turn of 2 ms takes 2 or 3 of the busy world's 1 ms messages, and it got some each round.
        assert 10 < busy.handled < 1000
        handled, rounds = busy.handled, 0
        while busy.handled < 1000 and rounds < 1000:
            group.wake()
            await asyncio.sleep(0)
            rounds += 1
        assert busy.handled == 1000  # its backlog was put off, never dropped
        assert rounds >= (1000 - handled) // (round(TURN_S / MESSAGE_COST_S) + 1)
        group.remove(busy.executor)
        group.remove(quiet.executor)
        await group.close()

    asyncio.run(scenario())


def test_each_world_is_charged_what_its_callbacks_took_and_the_charge_decays() -> None:
    async def scenario() -> None:
        clock, cost = ManualClock(), ManualClock()
        busy, quiet = Busy(clock, cost), Quiet(clock, cost, "quiet")
        group = ExecutorGroup(cost_clock=cost.now, turn_s=1.0, half_life_s=1.0)
        group.add(busy.executor)
        group.add(quiet.executor)
        busy.burst(30)
        clock.set(0.01)
        group.wake()
        await settle()
        assert busy.handled == 30 and len(quiet.ran_at) == 1
        assert group.usage_s(busy.executor) == pytest.approx(30 * MESSAGE_COST_S)
        assert group.usage_s(quiet.executor) == pytest.approx(TICK_COST_S)
        cost.advance(1.0)  # a half-life of the loop's time with nothing run
        group.wake()
        await settle()
        # It decays in steps (from the last step, 30 ms before these callbacks ended): about half.
        assert group.usage_s(busy.executor) == pytest.approx(15 * MESSAGE_COST_S, rel=0.05)
        assert group.usage_s(quiet.executor) == pytest.approx(TICK_COST_S / 2, rel=0.05)
        group.remove(busy.executor)
        group.remove(quiet.executor)
        await group.close()

    asyncio.run(scenario())


def test_the_least_used_world_has_the_first_turn_and_a_reset_keeps_the_charge() -> None:
    """Two worlds both due: the one that used less goes first. A world started again under the
    same name (a reset gives it a new bus and executor) keeps its charge and is charged what its
    start took; a new name starts at 0."""

    async def scenario() -> None:
        clock, cost = ManualClock(), ManualClock()
        heavy, light = Quiet(clock, cost, "heavy"), Quiet(clock, cost, "light")
        group = ExecutorGroup(cost_clock=cost.now, turn_s=TURN_S)
        group.add(heavy.executor)
        group.add(light.executor)
        Node("spender", context=heavy.bus).create_timer(0.01, lambda: cost.advance(0.005))
        clock.set(0.01)
        group.wake()
        await settle()
        assert group.usage_s(heavy.executor) > group.usage_s(light.executor)
        clock.set(0.02)
        group.wake()
        await settle()
        assert light.ran_at[-1] < heavy.ran_at[-1]  # added second, ran first: it used less
        charged = group.usage_s(heavy.executor)

        group.remove(heavy.executor)  # the reset: the same world, a new bus, charged its start
        again = Quiet(clock, cost, "heavy")
        group.add(again.executor, charge_s=0.1)
        assert group.usage_s(again.executor) == pytest.approx(charged + 0.1)
        clock.set(0.03)
        group.wake()
        await settle()
        assert light.ran_at[-1] < again.ran_at[-1]  # still after the light world
        newcomer = Quiet(clock, cost, "newcomer")
        group.add(newcomer.executor)
        assert group.usage_s(newcomer.executor) == 0.0
        for world in (light, again, newcomer):
            group.remove(world.executor)
        await group.close()

    asyncio.run(scenario())


def test_a_turn_that_is_over_still_runs_one_message_and_one_due_timer() -> None:
    """``spin_some`` with a turn that is already over: one queued message, then one due timer
    (with one message it published), and the rest stay for the next turn."""
    clock = ManualClock()
    bus = Bus(clock)
    executor = Executor(bus)
    node = Node("n", context=bus)
    pub = node.create_publisher(Int64, "/x", 100)
    heard: list[int] = []
    node.create_subscription(Int64, "/x", lambda m: heard.append(m.data), 100)
    ticks: list[str] = []
    for name in ("a", "b"):
        node.create_timer(0.1, lambda name=name: (ticks.append(name), pub.publish(Int64(data=-1))))
    for i in range(5):
        pub.publish(Int64(data=i))
    clock.set(0.1)
    assert executor.spin_some(lambda: True) == 3
    assert heard == [0, 1] and ticks == ["a"]
    assert executor.spin_some() == 6  # without a turn: everything left
    assert heard == [0, 1, 2, 3, 4, -1, -1] and ticks == ["a", "b"]


def test_a_turn_must_be_positive() -> None:
    with pytest.raises(ValueError, match="turn_s"):
        ExecutorGroup(turn_s=0.0)
