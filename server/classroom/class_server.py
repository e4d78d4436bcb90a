"""The class server: a world per student, joined with the class code, placed here or on a world
worker, shown to the instructor in one 3D view and in the class's own ROS domain.

It is the one place the class's parts meet: who may do what (grants.py), the worlds' labs
(worlds.py), the class's Zenoh graph (class_graph.py), where worlds run (placement.py), what its
workers' worlds report (remote_worlds.py) and the instructor's view (server/peripherals/viewer/class_view.py).
"""

from __future__ import annotations

import asyncio
import hmac
import logging
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from node_runtime.bus import Clock, ExecutorGroup, SystemClock
from node_runtime.limits import RateLimit
from node_runtime.transport.acl import ClassAuth
from server.base.tasks import cancel_and_wait
from server.classroom import remote_checkpoints, remote_worlds
from server.classroom.admission import Admission, check_student_name, new_code
from server.classroom.class_graph import ClassGraph
from server.classroom.class_load import ClassLoad, PlaceReport
from server.classroom.errors import (
    AtCapacityError,
    BadNameError,
    ClassFullError,
    NameTakenError,
    NotHereError,
    RateLimitedError,
    UnknownWorldError,
)
from server.classroom.grants import Grants, world_for
from server.classroom.join_queue import JoinQueue, JoinWaits
from server.classroom.load import CpuMeter, machine_id
from server.classroom.local_workers import LocalWorkers, local_workers_for
from server.classroom.placement import Placement
from server.classroom.progress_copies import ProgressCopies
from server.classroom.saved_students import SavedStudents
from server.classroom.tokens import Grant, TokenSigner, read_class_secret
from server.classroom.workspace_copies import WorkspaceCopies
from server.classroom.world import World, world_name
from server.classroom.world import drones as world_drones
from server.classroom.worlds import WorldLabs
from server.host.processes.start_pacing import StartPacer
from server.host.settings import Settings, class_section
from server.services.workspace.location import remove_world_workspace, world_has_files
from server.world.checkpoints.catalog import load as load_checkpoints
from server.world.checkpoints.progress import Progress

if TYPE_CHECKING:
    from node_runtime.transport.acl import Credentials
    from node_runtime.transport.domain_bridge import DomainBridge
    from server.classroom.class_bridges import ClassBridges
    from server.classroom.workers import WorkerDirectory
    from server.peripherals.viewer.class_view import ClassView

log = logging.getLogger("classroom")


