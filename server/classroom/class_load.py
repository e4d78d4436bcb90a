"""The class server's load as the instructor's panel and the join queue read it: each place's
worlds, CPU, memory and late worlds (this server's measured here, a world worker's as its last
hello said), and the verdict over them (capacity.py)."""

from __future__ import annotations

import asyncio
from collections.abc import Awaitable, Callable
from typing import Any

from server.classroom.capacity import SERVER_PLACE, Capacity, PlaceLoad, judge
from server.classroom.class_graph import ClassGraph
from server.classroom.lateness import late_worlds
from server.classroom.load import CpuMeter
from server.classroom.placement import Placement
from server.classroom.workers import WATCH_PERIOD_S, WorkerRef
from server.classroom.worlds import WorldLabs

FRESH_S = 3 * WATCH_PERIOD_S  # a watch round's answers younger than this stand for the workers now

LoadSource = Callable[[], Awaitable[list[PlaceLoad]]]
PlaceReport = tuple[list[PlaceLoad], Capacity, dict[str, Any]]  # each place's load, the verdict, the queue


class ClassLoad:
    """Reads the places' loads (``source``, replaceable by a test's fake) and judges them."""

    def __init__(
        self,
        labs: WorldLabs,
        graph: ClassGraph,
        cpu: CpuMeter,
        placement: Placement,
    ) -> None:
        self.labs = labs
        self.graph = graph
        self.cpu = cpu
        self.placement = placement
        self.source: LoadSource = self.measure

    async def places(self) -> list[PlaceLoad]:
        return await self.source()

    async def capacity(self) -> Capacity:
        """The verdict now; a ``full`` read from the last watch round's answers is read again from
        the workers themselves first (one may have come or freed room since), as placement would."""
        per_core = self.labs.class_settings.worlds_per_core
        capacity = judge(await self.places(), self._class_room(), per_core)
        if capacity.verdict == "full" and self.source == self.measure and self.graph.workers is not None:
            capacity = judge(await self.measure(fresh=True), self._class_room(), per_core)
        return capacity

    def _class_room(self) -> int:
        taken = len(self.labs.worlds) + len(self.labs.starting)
        return max(0, self.labs.class_settings.max_worlds - taken)

    async def measure(self, fresh: bool = False) -> list[PlaceLoad]:
        """This server (its own worlds and those starting here) and each world worker that
        answered the last watch round (or answers now, when that round is old)."""
        labs = self.labs
        here = [w.lab for w in labs.worlds.values() if w.worker is None]
        worlds_here = len(here) + self.placement.local_starting
        places = [
            PlaceLoad(SERVER_PLACE, worlds_here, labs.local_capacity, self.cpu.read(), late_worlds(here))
        ]
        for ref in await self._workers(fresh):
            ours = sum(1 for w in labs.worlds.values() if w.worker is not None and w.worker.id == ref.id)
            places.append(PlaceLoad(ref.id, max(ref.worlds, ours), ref.max_worlds, ref.load, ref.late))
        return places

    async def _workers(self, fresh: bool) -> list[WorkerRef]:
        workers = self.graph.workers
        if workers is None:
            return []
        answered = self.placement.answered
        if not fresh and answered is not None and self.labs.clock.now() - answered[0] < FRESH_S:
            return answered[1]
        return await asyncio.to_thread(workers.discover)
