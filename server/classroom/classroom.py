"""The class server's worlds: one lab per student, each with its own graph, sims and 3D view.

A world is a whole ``Lab`` (bus, executor, launched nodes, viser display) named after its
student. Worlds share the process and its event loop and nothing else: a student's topics,
keys, publishers and resets reach only their own world. The instructor's grant reaches all.
"""

from __future__ import annotations

import asyncio
import dataclasses
import hmac
import logging
import math
import re
import secrets
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from server.bus import Clock, ExecutorGroup, SystemClock
from server.devices.shared_physics import SharedQuadrotorPhysics, SharedSimpleSim
from server.lab import Lab
from server.limits import RateLimit
from server.settings import Settings
from server.tasks import cancel_and_wait
from server.transport.acl import ClassAuth, Credentials
from server.transport.config import ZenohSettings, endpoint_host

from .admission import Admission, check_student_name
from .errors import ClassroomError
from .load import Choice, CpuMeter, choose, machine_id
from .router_gate import RouterGate
from .tokens import Grant, TokenSigner
from .workers import (
    WATCH_PERIOD_S,
    Silence,
    WorkerDirectory,
    WorkerRef,
    worker_api_token,
    world_of_call_token,
)

if TYPE_CHECKING:
    from server.transport.domain_bridge import DomainBridge
    from server.transport.domain_routes import BridgeStats
    from server.viewer.class_view import ClassView

    from .class_bridges import ClassBridges
    from .class_router import ClassRouter
    from .local_workers import LocalWorkers

log = logging.getLogger("classroom")
CODE_ALPHABET = "ABCDEFGHJKLMNPQRSTUVWXYZ23456789"  # no 0/O, 1/I: read aloud or off a projector
CODE_CHARS = 6
MAX_NAME_CHARS = 32
MAX_DOMAIN_ID = 232  # ROS 2's highest ROS_DOMAIN_ID
WORKERS_BACK_S = 10.0  # how long a reopened router waits for its world workers to answer again
# A world's name is a ROS namespace token: letters, digits and underscores, not starting with a digit.
_NOT_NAME = re.compile(r"[^a-z0-9_]+")


def new_code() -> str:
    return "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_CHARS))


def world_name(student: str) -> str:
    """``"Ada Lovelace"`` → ``ada_lovelace``; ValueError when nothing usable is left."""
    name = _NOT_NAME.sub("_", student.strip().lower()).strip("_")[:MAX_NAME_CHARS].rstrip("_")
    if not name:
        raise ValueError("a name needs at least one letter or digit")
    return name if not name[0].isdigit() else f"s_{name}"[:MAX_NAME_CHARS]


@dataclass
class World:
    name: str
    student: str
    token_id: str
    lab: Lab | None  # None when the world runs on a world worker
    writes: RateLimit
    domain_id: int = 0  # its ROS_DOMAIN_ID on the class's Zenoh graph
    joined_at: float = field(default_factory=time.time)
    resets: int = 0
    worker: WorkerRef | None = None  # the world worker that hosts it, if one does
    moves: int = 0  # times it started again elsewhere because its world worker was gone
    placed_at: float = -math.inf  # when it was last started where it is (the class's clock)
    lost: str | None = None  # why it cannot be reached now (its worker is gone and it waits for room)
    login: Credentials | None = field(default=None, repr=False)  # its Zenoh login (class_router.py)
    address: str | None = None  # the client address it was joined from (a class server's)
    reset_limit: RateLimit | None = None  # a student's resets, besides their writes
    sockets: int = 0  # a student's WebSockets open on it now (api/ws_cap.py)

    def describe(self) -> dict[str, Any]:
        """What the class server knows itself; a worker's world adds what its worker reports."""
        out: dict[str, Any] = {
            "world": self.name,
            "student": self.student,
            "domain_id": self.domain_id,
            "joined_at": self.joined_at,
            "resets": self.resets,
            "writes_refused": self.writes.refused,
            "worker": self.worker.id if self.worker is not None else None,
            "moves": self.moves,
            "lost": self.lost,
        }
        lab = self.lab
        if lab is None:
            return out
        rocket = lab.rocket.view.tracker if lab.rocket.view is not None else None
        return {
            **out,
            "domain_id": self.domain_id if lab.zenoh is not None else None,
            "keys_held": sorted(lab.keyboard.held()),
            "rocket": None
            if rocket is None
            else {"phase": rocket.phase, "altitude_m": round(rocket.altitude_m, 2)},
            "drone": drone_position(lab),
            "crashed_nodes": sorted(n.fully_qualified_name for n in lab.bus.nodes if n.state == "crashed"),
            "nodes": len(lab.bus.nodes),
        }


