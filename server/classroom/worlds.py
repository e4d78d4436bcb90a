"""The worlds one process knows and the labs it runs for them: what a class server and a world
worker share.

Every world's lab runs on the one clock, in one executor group (one task runs every world's
callbacks) and with the drones of all stepped in one batch (server/peripherals/devices/shared_physics.py). A
world's graph joins the class's router in a ROS domain of its own; its other ports (Foxglove,
rosbridge) are not opened per world; its bags go in a folder of its own.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from pathlib import Path

from node_runtime.bus import Clock, ExecutorGroup
from node_runtime.limits import RateLimit
from node_runtime.transport.acl import Credentials
from node_runtime.transport.config import ZenohSettings
from server.classroom.errors import (
    ClassFullError,
    RateLimitedError,
    StudentCodeElsewhereError,
    UnknownWorldError,
)
from server.classroom.lateness import SkippedCalls
from server.classroom.world import World
from server.host.processes.start_pacing import (
    MachineStartPacer,
    StartPacer,
    default_slots,
    machine_slots_file,
)
from server.host.settings import Settings, class_section
from server.peripherals.devices.shared_physics import SharedQuadrotorPhysics, SharedSimpleSim
from server.services.launch.groups import NodeBudget
from server.world.checkpoints.catalog import load as load_checkpoints
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.store import ProgressStore
from server.world.lab import Lab

MAX_DOMAIN_ID = 232  # ROS 2's highest ROS_DOMAIN_ID
Launch = tuple[str, dict[str, str]]  # a launch file and its arguments


class WorldLabs:
    """The worlds by name (``worlds``, shared with whoever shows them), those starting, and the
    labs of those that run here. ``endpoint`` says where a world's graph connects now (None: no
    Zenoh), ``process_socket`` the router's Unix socket on this machine for the worlds' sandboxed
    nodes (None: none here)."""

    def __init__(
        self,
        settings: Settings,
        clock: Clock,
        endpoint: Callable[[], str | None],
        process_socket: Callable[[], Path | None],
        worlds: dict[str, World] | None = None,
    ) -> None:
        self.settings = settings
        self.class_settings = class_section(settings)
        self.clock = clock  # every world's, the physics' and the limits'
        self.endpoint = endpoint
        self.process_socket = process_socket
        self.worlds: dict[str, World] = worlds if worlds is not None else {}
        self.starting: dict[str, int] = {}  # world → its ROS domain, while it starts
        self.physics = SharedQuadrotorPhysics(clock)
        self.simple_physics = SharedSimpleSim(clock)  # the worlds flown with simple:=true
        self.executors = ExecutorGroup()
        self.node_budget = NodeBudget(settings.limits.max_server_nodes)  # every world's node processes
        # and their starts, which yield to these worlds' ticks
        self.skipped = SkippedCalls(
            lambda: [w.lab.bus for w in list(self.worlds.values()) if w.lab is not None]
        )
        self.start_pacer = _start_pacer(settings, clock, self.skipped.read)
        # Each world's checkpoints and answers, kept in the state folder across restarts.
        self.progress = ProgressStore.in_state_dir(settings.lab.state_dir)

    def get(self, name: str) -> World:
        world = self.worlds.get(name)
        if world is None:
            raise UnknownWorldError(f"no world named {name!r}")
        return world

    def taken(self, name: str) -> bool:
        return name in self.worlds or name in self.starting

    def full(self) -> bool:
        return len(self.worlds) + len(self.starting) >= self.class_settings.max_worlds

    @property
    def hosted_here(self) -> int:
        """Worlds this process runs itself (not on a world worker)."""
        return sum(1 for w in self.worlds.values() if w.worker is None)

    @property
    def local_capacity(self) -> int:
        return self.class_settings.local_capacity

    def write_limit(self) -> RateLimit:
        return RateLimit(
            self.clock, self.class_settings.world.writes_hz, self.class_settings.world.writes_burst
        )

    def free_domain(self, also_taken: set[int]) -> int:
        """The lowest ROS domain no world, starting world, nor ``also_taken`` holds."""
        taken = {w.domain_id for w in self.worlds.values()} | set(self.starting.values()) | also_taken
        if self.settings.lab.zenoh is not None:
            taken.add(self.settings.lab.zenoh.domain_id)  # the class's own domain stays empty
        free = (d for d in range(1, MAX_DOMAIN_ID + 1) if d not in taken)
        domain = next(free, None)
        if domain is None:
            raise ClassFullError(f"every ROS domain (1..{MAX_DOMAIN_ID}) is taken")
        return domain

    def charge_reset(self, name: str) -> None:
        """A student's reset: one of their world's few resets, and one of its writes
        (RateLimitedError over either, which charges neither)."""
        world = self.get(name)
        limits, resets = self.class_settings.world, world.reset_limit
        if resets is not None and not resets.ready():
            resets.refused += 1
            raise RateLimitedError(
                f"too many resets of world {name!r}: at most {limits.resets_burst} in a row, "
                f"then one in {1 / limits.resets_hz:g} s",
                resets.retry_after_s(),
            )
        if not world.writes.take():
            raise RateLimitedError(
                f"too many requests for world {name!r}: at most {limits.writes_hz:g} writes a second",
                world.writes.retry_after_s(),
            )
        if resets is not None:
            resets.take()

    async def start(
        self,
        name: str,
        domain_id: int,
        launch: Launch | None = None,
        login: Credentials | None = None,
        progress: Progress | None = None,
    ) -> Lab:
        """Start world ``name``'s lab in ``domain_id`` (the class's launch unless ``launch``), with
        ``progress`` (a reset's), else the one its files keep."""
        socket = self.process_socket()
        settings = self._world_settings(name, domain_id, launch, login, socket)
        if progress is None:
            checkpoints = load_checkpoints(self.settings.lab.checkpoints)
            progress = await asyncio.to_thread(self.progress.open, name, checkpoints)
        # On a world worker without the class router's socket, a sandbox that could be built here
        # cannot reach the router: its refusal says so.
        away = (
            StudentCodeElsewhereError(name) if self.settings.worker is not None and socket is None else None
        )
        lab = Lab(
            settings,
            self.clock,
            executors=self.executors,
            progress=progress,
            node_budget=self.node_budget,
            start_pacer=self.start_pacer,
            label=name,  # its nodes' console lines carry its name
            devices={"quadrotor_physics": self.physics, "simple_sim_physics": self.simple_physics},
            sandbox_unreachable=away,
        )  # every world's drone stepped in one batch, by the shared physics
        await lab.start()
        return lab

    async def remove_progress(self, name: str) -> None:
        """Remove world ``name``'s saved progress (its student was removed)."""
        await asyncio.to_thread(self.progress.remove, name)

    async def close_progress(self) -> None:
        """Write every world's progress that is still queued (the server stops)."""
        await asyncio.to_thread(self.progress.close)

    async def restart(self, world: World) -> None:
        """A world that runs here, fresh: same name, domain, login and launch, every node anew."""
        assert world.lab is not None
        await world.lab.stop()  # first: the new world takes the same ROS domain on the graph
        launch = world.lab.settings.lab.launch, world.lab.settings.lab.launch_args
        progress = world.lab.checkpoints.progress  # what was met stays met
        world.lab = await self.start(world.name, world.domain_id, launch, world.login, progress)

    def _world_settings(
        self, name: str, domain_id: int, launch: Launch | None, login: Credentials | None, socket: Path | None
    ) -> Settings:
        endpoint = self.endpoint()
        zenoh = None
        if endpoint is not None:
            config_file = self.settings.lab.zenoh.config_file if self.settings.lab.zenoh is not None else None
            zenoh = ZenohSettings(
                mode="client",
                listen=(),
                connect=(endpoint,),
                domain_id=domain_id,
                config_file=config_file,
                login=login,
                samples_hz=self.class_settings.world.samples_hz,
                process_socket=socket,
            )
        file, args = (
            launch if launch is not None else (self.settings.lab.launch, self.settings.lab.launch_args)
        )
        return self.settings.for_world(name, zenoh, file, args)


def _start_pacer(settings: Settings, clock: Clock, skipped: Callable[[], float]) -> StartPacer:
    """The class server's node starts and those of the world workers it started on this machine
    take turns at the machine's slots; a world worker started by hand paces its own. Each yields
    to what its worlds' timers ``skipped``, the machine's to what any of its places' skipped."""
    if settings.worker is None:
        return MachineStartPacer(machine_slots_file(settings.lab.state_dir), default_slots(), skipped=skipped)
    if settings.worker.start_slots is not None:
        return MachineStartPacer(settings.worker.start_slots, default_slots(), skipped=skipped)
    return StartPacer(default_slots(), clock=clock.now, skipped=skipped)
