"""Where a class's worlds run: on the class server or on a world worker, and again elsewhere when
their worker goes.

A new world goes where the load is lowest (worlds over capacity), never to a place whose CPU is
saturated (load.py), nor to a machine that has its world budget (budget.py), while another has
room. The class server says hello to its workers every ``WATCH_PERIOD_S``; the worlds of a
worker silent for ``--worker-timeout``, or of one that answers but no longer hosts them, start
again elsewhere under the same names, domains and tokens. A world a worker hosts that the class
does not count there (removed or moved while the worker was cut off) is ended.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import Awaitable, Callable
from typing import Any

from node_runtime.transport.acl import Credentials
from server.classroom.budget import within_budget
from server.classroom.capacity import SERVER_PLACE
from server.classroom.class_graph import ClassGraph
from server.classroom.errors import ClassroomError, NoRoomError, WorkerRefusedError
from server.classroom.load import Choice, CpuLoad, CpuMeter, choose
from server.classroom.progress_copies import ProgressCopies
from server.classroom.remote_worlds import on_workers
from server.classroom.workers import WATCH_PERIOD_S, Silence, WorkerRef
from server.classroom.workspace_copies import WorkspaceCopies
from server.classroom.world import World
from server.classroom.worlds import WorldLabs
from server.host.settings import Settings, class_section
from server.world.lab import Lab

log = logging.getLogger("classroom")


class Placement:
    """The class server's placing and its watch over the workers; ``end`` ends a world wherever
    it runs."""

    def __init__(
        self,
        settings: Settings,
        labs: WorldLabs,
        graph: ClassGraph,
        cpu: CpuMeter,
        end: Callable[[World], Awaitable[None]],
        copies: ProgressCopies | None = None,
        workspaces: WorkspaceCopies | None = None,
    ) -> None:
        self.settings = settings
        self.class_settings = class_section(settings)
        self.labs = labs
        self.graph = graph
        self.cpu = cpu
        self._end = end
        self.copies = copies  # the progress of worlds on workers with folders of their own
        self.workspaces = workspaces  # and their files
        self._hosting: set[tuple[str, str]] = set()  # (worker id, world) while it is placed there
        self._local_starting = 0  # worlds being started here
        self._silent_workers = Silence(self.class_settings.worker_timeout_s)
        # The workers that answered the last watch round, and when (the load panel reads them).
        self.answered: tuple[float, list[WorkerRef]] | None = None

    @property
    def local_starting(self) -> int:
        """Worlds being started on this server now."""
        return self._local_starting

    async def start(
        self, name: str, student: str, domain_id: int, login: Credentials | None, exclude: str | None = None
    ) -> tuple[Lab | None, WorkerRef | None]:
        """Place world ``name`` and start it there: its lab when here, else the worker it is on."""
        place = await self._place(exclude=exclude)
        if place is not None:
            await self._host_on(place, name, student, domain_id, login)
            return None, place
        self._local_starting += 1
        try:
            return await self.labs.start(name, domain_id, login=login), None
        finally:
            self._local_starting -= 1

    async def _place(self, exclude: str | None = None) -> WorkerRef | None:
        """Where a new world goes: here or the world worker with the lowest load (worlds over
        capacity), but never a place whose CPU is saturated (``load.py``) while another has room,
        nor one on a machine at its world budget (``budget.py``) while another machine has some;
        on a tie a worker, so the class server keeps its core for the pages. Never on worker
        ``exclude``."""
        capacity = self.labs.local_capacity
        local = self.labs.hosted_here + self._local_starting
        here = self.cpu.read()
        places: list[tuple[str, int, CpuLoad | None]] = [(SERVER_PLACE, local, here)]
        choices: list[tuple[str, Choice[WorkerRef]]] = []
        if local < capacity:
            choices.append((SERVER_PLACE, Choice(local / max(capacity, 1), None, here)))
        workers = self.graph.workers
        refs = await asyncio.to_thread(workers.discover) if workers is not None else []
        on = on_workers(self.labs.worlds)
        for ref in refs:
            ours = len(on[ref.id][1]) if ref.id in on else 0
            placing = sum(1 for wid, _ in self._hosting if wid == ref.id)
            worlds = max(ref.worlds, ours) + placing
            places.append((ref.id, worlds, ref.load))
            if ref.id != exclude and worlds < ref.max_worlds:
                choices.append((ref.id, Choice(worlds / ref.max_worlds, ref, ref.load)))
        if not choices:
            raise NoRoomError(
                f"no room for another world: this server hosts {capacity} itself "
                f"(--local-worlds) and {'no world worker has room' if refs else 'no world worker answered'}"
            )
        best, full = choose(within_budget(choices, places, self.class_settings.worlds_per_core))
        if full:
            log.warning(
                "every place with room for a new world is saturated (CPU): placing it on the least full"
            )
        return best.ref

    async def _host_on(
        self, ref: WorkerRef, name: str, student: str, domain_id: int, login: Credentials | None
    ) -> None:
        assert self.graph.workers is not None
        self._hosting.add((ref.id, name))
        try:
            body: dict[str, Any] = {
                "world": name,
                "student": student,
                "domain_id": domain_id,
                "launch": self.settings.lab.launch,
                "launch_args": self.settings.lab.launch_args,
            }
            if login is not None:  # the world's own login: its graph joins the router with it
                body |= {"zenoh_user": login.user, "zenoh_password": login.password}
            socket = self.graph.process_socket()
            if socket is not None:  # a worker on this machine runs students' nodes through it
                body["router_socket"] = str(socket)
            handed = await self.copies.handover(ref, name) if self.copies is not None else None
            if handed is not None:  # its progress, which that worker's own folder does not hold
                body["progress"] = handed
            await self.graph.workers.checked(ref, "POST", "/api/classroom/host", body=body)
            if self.workspaces is not None:  # its files, before its student can reach it there
                try:
                    await self.workspaces.hand_over(self.graph.workers, ref, name)
                except ClassroomError:  # not started there after all: never run it without its files
                    with contextlib.suppress(ClassroomError):
                        await self.graph.workers.checked(ref, "DELETE", f"/api/classroom/worlds/{name}")
                    raise
        finally:
            self._hosting.discard((ref.id, name))

    # -- workers that go -----------------------------------------------------------------------
    async def watch(self) -> None:
        """Say hello to the workers every few seconds, and act on what they answer."""
        while self.graph.workers is not None:
            await asyncio.sleep(WATCH_PERIOD_S)
            self.cpu.read()  # a new window: a placement weighs the last seconds, not all since the last join
            try:
                await self.watch_once()
            except Exception:  # the watch must outlive any one round
                log.exception("watching the world workers failed; trying again")

    async def watch_once(self) -> None:
        workers, worlds, clock = self.graph.workers, self.labs.worlds, self.labs.clock
        assert workers is not None
        asked_at = clock.now()
        answered = await asyncio.to_thread(workers.discover)
        now = clock.now()
        self.answered = now, answered
        answering = {ref.id for ref in answered}
        for ref in answered:
            self._silent_workers.heard(ref.id, now)
        hosting = {w.worker.id for w in worlds.values() if w.worker is not None}
        gone = self._silent_workers.silent(hosting, now)
        # A worker that answers but no longer hosts a world placed on it before this hello (it
        # restarted, or freed its worlds while cut off): that world is gone too.
        missing = {
            (ref.id, name)
            for ref in answered
            if ref.hosted is not None
            for name, world in worlds.items()
            if world.worker is not None
            and world.worker.id == ref.id
            and world.placed_at < asked_at
            and name not in ref.hosted
        }
        await self._end_strays(answered)
        if self.copies is not None:
            await self.copies.refresh(workers, worlds, answered)
        if self.workspaces is not None:
            await self.workspaces.refresh(workers, worlds, answered)
        for world in list(worlds.values()):
            if world.worker is None:
                continue
            if world.worker.id in gone:
                why = f"no hello for {self.class_settings.worker_timeout_s:g} s"
            elif (world.worker.id, world.name) in missing:
                why = "it answers but no longer hosts this world (restarted?)"
            elif world.lost is not None:
                why = "still waiting for room"
            else:
                continue
            # Never back onto a worker that did not answer this round.
            await self._move(
                world, why, exclude=world.worker.id if world.worker.id not in answering else None
            )

    async def _end_strays(self, answered: list[WorkerRef]) -> None:
        """End each world a worker says it hosts that this class server does not count on it: one
        the instructor removed, or one that moved elsewhere, while that worker could not be
        reached. (Worlds being placed there now are not strays.)"""
        workers, worlds = self.graph.workers, self.labs.worlds
        assert workers is not None
        for ref in answered:
            ours = {name for name, w in worlds.items() if w.worker is not None and w.worker.id == ref.id}
            placing = {name for wid, name in self._hosting if wid == ref.id}
            for name in sorted((ref.hosted or frozenset()) - ours - placing - set(self.labs.starting)):
                log.warning(
                    "world worker %s still hosts world %s, which this class does not count there: ending it",
                    ref.id,
                    name,
                )
                try:
                    await workers.checked(ref, "DELETE", f"/api/classroom/worlds/{name}")
                except WorkerRefusedError as exc:
                    if exc.answered != 404:  # the worker has no such world: it ended meanwhile
                        log.warning("world %s on world worker %s: %s", name, ref.id, exc)
                except ClassroomError as exc:
                    log.warning("world %s on world worker %s: %s", name, ref.id, exc)

    async def _move(self, world: World, why: str, exclude: str | None) -> None:
        """Start a world whose worker is gone again, here or on another worker; its student's
        token and ROS domain stay, its state starts over (as after a reset)."""
        gone = world.worker
        assert gone is not None
        if world.lost is None:
            log.warning("world worker %s lost world %s (%s): moving it", gone.id, world.name, why)
        world.lost = (
            f"world {world.name!r} was lost by world worker {gone.id!r} ({why}); it is starting again"
        )
        try:
            async with self.graph.gate.use():
                lab, place = await self.start(
                    world.name, world.student, world.domain_id, world.login, exclude=exclude
                )
        except ClassroomError as exc:
            world.lost = f"{world.lost}, when there is room ({exc})"
            return
        if self.labs.worlds.get(world.name) is not world:  # kicked while it started
            await self._end(World(world.name, world.student, world.token_id, lab, world.writes, worker=place))
            return
        world.lab, world.worker, world.lost = lab, place, None
        world.moves += 1
        world.placed_at = self.labs.clock.now()
        where = f"world worker {place.id}" if place is not None else "the class server"
        log.info("world %s started again on %s", world.name, where)