def drone_position(lab: Lab) -> list[float] | None:
    """Where the world's drone is (its GPS topic's latest pose), or None before the first fix."""
    topic = lab.bus.topics.get("/uav/sensors/gps")
    latest: Any = topic.latest if topic is not None else None
    if latest is None:
        return None
    p = latest.pose.position
    return [round(p.x, 3), round(p.y, 3), round(p.z, 3)]


class Classroom:
    """The worlds of one class server, and who may do what in them. On a world worker
    (``settings.worker``) the same class hosts the worlds a class server places on it."""

    def __init__(
        self,
        settings: Settings,
        clock: Clock | None = None,
        *,
        code: str | None = None,
        signer: TokenSigner | None = None,
    ) -> None:
        self.settings = settings
        self.clock: Clock = clock or SystemClock()  # every world's, the physics' and the limits'
        self.code = code or new_code()
        self.signer = signer or TokenSigner()
        self.instructor_token, self.instructor = self.signer.issue("instructor", None, "instructor")
        self.worlds: dict[str, World] = {}
        self.admission = Admission(settings.joins, self.clock)
        self.physics = SharedQuadrotorPhysics(self.clock)
        self.simple_physics = SharedSimpleSim(self.clock)  # the worlds flown with simple:=true
        self.executors = ExecutorGroup()  # one task runs every world's callbacks here
        self.workers: WorkerDirectory | None = None  # the class server's world workers, with Zenoh
        self._revoked: set[str] = set()
        self._starting: dict[str, int] = {}  # world → its ROS domain, while it starts
        self._hosting: set[tuple[str, str]] = set()  # (worker id, world) while it is placed there
        self._local_starting = 0  # worlds being started here
        self.router: ClassRouter | None = None  # the class's Zenoh router and its logins
        self._gate = RouterGate()  # worlds start while the router is open, never while it opens again
        self._revoking: set[int] = set()  # domains whose old login the router may still let in
        self.local_workers: LocalWorkers | None = None  # world workers started here (--workers)
        self.class_graph: DomainBridge | None = None  # every world under /<world> in the class's domain
        self._graph_stats: BridgeStats | None = None  # the class graph's counts, over every reopening
        # The instructor's Foxglove and rosbridge ports on the class domain.
        self.bridges: ClassBridges | None = None
        self._control: Any = None  # a worker's hello queryable (WorkerControl) and its session
        self._control_session: Any = None
        self._watch: asyncio.Task[None] | None = None  # the class server's hellos, or a worker's orphan check
        self.view: ClassView | None = None  # the instructor's 3D view of every world (a class server's)
        self._view_task: asyncio.Task[None] | None = None
        self._silent_workers = Silence(settings.worker_timeout_s)
        # This process's and machine's CPU: a worker's hello, the class server's placing. Each reads
        # it every WATCH_PERIOD_S (a hello, a watch round), so a load covers the last seconds.
        self.cpu = CpuMeter(machine=machine_id())
        self._class_heard_at = self.clock.now()  # a worker: the class server's last hello or call
        worker = settings.worker
        self._worker_token = worker_api_token(worker.class_token, worker.id) if worker is not None else None

    @property
    def is_worker(self) -> bool:
        return self.settings.worker is not None

    @property
    def hosted_here(self) -> int:
        """Worlds this process runs itself (not on a world worker)."""
        return sum(1 for w in self.worlds.values() if w.worker is None)

    @property
    def local_capacity(self) -> int:
        local = self.settings.local_worlds
        return self.settings.max_worlds if local is None else min(local, self.settings.max_worlds)

    # -- who is calling ------------------------------------------------------
    def grant(self, token: str | None) -> Grant | None:
        """The grant of a genuine, current token: a student's world must still be theirs."""
        if not token:
            return None
        if self._worker_token is not None and hmac.compare_digest(
            token.encode(), self._worker_token.encode()
        ):
            self.heard_from_class()
            return self.instructor  # the class server, calling its worker
        if (forwarded := self._forwarded_world(token)) is not None:
            self.heard_from_class()
            world = self.worlds.get(forwarded)
            # A student's call, forwarded by the class server: that world's student, nothing more.
            return Grant("student", world.name, world.student, world.token_id) if world is not None else None
        grant = self.signer.verify(token)
        if grant is None or grant.token_id in self._revoked:
            return None
        if grant.is_instructor:
            return grant
        world = self.worlds.get(grant.world or "")
        return grant if world is not None and world.token_id == grant.token_id else None

    def _forwarded_world(self, token: str) -> str | None:
        """On a worker: the world a class server's forwarded credential is for (None: not one)."""
        worker = self.settings.worker
        return world_of_call_token(worker.class_token, worker.id, token) if worker is not None else None

    def world_for(self, grant: Grant, asked: str | None) -> World:
        """The world a call acts on: a student's own (naming another is 403); the instructor's
        must be named."""
        if grant.is_instructor:
            if asked is None:
                raise ClassroomError(400, "name a world (the X-Lab-World header or ?world=)")
            return self.get(asked)
        if asked is not None and asked != grant.world:
            raise ClassroomError(403, f"your token is for world {grant.world!r}, not {asked!r}")
        return self.get(grant.world or "")

    def get(self, name: str) -> World:
        world = self.worlds.get(name)
        if world is None:
            raise ClassroomError(404, f"no world named {name!r}")
        return world

    # -- the class's Zenoh graph ---------------------------------------------------------------
    async def open(self) -> None:
        """Open the class's Zenoh router (if Zenoh is on): each world joins it in a ROS domain of
        its own, so students' node processes join their world with its ROS_DOMAIN_ID. On a world
        worker: join the class's router and answer the class server's hellos."""
        if not self.is_worker and self.settings.viewer:
            from server.viewer.class_view import ClassView, run_class_view

            self.view = ClassView(asyncio.get_running_loop())
            self._view_task = asyncio.create_task(run_class_view(self.view, self.clock, self))
        zenoh = self.settings.zenoh
        if zenoh is None:
            return
        from server.transport.session import TransportError, open_session

        if self.settings.worker is not None:
            from .worker_control import WorkerControl

            zenoh = dataclasses.replace(zenoh, login=self.zenoh_auth.class_credentials())
            self._control_session = await asyncio.to_thread(open_session, zenoh)
            self._control = WorkerControl(
                self._control_session, self.settings.worker, self._load, self.heard_from_class
            )
            self._watch = asyncio.create_task(self._watch_class(self.settings.worker.orphan_timeout_s))
            return
        if zenoh.mode != "router":
            return
        # The router logs every session in and holds each world's to its own ROS domain.
        from .class_router import ClassRouter

        router = ClassRouter(zenoh, self.zenoh_auth.class_credentials())
        try:
            session = await router.open()
        except TransportError as exc:
            log.warning("%s; the worlds run without Zenoh", exc)
            return
        self.router = router
        self.workers = WorkerDirectory(session, self.instructor_token)
        self._open_class_graph(session)
        self._watch = asyncio.create_task(self._watch_workers())
        endpoint = self.router_endpoint()
        if endpoint is not None:  # the instructor's bridges: /class/rosbridge, and their ports if asked
            from .class_bridges import ClassBridges

            try:
                self.bridges = await ClassBridges.open(
                    self.settings, self.clock, self.executors, endpoint, zenoh.domain_id,
                    self.zenoh_auth.class_credentials(), self.instructor_token,
                )  # fmt: skip
            except TransportError as exc:
                log.warning("the class's Foxglove and rosbridge ports not opened: %s", exc)
        # Started last: a start-up that fails earlier leaves no worker behind to clean up.
        if endpoint is not None and self.settings.local_workers > 0:
            from .local_workers import LocalWorkers

            self.local_workers = LocalWorkers(
                self.settings.local_workers, endpoint, self.instructor_token, self.settings.max_worlds,
                self.settings.workspace, self.settings.bag_dir, world_log_level=self.settings.world_log_level,
            )  # fmt: skip
            self.local_workers.start()

    # -- the instructor's 3D view: its drones (server/viewer/class_view.py moves them) -------------
    def drones(
        self, remote: Mapping[str, list[float] | None] | None = None
    ) -> dict[str, tuple[str, list[float] | None]]:
        """Every world's student and drone position, as the class view shows them (None: not known
        now); a worker's world's from ``remote`` (the latest its worker reported)."""
        remote = remote or {}
        out: dict[str, tuple[str, list[float] | None]] = {}
        for world in self.worlds.values():
            if world.lab is not None:
                position = drone_position(world.lab)
            else:
                position = None if world.lost is not None else remote.get(world.name)
            out[world.name] = (world.student, position)
        return out

    async def remote_drones(self) -> dict[str, list[float] | None]:
        reports, _errors = await self._worker_reports()
        found: dict[str, list[float] | None] = {}
        for (_wid, name), report in reports.items():
            drone = report.get("drone")
            if isinstance(drone, list) and len(drone) == 3 and all(isinstance(v, int | float) for v in drone):
                found[name] = [float(v) for v in drone]
            else:
                found[name] = None
        return found

    # -- workers that go, class servers that go ------------------------------------------------
    async def _watch_workers(self) -> None:
        """The class server: say hello to the workers every few seconds; the worlds of one silent
        for ``--worker-timeout`` start again elsewhere, under the same names, domains and tokens."""
        while self.workers is not None:
            await asyncio.sleep(WATCH_PERIOD_S)
            self.cpu.read()  # a new window: a placement weighs the last seconds, not all since the last join
            try:
                await self.watch_workers_once()
            except Exception:  # the watch must outlive any one round
                log.exception("watching the world workers failed; trying again")

    async def watch_workers_once(self) -> None:
        assert self.workers is not None
        asked_at = self.clock.now()
        answered = await asyncio.to_thread(self.workers.discover)
        now = self.clock.now()
        answering = {ref.id for ref in answered}
        for ref in answered:
            self._silent_workers.heard(ref.id, now)
        hosting = {w.worker.id for w in self.worlds.values() if w.worker is not None}
        gone = self._silent_workers.silent(hosting, now)
        # A worker that answers but no longer hosts a world placed on it before this hello (it
        # restarted, or freed its worlds while cut off): that world is gone too.
        missing = {
            (ref.id, name)
            for ref in answered
            if ref.hosted is not None
            for name, world in self.worlds.items()
            if world.worker is not None and world.worker.id == ref.id and world.placed_at < asked_at
            and name not in ref.hosted
        }  # fmt: skip
        await self._end_strays(answered)
        for world in list(self.worlds.values()):
            if world.worker is None:
                continue
            silent = world.worker.id in gone
            if silent:
                why = f"no hello for {self.settings.worker_timeout_s:g} s"
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
        assert self.workers is not None
        for ref in answered:
            ours = {name for name, w in self.worlds.items() if w.worker is not None and w.worker.id == ref.id}
            placing = {name for wid, name in self._hosting if wid == ref.id}
            for name in sorted((ref.hosted or frozenset()) - ours - placing - set(self._starting)):
                log.warning("world worker %s still hosts world %s, which this class does not count there: "
                            "ending it", ref.id, name)  # fmt: skip
                try:
                    await self.workers.checked(ref, "DELETE", f"/api/classroom/worlds/{name}")
                except ClassroomError as exc:
                    if exc.status != 404:  # 404: it ended meanwhile
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
        lab: Lab | None = None
        try:
            async with self._gate.use():
                place = await self._place(exclude=exclude)
                if place is None:
                    self._local_starting += 1
                    try:
                        lab = await self._start_lab(world.name, world.domain_id, login=world.login)
                    finally:
                        self._local_starting -= 1
                else:
                    await self._host_on(place, world.name, world.student, world.domain_id, world.login)
        except ClassroomError as exc:
            world.lost = f"{world.lost}, when there is room ({exc})"
            return
        if self.worlds.get(world.name) is not world:  # kicked while it started
            await self._end(World(world.name, world.student, world.token_id, lab, world.writes, worker=place))
            return
        world.lab, world.worker, world.lost = lab, place, None
        world.moves += 1
        world.placed_at = self.clock.now()
        where = f"world worker {place.id}" if place is not None else "the class server"
        log.info("world %s started again on %s", world.name, where)

    def heard_from_class(self) -> None:
        """A worker: the class server said hello or called (Zenoh's thread or the loop)."""
        self._class_heard_at = self.clock.now()

    async def _watch_class(self, timeout_s: float) -> None:
        """A worker: free every world when the class server has been silent for ``timeout_s`` (it
        stopped or lost the network): nobody can reach them, and its replacement starts them anew."""
        while True:
            await asyncio.sleep(min(WATCH_PERIOD_S, timeout_s / 2))
            try:
                await self.free_if_orphaned(timeout_s)
            except Exception:
                log.exception("checking on the class server failed; trying again")

    async def free_if_orphaned(self, timeout_s: float) -> list[str]:
        """The worlds freed because the class server has said nothing for ``timeout_s``."""
        silent_s = self.clock.now() - self._class_heard_at
        if not self.worlds or silent_s < timeout_s:
            return []
        names = list(self.worlds)
        log.warning(
            "no hello from the class server for %.0f s: freeing worlds %s", silent_s, ", ".join(names)
        )
        for name in names:
            await self._end(self.worlds.pop(name))
        return names

    def _load(self) -> dict[str, Any]:
        """A worker's hello: how full it is, and which worlds it hosts (Zenoh's thread: a copy)."""
        hosted = sorted(self.worlds)
        return {"worlds": len(hosted) + len(self._starting), "max_worlds": self.settings.max_worlds,
                "hosted": hosted, "cpu": self.cpu.read().describe()}  # fmt: skip

    @property
    def zenoh_auth(self) -> ClassAuth:
        """The class's Zenoh logins, from the instructor's token (a worker holds it as its class token)."""
        worker = self.settings.worker
        return ClassAuth(worker.class_token if worker is not None else self.instructor_token)

    def router_endpoint(self) -> str | None:
        """Where worlds and node processes connect: the class's router, or the one it joined."""
        zenoh = self.settings.zenoh
        if zenoh is None or (zenoh.mode == "router" and self.router is None):
            return None
        if zenoh.mode != "router":
            return zenoh.connect[0]
        proto, host, port = endpoint_host(zenoh.listen[0])
        return f"{proto}/{'127.0.0.1' if host in ('0.0.0.0', '[::]', '::') else host}:{port}"

    def _free_domain(self) -> int:
        taken = {w.domain_id for w in self.worlds.values()} | set(self._starting.values()) | self._revoking
        if self.settings.zenoh is not None:
            taken.add(self.settings.zenoh.domain_id)  # the class's own domain stays empty
        free = (d for d in range(1, MAX_DOMAIN_ID + 1) if d not in taken)
        domain = next(free, None)
        if domain is None:
            raise ClassroomError(429, f"every ROS domain (1..{MAX_DOMAIN_ID}) is taken")
        return domain

    def _world_settings(
        self, name: str, domain_id: int, launch: tuple[str, dict[str, str]] | None, login: Credentials | None
    ) -> Settings:
        # A world's graph joins the class's router in a ROS domain of its own; the class server's
        # other ports (Foxglove, rosbridge) are not opened per world; bags go in a folder per world.
        endpoint = self.router_endpoint()
        zenoh = None
        if endpoint is not None:
            config_file = self.settings.zenoh.config_file if self.settings.zenoh is not None else None
            zenoh = ZenohSettings(
                mode="client", listen=(), connect=(endpoint,), domain_id=domain_id, config_file=config_file,
                login=login, samples_hz=self.settings.world_samples_hz,
            )  # fmt: skip
        file, args = launch if launch is not None else (self.settings.launch, self.settings.launch_args)
        return dataclasses.replace(
            self.settings,
            zenoh=zenoh,
            foxglove_port=None,
            rosbridge_port=None,
            bag_dir=self.settings.bag_dir / name,
            launch=file,
            launch_args=args,
            max_launch_groups=min(self.settings.max_launch_groups, self.settings.world_launches),
            max_nodes_per_launch=min(self.settings.max_nodes_per_launch, self.settings.world_launch_nodes),
            socket_frames_hz=self.settings.world_socket_frames_hz,
            socket_requests_hz=self.settings.world_socket_requests_hz,
        )

    async def _start_lab(
        self,
        name: str,
        domain_id: int,
        launch: tuple[str, dict[str, str]] | None = None,
        login: Credentials | None = None,
    ) -> Lab:
        settings = self._world_settings(name, domain_id, launch, login)
        lab = Lab(settings, self.clock, executors=self.executors)
        lab.bus.label = name  # its nodes' console lines carry its name (server/console.py)
        lab.bus.devices["quadrotor_physics"] = self.physics  # every world's drone in one batch
        lab.bus.devices["simple_sim_physics"] = self.simple_physics
        await lab.start()
        return lab

    # -- worlds ----------------------------------------------------------------
    async def join(self, student: str, code: str, address: str = "unknown") -> tuple[World, str]:
        """A new world for ``student``, joined from client ``address`` (its limits: admission.py)."""
        if self.is_worker:
            raise ClassroomError(403, "this is a world worker: students join through the class server")
        self.admission.check(address)
        if not hmac.compare_digest(code.strip().upper().encode(), self.code.encode()):
            raise self.admission.wrong_code(address)
        check_student_name(student)
        try:
            name = world_name(student)
        except ValueError as exc:
            raise ClassroomError(422, str(exc)) from None
        if name in self.worlds or name in self._starting:
            raise ClassroomError(409, f"the name {student!r} is taken in this class (world {name!r})")
        if len(self.worlds) + len(self._starting) >= self.settings.max_worlds:
            raise ClassroomError(429, f"the class is full ({self.settings.max_worlds} worlds)")
        student = student.strip()[:64]
        domain_id = self._free_domain()
        login = self.router.login(domain_id) if self.router is not None else None
        self.admission.hold(address)
        self._starting[name] = domain_id  # held while the world starts: no two joins take one name
        try:
            async with self._gate.use():
                place = await self._place()
                lab: Lab | None = None
                if place is None:
                    self._local_starting += 1
                    try:
                        lab = await self._start_lab(name, domain_id, login=login)
                    finally:
                        self._local_starting -= 1
                else:
                    await self._host_on(place, name, student, domain_id, login)
        except BaseException:
            self.admission.release(address)
            raise
        finally:
            del self._starting[name]
        token, grant = self.signer.issue("student", name, student)
        world = self.worlds[name] = World(
            name,
            student,
            grant.token_id,
            lab,
            self._limit(),
            domain_id,
            worker=place,
            placed_at=self.clock.now(),
            login=login,
            address=address,
            reset_limit=RateLimit(
                self.clock, self.settings.world_resets_hz, self.settings.world_resets_burst
            ),
        )
        if self.class_graph is not None:
            self.class_graph.set_world(domain_id, name)
        where = f" on world worker {place.id}" if place is not None else ""
        log.info("%s joined: world %s%s", student, name, where)
        return world, token

    async def _place(self, exclude: str | None = None) -> WorkerRef | None:
        """Where a new world goes: here or the world worker with the lowest load (worlds over
        capacity), but never a place whose CPU is saturated (``load.py``) while another has room;
        on a tie a worker, so the class server keeps its core for the pages. Never on worker
        ``exclude``."""
        local = self.hosted_here + self._local_starting
        choices: list[Choice] = []
        if local < self.local_capacity:
            choices.append(Choice(local / max(self.local_capacity, 1), None, self.cpu.read()))
        refs = await asyncio.to_thread(self.workers.discover) if self.workers is not None else []
        on_workers = self._on_workers()
        for ref in refs:
            if ref.id == exclude:
                continue
            ours = len(on_workers[ref.id][1]) if ref.id in on_workers else 0
            placing = sum(1 for wid, _ in self._hosting if wid == ref.id)
            worlds = max(ref.worlds, ours) + placing
            if worlds < ref.max_worlds:
                choices.append(Choice(worlds / ref.max_worlds, ref, ref.load))
        if not choices:
            raise ClassroomError(
                503, f"no room for another world: this server hosts {self.local_capacity} itself "
                     f"(--local-worlds) and {'no world worker has room' if refs else 'no world worker answered'}"
            )  # fmt: skip
        best, full = choose(choices)
        if full:
            log.warning(
                "every place with room for a new world is saturated (CPU): placing it on the least full"
            )
        return best.ref

    async def _host_on(
        self, ref: WorkerRef, name: str, student: str, domain_id: int, login: Credentials | None
    ) -> None:
        assert self.workers is not None
        self._hosting.add((ref.id, name))
        try:
            body: dict[str, Any] = {"world": name, "student": student, "domain_id": domain_id,
                    "launch": self.settings.launch, "launch_args": self.settings.launch_args}  # fmt: skip
            if login is not None:  # the world's own login: its graph joins the router with it
                body |= {"zenoh_user": login.user, "zenoh_password": login.password}
            await self.workers.checked(ref, "POST", "/api/classroom/host", body=body)
        finally:
            self._hosting.discard((ref.id, name))

    async def host(
        self,
        name: str,
        student: str,
        domain_id: int,
        launch: str,
        launch_args: dict[str, str],
        login: Credentials | None = None,
    ) -> World:
        """A world worker: start the world a class server placed here, in the domain it chose."""
        if not self.is_worker:
            raise ClassroomError(404, "only a world worker hosts worlds for a class server")
        self.heard_from_class()
        if name in self.worlds or name in self._starting:
            raise ClassroomError(409, f"world {name!r} is already here")
        if len(self.worlds) + len(self._starting) >= self.settings.max_worlds:
            raise ClassroomError(429, f"this worker is full ({self.settings.max_worlds} worlds)")
        self._starting[name] = domain_id
        try:
            lab = await self._start_lab(name, domain_id, (launch, launch_args), login)
        finally:
            del self._starting[name]
        _token, grant = self.signer.issue(
            "student", name, student
        )  # never handed out: the class server proxies
        world = self.worlds[name] = World(
            name, student, grant.token_id, lab, self._limit(), domain_id, login=login
        )
        log.info("hosting world %s (%s), ROS domain %d", name, student, domain_id)
        return world

    def _on_workers(self) -> dict[str, tuple[WorkerRef, list[str]]]:
        """Worker id → that worker and the names of the worlds it hosts for this class (not those
        it lost: they are being started again, and count nowhere until they are)."""
        out: dict[str, tuple[WorkerRef, list[str]]] = {}
        for world in self.worlds.values():
            if world.worker is not None and world.lost is None:
                out.setdefault(world.worker.id, (world.worker, []))[1].append(world.name)
        return out

    def _limit(self) -> RateLimit:
        return RateLimit(self.clock, self.settings.world_writes_hz, self.settings.world_writes_burst)

    async def describe_all(self) -> list[dict[str, Any]]:
        """Every world as the instructor's page shows it; a worker's worlds as their worker reports."""
        reports, errors = await self._worker_reports()
        out = []
        for world in self.worlds.values():
            mine = world.describe()
            if world.worker is not None:
                reported = reports.get((world.worker.id, world.name), {})
                mine = {**reported, **mine}
                if world.worker.id in errors:
                    mine["worker_error"] = errors[world.worker.id]
            out.append(mine)
        return out

    async def _worker_reports(self) -> tuple[dict[tuple[str, str], dict[str, Any]], dict[str, str]]:
        """What each world worker reports of the worlds it hosts for this class, by (worker id,
        world); and why each worker that could not answer did not."""
        reports: dict[tuple[str, str], dict[str, Any]] = {}
        errors: dict[str, str] = {}
        for ref, names in self._on_workers().values():
            assert self.workers is not None
            try:
                listed = await self.workers.checked(ref, "GET", "/api/classroom/worlds")
            except ClassroomError as exc:
                errors[ref.id] = str(exc)
                continue
            reports.update(
                {
                    (ref.id, str(w.get("world"))): w
                    for w in listed.get("worlds", [])
                    if w.get("world") in names
                }
            )
        return reports, errors

    async def broadcast_on_workers(self, body: dict[str, Any]) -> tuple[list[str], dict[str, str]]:
        """The instructor's broadcast, published by each world worker in the worlds it hosts."""
        reached: list[str] = []
        refused: dict[str, str] = {}
        for ref, names in self._on_workers().values():
            assert self.workers is not None
            try:
                answer = await self.workers.checked(ref, "POST", "/api/classroom/broadcast", body=body)
            except ClassroomError as exc:
                refused |= dict.fromkeys(names, str(exc))
                continue
            reached += [n for n in answer.get("reached", []) if n in names]
            refused |= {n: str(why) for n, why in answer.get("refused", {}).items() if n in names}
        return reached, refused

    def charge_reset(self, name: str) -> None:
        """A student's reset: one of their world's few resets, and one of its writes (429 over
        either, which charges neither)."""
        world = self.get(name)
        settings, resets = self.settings, world.reset_limit
        if resets is not None and not resets.ready():
            resets.refused += 1
            raise ClassroomError(
                429, f"too many resets of world {name!r}: at most {settings.world_resets_burst} in a row, "
                f"then one in {1 / settings.world_resets_hz:g} s", resets.retry_after_s(),
            )  # fmt: skip
        if not world.writes.take():
            raise ClassroomError(429, f"too many requests for world {name!r}: at most "
                                      f"{settings.world_writes_hz:g} writes a second", world.writes.retry_after_s())  # fmt: skip
        if resets is not None:
            resets.take()

    async def reset(self, name: str) -> World:
        """A fresh world under the same name and token: every node starts over, the 3D view too."""
        world = self.get(name)
        async with self._gate.use():  # the world's graph joins the router again as it starts
            if world.worker is not None:
                assert self.workers is not None
                await self.workers.checked(world.worker, "POST", f"/api/classroom/worlds/{name}/reset")
            else:
                assert world.lab is not None
                await world.lab.stop()  # first: the new world takes the same ROS domain on the graph
                launch = self._launch_of(world.lab)
                world.lab = await self._start_lab(name, world.domain_id, launch, world.login)
        world.resets += 1
        log.info("world %s reset", name)
        return world

    @staticmethod
    def _launch_of(lab: Lab) -> tuple[str, dict[str, str]]:
        return lab.settings.launch, lab.settings.launch_args

    async def kick(self, name: str) -> World:
        world = self.worlds.pop(name, None)
        if world is None:
            raise ClassroomError(404, f"no world named {name!r}")
        if self.router is not None:  # at once: a join while the world ends must not get its domain
            self._revoking.add(world.domain_id)
        self._revoked.add(world.token_id)
        self.admission.release(world.address)
        if self.class_graph is not None:
            self.class_graph.drop_world(world.domain_id)
        await self._end(world)
        await self._revoke_login(world.domain_id)
        log.info("%s kicked: world %s removed", world.student, name)
        return world

    async def _revoke_login(self, domain_id: int) -> None:
        """Retire the login of the world that was in ``domain_id``: the router opens again without
        it (class_router.py), which drops every session of it. Until then nobody gets the domain;
        removals that wait meanwhile are done by the same reopening."""
        if self.router is None:
            return
        self._revoking.add(domain_id)
        try:
            async with self._gate.reopening():
                if domain_id in self._revoking:  # not yet done by a reopening this one waited for
                    batch = set(self._revoking)
                    await self._reopen_router(batch)
                    self._revoking -= batch
        finally:
            self._revoking.discard(domain_id)

    async def _reopen_router(self, domains: set[int]) -> None:
        from server.transport.session import TransportError

        assert self.router is not None
        if self.workers is not None:
            self.workers.session = None
        if self.class_graph is not None:  # it lives on the router's session: built again on the new one
            await asyncio.to_thread(self.class_graph.close)
            self.class_graph = None
        try:
            session = await self.router.revoke(domains)
        except TransportError as exc:
            log.error("the class's Zenoh router did not open again (%s): the worlds are off Zenoh", exc)
            return
        self._open_class_graph(session)
        if self.workers is not None:
            await self._workers_back(session)
        log.info("Zenoh logins of ROS domains %s revoked: the class's router opened again",
                 ", ".join(map(str, sorted(domains))))  # fmt: skip

    async def _workers_back(self, session: Any) -> None:
        """Until the workers found before the router opened again answer on the new one (their
        sessions connect again by themselves), for at most WORKERS_BACK_S: a join meanwhile
        would find no room on them."""
        assert self.workers is not None
        expected = set(self.workers.last_found)
        self.workers.session = session
        deadline = time.monotonic() + WORKERS_BACK_S
        while expected and time.monotonic() < deadline:
            found = {ref.id for ref in await asyncio.to_thread(self.workers.discover)}
            if expected <= found:
                return
            await asyncio.sleep(0.1)
        if expected:
            log.warning("world workers %s did not answer within %g s of the router opening again",
                        ", ".join(sorted(expected - self.workers.last_found)), WORKERS_BACK_S)  # fmt: skip

    def _open_class_graph(self, session: Any) -> None:
        from server.transport.domain_bridge import DomainBridge

        assert self.settings.zenoh is not None
        self.class_graph = DomainBridge(session, self.settings.zenoh.domain_id, self._graph_stats)
        self._graph_stats = self.class_graph.stats
        for world in self.worlds.values():
            self.class_graph.set_world(world.domain_id, world.name)

    async def _end(self, world: World) -> None:
        if world.lab is not None:
            await world.lab.stop()
        elif world.worker is not None and self.workers is not None:
            try:  # a worker that is gone took its world with it
                await self.workers.checked(world.worker, "DELETE", f"/api/classroom/worlds/{world.name}")
            except ClassroomError as exc:
                log.warning("world %s: %s", world.name, exc)

    async def stop(self) -> None:
        for task in (self._watch, self._view_task):
            if task is not None:
                await cancel_and_wait(task)
        self._watch = self._view_task = None
        if self.view is not None:
            self.view.stop()
            self.view = None
        for name in list(self.worlds):
            await self._end(self.worlds.pop(name))
        if self.local_workers is not None:
            await self.local_workers.stop()
            self.local_workers = None
        if self.bridges is not None:
            await self.bridges.close(self.executors)
            self.bridges = None
        await self.executors.close()
        if self.workers is not None:
            await self.workers.close()
            self.workers = None
        if self._control is not None:
            self._control.close()
            self._control = None
        if self.class_graph is not None:
            await asyncio.to_thread(self.class_graph.close)
            self.class_graph = None
        if self._control_session is not None:
            self._control_session.close()
            self._control_session = None
        if self.router is not None:
            async with self._gate.reopening():  # not while it opens again
                self.router.close()
            self.router = None