class ClassServer:
    """The worlds of one class, and who may do what in them (a ``Classroom``, roles.py)."""

    def __init__(
        self,
        settings: Settings,
        clock: Clock | None = None,
        *,
        code: str | None = None,
        signer: TokenSigner | None = None,
    ) -> None:
        self.settings = settings
        self.class_settings = class_section(settings)
        self.clock: Clock = clock or SystemClock()
        self.code = code or new_code()
        secret_file = self.class_settings.class_secret_file
        # The class secret, when given: the same instructor's token at every start (tokens.py).
        self.grants = Grants(signer or (TokenSigner(read_class_secret(secret_file)) if secret_file else None))
        self.admission = Admission(self.class_settings.joins, self.clock)
        worlds: dict[str, World] = {}  # the class's, which its graph shows in the class domain
        self.graph = ClassGraph(settings, worlds, self.grants.instructor_token)
        self.labs = WorldLabs(settings, self.clock, self.graph.endpoint, self.graph.process_socket, worlds)
        # This process's and machine's CPU, read every WATCH_PERIOD_S (a watch round): a
        # placement weighs the last seconds.
        self.cpu = CpuMeter(machine=machine_id())
        # A copy of the progress of worlds on workers that keep it in folders of their own.
        self.progress_copies = ProgressCopies(self.labs.progress, load_checkpoints(settings.lab.checkpoints))
        # A copy of the files of worlds on workers that keep them in folders of their own.
        self.workspace_copies = WorkspaceCopies(self.class_settings.workspaces_dir, settings.workspace)
        self.placement = Placement(
            settings, self.labs, self.graph, self.cpu, self._end, self.progress_copies, self.workspace_copies
        )
        self.load = ClassLoad(self.labs, self.graph, self.cpu, self.placement)
        self.queue = JoinQueue(self.class_settings.join_queue, self.clock)
        # The progress and code on disk: whose each world's are, and those not joined since the start.
        self.saved = SavedStudents(
            self.labs.progress,
            lambda: load_checkpoints(settings.lab.checkpoints),
            lambda name: world_has_files(self.class_settings.workspaces_dir, name),
        )
        self.local_workers: LocalWorkers | None = None  # world workers started here (--workers)
        self.view: ClassView | None = None  # the instructor's 3D view of every world
        self._tasks: list[asyncio.Task[None]] = []  # the watch over the workers, the view's loop

    # -- what the routes read ------------------------------------------------------------------
    @property
    def worlds(self) -> dict[str, World]:
        return self.labs.worlds

    @property
    def executors(self) -> ExecutorGroup:
        return self.labs.executors

    @property
    def instructor_token(self) -> str:
        return self.grants.instructor_token

    @property
    def workers(self) -> WorkerDirectory | None:
        return self.graph.workers

    @property
    def class_graph(self) -> DomainBridge | None:
        return self.graph.bridge

    @property
    def bridges(self) -> ClassBridges | None:
        return self.graph.bridges

    @property
    def hosted_here(self) -> int:
        return self.labs.hosted_here

    @property
    def local_capacity(self) -> int:
        return self.labs.local_capacity

    @property
    def start_pacer(self) -> StartPacer:
        return self.labs.start_pacer

    @property
    def zenoh_auth(self) -> ClassAuth:
        """The class's Zenoh logins, from the instructor's token."""
        return self.graph.auth

    def router_endpoint(self) -> str | None:
        return self.graph.endpoint()

    # -- who is calling ------------------------------------------------------------------------
    def grant(self, token: str | None) -> Grant | None:
        """The grant of a genuine, current token: a student's world must still be theirs."""
        return self.grants.check(token, self.worlds) if token else None

    def world_for(self, grant: Grant, asked: str | None) -> World:
        return world_for(grant, asked, self.worlds)

    def get(self, name: str) -> World:
        return self.labs.get(name)

    def charge_write(self, world: World) -> None:
        """A student's write to ``world``, charged here (its world worker, if any, charges none)."""
        if not world.writes.take():
            raise RateLimitedError(
                f"too many requests for world {world.name!r}: at most "
                f"{self.class_settings.world.writes_hz:g} writes a second",
                world.writes.retry_after_s(),
            )

    def charge_reset(self, name: str) -> None:
        self.labs.charge_reset(name)

    # -- start and stop ------------------------------------------------------------------------
    async def open(self) -> None:
        """Open the instructor's view and the class's Zenoh graph (if Zenoh is on), then start the
        watch over the world workers and those started here."""
        await self.saved.load()
        # Workers that read this mark in their own workspaces folder share this one (class_mark.py).
        try:
            await asyncio.to_thread(self.workspace_copies.leave_mark)
        except OSError as exc:  # no worker shares it then: their worlds' workspaces are refused (409)
            log.warning(
                "no mark left in the workspaces folder %s: %s", self.class_settings.workspaces_dir, exc
            )
        # Workers that read this mark in their own progress folder share this one (progress_copies.py).
        try:
            await asyncio.to_thread(self.progress_copies.leave_mark)
        except OSError as exc:  # then every worker's worlds' progress is copied here
            log.warning("no mark left in the progress folder %s: %s", self.labs.progress.folder, exc)
        if self.settings.lab.viewer:
            from server.peripherals.viewer.class_view import ClassView, run_class_view

            self.view = ClassView(asyncio.get_running_loop())
            self._tasks.append(asyncio.create_task(run_class_view(self.view, self.clock, self)))
        if not await self.graph.open(self.clock, self.executors):
            return
        self._tasks.append(asyncio.create_task(self.placement.watch()))
        endpoint = self.graph.endpoint()
        # Started last: a start-up that fails earlier leaves no worker behind to clean up.
        if endpoint is not None:
            self.local_workers = local_workers_for(self.settings, endpoint, self.instructor_token)
            if self.local_workers is not None:
                self.local_workers.start()

    async def stop(self) -> None:
        for task in self._tasks:
            await cancel_and_wait(task)
        self._tasks.clear()
        if self.view is not None:
            self.view.stop()
            self.view = None
        for name in list(self.worlds):
            await self._end(self.worlds.pop(name))
        if self.local_workers is not None:
            await self.local_workers.stop()
            self.local_workers = None
        await self.graph.close_bridges(self.executors)
        await self.executors.close()
        await self.labs.close_progress()
        await self.graph.close()

    # -- worlds --------------------------------------------------------------------------------
    async def join(
        self, student: str, code: str, address: str = "unknown", token: str | None = None
    ) -> tuple[World, str]:
        """A new world for ``student``, joined from client ``address`` (its limits: admission.py)
        with the ``token`` its browser holds, if any (its progress on disk: saved_students.py).
        At the class's capacity (capacity.py), or behind joins already waiting, it waits in the
        join queue instead: ``JoinWaits`` carries its ticket."""
        self.admission.check(address)
        if not hmac.compare_digest(code.strip().upper().encode(), self.code.encode()):
            raise self.admission.wrong_code(address)
        check_student_name(student)
        proven = await self.saved.check(self._free_name(student), student.strip()[:64], token)
        capacity = await self.load.capacity()  # before the name is checked again: no await after it
        name = self._free_name(student)
        student = student.strip()[:64]
        # Nobody passes a join already waiting; a full class lets one in only as the instructor said.
        if self.queue or (capacity.verdict == "full" and not self.queue.use_let_through()):
            if not self.class_settings.join_queue.size:
                why = "; ".join(capacity.reasons)
                raise AtCapacityError(f"the class server is at its capacity ({why}): try again later",
                                      self.class_settings.join_queue.retry_after_s)  # fmt: skip
            waiting = self.queue.add(student, name, address)
            log.info("%s waits to join (%s)", student, "; ".join(capacity.reasons) or "joins ahead")
            raise JoinWaits(waiting, len(self.queue) - 1)
        return await self._start_world(student, name, address, token if proven else None)

    async def poll_join(self, ticket: str) -> tuple[World, str]:
        """A waiting join, asked again: its world and token once it is admitted (oldest first,
        when the class is no longer full or the instructor let it through), else ``JoinWaits``
        saying how many wait ahead of it."""
        waiting, ahead = self.queue.find(ticket)
        if ahead:
            raise JoinWaits(waiting, ahead)
        capacity = await self.load.capacity()
        waiting, ahead = self.queue.find(ticket)  # still there and first after the await?
        if ahead or (capacity.verdict == "full" and not self.queue.use_let_through()):
            raise JoinWaits(waiting, ahead)
        self.queue.admit(waiting)
        log.info("%s leaves the join queue after %.0f s", waiting.student, self.clock.now() - waiting.since_s)
        return await self._start_world(waiting.student, waiting.world, waiting.address)

    def _free_name(self, student: str) -> str:
        try:
            name = world_name(student)
        except ValueError as exc:
            raise BadNameError(str(exc)) from None
        if self.labs.taken(name) or self.queue.holds(name):
            raise NameTakenError(f"the name {student!r} is taken in this class (world {name!r})")
        if self.labs.full():
            raise ClassFullError(f"the class is full ({self.class_settings.max_worlds} worlds)")
        return name

    async def _start_world(
        self, student: str, name: str, address: str, kept: str | None = None
    ) -> tuple[World, str]:
        """``kept``: the token the join proved its student's (grants.py keeps it if it may)."""
        if self.labs.full():  # a waiting join whose turn came after the class filled up
            raise ClassFullError(f"the class is full ({self.class_settings.max_worlds} worlds)")
        domain_id = self.labs.free_domain(self.graph.revoking)
        login = self.graph.login(domain_id)
        self.admission.hold(address)
        self.labs.starting[name] = domain_id  # held while the world starts: no two joins take one name
        try:
            async with self.graph.gate.use():
                lab, place = await self.placement.start(name, student, domain_id, login)
        except BaseException:
            self.admission.release(address)
            raise
        finally:
            del self.labs.starting[name]
        token, grant = self.grants.issue(name, student, kept)
        resets = RateLimit(
            self.clock, self.class_settings.world.resets_hz, self.class_settings.world.resets_burst
        )
        world = self.worlds[name] = World(
            name, student, grant.token_id, lab, self.labs.write_limit(), domain_id, worker=place,
            placed_at=self.clock.now(), login=login, address=address, reset_limit=resets,
        )  # fmt: skip
        self.graph.show(world)
        if self.local_workers is not None:  # --workers auto: another worker as the class grows
            self.local_workers.spread(len(self.worlds))
        await self.saved.claim(name, student, token)
        where = f" on world worker {place.id}" if place is not None else ""
        log.info("%s joined: world %s%s", student, name, where)
        return world, token

    async def reset(self, name: str) -> World:
        """A fresh world under the same name and token: every node starts over, the 3D view too."""
        world = self.get(name)
        async with self.graph.gate.use():  # the world's graph joins the router again as it starts
            if world.worker is not None:
                assert self.workers is not None
                await self.workers.checked(world.worker, "POST", f"/api/classroom/worlds/{name}/reset")
            else:
                await self.labs.restart(world)
        world.resets += 1
        log.info("world %s reset", name)
        return world

    async def host(
        self,
        name: str,
        student: str,
        domain_id: int,
        launch: str,
        launch_args: dict[str, str],
        login: Credentials | None = None,
        router_socket: str | None = None,
        progress: Mapping[str, Any] | None = None,
    ) -> World:
        """A class server places worlds; it hosts none for another."""
        raise NotHereError("only a world worker hosts worlds for a class server")

    async def kick(self, name: str, *, remove_workspace: bool = True) -> World:
        """Remove a student's world; its workspace and progress always go with it, here and on
        the world worker that hosted it (``remove_workspace`` is a world worker's choice)."""
        world = self.worlds.pop(name, None)
        if world is None:
            raise UnknownWorldError(f"no world named {name!r}")
        self.graph.hold(world)  # at once: a join while the world ends must not get its domain
        self.grants.revoke(world)
        self.admission.release(world.address)
        # The world is out of the class from here on: each step below runs even when one before it
        # failed (a lab that stops badly must not keep its login alive), and a failure is logged
        # with its traceback rather than turned into a 500 for a removal that took place.
        try:
            await self._end(world, remove_workspace=True)
        except Exception:
            log.exception("world %s: its lab did not stop cleanly", name)
        await self.graph.revoke_login(world.domain_id)
        # Its workspace and progress go with it, here and on the world worker that hosted it.
        try:
            remove_world_workspace(self.class_settings.workspaces_dir, name)
        except OSError:
            log.exception("world %s: its workspace was not removed completely", name)
        await self.labs.remove_progress(name)
        self.progress_copies.forget(name)
        log.info("%s kicked: world %s removed", world.student, name)
        return world

    async def _end(self, world: World, *, remove_workspace: bool = False) -> None:
        if world.lab is not None:
            await world.lab.stop()
        elif world.worker is not None and self.workers is not None:
            await remote_worlds.end_remote(self.workers, world, remove_workspace=remove_workspace)

    # -- what the instructor sees --------------------------------------------------------------
    async def describe_all(self) -> list[dict[str, Any]]:
        """Every world as the instructor's page shows it; a worker's worlds as their worker reports."""
        return await remote_worlds.describe_worlds(self.workers, self.worlds)

    async def worker_checkpoints(self, checkpoints: list[str]) -> tuple[list[dict[str, Any]], dict[str, str]]:
        """The checkpoint table's rows of the worlds on world workers, as their workers keep them
        (a worker that does not answer: its worlds' rows say so)."""
        return await remote_checkpoints.checkpoint_rows(self.workers, self.worlds, checkpoints)

    async def worker_reports(self) -> tuple[list[tuple[str, bytes]], dict[str, str]]:
        """The signed reports of the worlds on world workers; why each world without one has none."""
        return await remote_checkpoints.report_files(self.workers, self.worlds)

    async def broadcast_on_workers(self, body: dict[str, Any]) -> tuple[list[str], dict[str, str]]:
        """The instructor's broadcast, published by each world worker in the worlds it hosts."""
        return await remote_worlds.broadcast(self.workers, self.worlds, body)

    # -- the load and the join queue -----------------------------------------------------------
    async def class_load(self) -> PlaceReport:
        """Each place's load, the capacity verdict, and the join queue (its expired joins dropped)."""
        places = await self.load.places()
        capacity = await self.load.capacity()
        self.queue.expire()
        return places, capacity, self.queue.describe()

    def let_through(self, count: int) -> dict[str, Any]:
        self.queue.let_in(count)
        return self.queue.describe()

    # -- students not joined since the start ---------------------------------------------------
    def not_joined(self) -> list[tuple[str, Progress]]:
        return self.saved.not_joined(self.worlds)

    async def not_joined_with_captures(self) -> list[tuple[str, Progress]]:
        return [(name, await self.saved.with_captures(name)) for name, _saved in self.not_joined()]

    async def release_progress(self, name: str) -> str:
        return await self.saved.release(name, self.worlds)

    def drones(
        self, remote: Mapping[str, list[float] | None] | None = None
    ) -> dict[str, tuple[str, list[float] | None]]:
        """Every world's student and drone position, as the class view shows them (None: not known
        now); a worker's world's from ``remote`` (the latest its worker reported)."""
        return world_drones(self.worlds.values(), remote or {})

    async def remote_drones(self) -> dict[str, list[float] | None]:
        return await remote_worlds.remote_drones(self.workers, self.worlds)
