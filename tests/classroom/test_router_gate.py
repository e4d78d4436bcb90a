"""The gate between worlds that start and the class's router opening again (server/classroom/router_gate.py)."""

from __future__ import annotations

import asyncio

from server.classroom.router_gate import RouterGate


def test_worlds_start_together_and_a_reopening_waits_for_them_and_goes_before_later_ones() -> None:
    async def run() -> list[str]:
        gate, order = RouterGate(), []
        first_in, release_first = asyncio.Event(), asyncio.Event()

        async def world(
            name: str, hold: asyncio.Event | None = None, entered: asyncio.Event | None = None
        ) -> None:
            async with gate.use():
                order.append(f"{name} in")
                if entered is not None:
                    entered.set()
                if hold is not None:
                    await hold.wait()
                order.append(f"{name} out")

        async def reopen() -> None:
            async with gate.reopening():
                order.append("reopen")
                await asyncio.sleep(0)
                order.append("reopened")

        first = asyncio.create_task(world("a", release_first, first_in))
        await first_in.wait()
        second = asyncio.create_task(world("b"))  # alongside a: worlds do not wait for each other
        await second
        reopening = asyncio.create_task(reopen())
        for _ in range(5):
            await asyncio.sleep(0)
        later = asyncio.create_task(world("c"))  # comes after the reopening: waits behind it
        for _ in range(5):
            await asyncio.sleep(0)
        assert order == ["a in", "b in", "b out"]  # the reopening waits for a, and c for it
        release_first.set()
        await asyncio.gather(first, reopening, later)
        return order

    assert asyncio.run(run()) == ["a in", "b in", "b out", "a out", "reopen", "reopened", "c in", "c out"]


def test_a_reopening_given_up_while_it_waits_holds_no_world_back() -> None:
    async def run() -> None:
        gate = RouterGate()
        entered, later_in, release = asyncio.Event(), asyncio.Event(), asyncio.Event()

        async def world(entered: asyncio.Event, hold: asyncio.Event | None = None) -> None:
            async with gate.use():
                entered.set()
                if hold is not None:
                    await hold.wait()

        async def reopen() -> None:
            async with gate.reopening():
                pass

        holder = asyncio.create_task(world(entered, release))
        await entered.wait()
        waiting = asyncio.create_task(reopen())
        for _ in range(5):
            await asyncio.sleep(0)
        later = asyncio.create_task(world(later_in))  # behind the waiting reopening
        for _ in range(5):
            await asyncio.sleep(0)
        assert not later_in.is_set()
        waiting.cancel()
        await asyncio.gather(waiting, return_exceptions=True)
        async with asyncio.timeout(5):
            await later_in.wait()  # let in once the reopening is given up, while the holder still holds
        release.set()
        await asyncio.gather(holder, later)

    asyncio.run(run())
