"""Settings for one app instance, in one frozen model: where it listens and what it lets in
(``listen``), what its lab runs (``lab``), what a lab's clients may hold (``limits``), and, for a
class server or a world worker, the class (``classroom``) and the worker (``worker``).

Every rule across fields lives here, so ``python -m server``, ``ros2lab world-worker`` and a test
that builds settings by hand meet the same ones; so does every default: the two command lines
read their options' defaults from the fields (:func:`default_of`), and the few where a command
line differs from a model built by hand are constants here (``FOXGLOVE_PORT``,
``WORKER_MAX_WORLDS``, ``WORKER_PORT``). The rules' messages name the command-line options,
where people meet them; :func:`explain` turns a ``ValidationError`` into those lines, and
:func:`is_refusal` tells an unsafe combination (no login beyond loopback) from a usage mistake.
"""

from __future__ import annotations

from pydantic import ValidationError, field_validator, model_validator
from pydantic_core import PydanticCustomError

from node_runtime.transport.config import ZenohSettings, is_loopback
from server.base.loop_priority import Scheduling
from server.host.settings.base import (
    ANY_ADDRESS,
    LOCAL_WORLDS_RULE,
    LOOPBACK_HOSTS,
    MAX_LOCAL_WORKERS,
    ORPHAN_TIMEOUT_S,
    REFUSAL,
    SPREAD_AT_WORLDS,
    WORKER_TIMEOUT_S,
    WORKERS_RULE,
    Section,
    choices_of,
    default_of,
    is_loopback_host,
    log_level,
    shown,
)
from server.host.settings.classroom import (
    WORKER_MAX_WORLDS,
    WORKER_PORT,
    ClassroomSettings,
    JoinLimits,
    JoinQueueSettings,
    WorkerSettings,
    WorldLimits,
)
from server.host.settings.lab import (
    FOXGLOVE_PORT,
    LabLimits,
    LabSettings,
    Listening,
    SandboxSettings,
    WorkspaceLimits,
)

__all__ = [
    "ANY_ADDRESS",
    "FOXGLOVE_PORT",
    "LOCAL_WORLDS_RULE",
    "LOOPBACK_HOSTS",
    "MAX_LOCAL_WORKERS",
    "ORPHAN_TIMEOUT_S",
    "REFUSAL",
    "SPREAD_AT_WORLDS",
    "WORKERS_RULE",
    "WORKER_MAX_WORLDS",
    "WORKER_PORT",
    "WORKER_TIMEOUT_S",
    "ClassroomSettings",
    "JoinLimits",
    "JoinQueueSettings",
    "LabLimits",
    "LabSettings",
    "Listening",
    "SandboxSettings",
    "Section",
    "Settings",
    "WorkerSettings",
    "WorkspaceLimits",
    "WorldLimits",
    "choices_of",
    "class_section",
    "default_of",
    "explain",
    "is_loopback_host",
    "is_refusal",
    "shown",
]


class Settings(Section):
    """One app: a single lab (no ``classroom``), a class server (``classroom``) or a world
    worker (``classroom`` and ``worker``)."""

    listen: Listening = Listening()
    lab: LabSettings = LabSettings()
    limits: LabLimits = LabLimits()
    workspace: WorkspaceLimits = WorkspaceLimits()
    classroom: ClassroomSettings | None = None
    worker: WorkerSettings | None = None
    sandbox: SandboxSettings = SandboxSettings()
    log_level: str = "info"  # the app's own console lines and uvicorn's
    # The thread of the worlds' loop in the kernel's real-time class where the machine allows it
    # (server/base/loop_priority.py), or left in the fair class with every other thread.
    loop_priority: Scheduling = "realtime"

    @field_validator("log_level")
    @classmethod
    def _level(cls, value: str) -> str:
        return log_level(value)

    @model_validator(mode="after")
    def _class_needs_zenoh(self) -> Settings:
        classroom = self.classroom
        if classroom is None:
            return self
        # auto needs no router: without one (--no-zenoh, or a client of another) none are started
        if classroom.workers_at_start and self.lab.zenoh_router is None:
            raise ValueError(WORKERS_RULE)
        if classroom.local_worlds is not None and self.lab.zenoh is None:
            raise ValueError(LOCAL_WORLDS_RULE)
        return self

    @model_validator(mode="after")
    def _worker_is_reachable(self) -> Settings:
        if self.worker is None:
            return self
        if self.classroom is None:
            raise ValueError("a world worker hosts a class's worlds: it needs the classroom section")
        host = self.worker.url.partition("://")[2].rpartition(":")[0].strip("[]")
        if host in ANY_ADDRESS:
            raise ValueError(
                "with --host 0.0.0.0, name the address the class server reaches this machine on: --advertise HOST"
            )
        return self

    @model_validator(mode="after")
    def _login_beyond_loopback(self) -> Settings:
        """Anyone who reaches a port beyond loopback could fly the drone: such an app needs a login,
        one lab's token or a class's."""
        if self.classroom is not None or self.listen.token is not None:
            return self
        if not self.listen.on_loopback:
            raise PydanticCustomError(
                REFUSAL,
                "refusing to listen on {host} with no login: anyone who reaches this machine could fly the "
                "drone. Add --token auto (one lab behind a token) or --classroom (a world per student).",
                {"host": self.listen.host},
            )
        router = self.lab.zenoh_router
        wide = [e for e in router.listen if not is_loopback(e)] if router is not None else []
        if wide:
            raise PydanticCustomError(
                REFUSAL,
                "refusing to open the Zenoh router on {wide} with no login: anyone who reaches it could join "
                "the graph and fly the drone. Add --token auto (the router then asks every session for the "
                "lab's login: GET /api/zenoh/join gives it) or --classroom.",
                {"wide": ", ".join(wide)},
            )
        return self

    def for_world(
        self, name: str, zenoh: ZenohSettings | None, launch: str, launch_args: dict[str, str]
    ) -> Settings:
        """A class world's lab: its own graph session (``zenoh``), launch, bag folder and workspace, no bridge
        port of its own (the class's serve every world), and the smaller of each lab limit and the
        class's limit per world."""
        if self.classroom is None:
            raise ValueError("only a class server or a world worker has worlds")
        world, limits = self.classroom.world, self.limits
        lab = self.lab.model_copy(
            update={
                "zenoh": zenoh,
                "foxglove_port": None,
                "rosbridge_port": None,
                "bag_dir": self.lab.bag_dir / name,
                "launch": launch,
                "launch_args": launch_args,
                "workspace": self.classroom.workspaces_dir / name,
            }
        )
        limits = limits.model_copy(
            update={
                "max_launch_groups": min(limits.max_launch_groups, world.launches),
                "max_nodes_per_launch": min(limits.max_nodes_per_launch, world.launch_nodes),
                "socket_frames_hz": world.socket_frames_hz,
                "socket_requests_hz": world.socket_requests_hz,
            }
        )
        return self.model_copy(update={"lab": lab, "limits": limits})

    @property
    def confines_paths(self) -> bool:
        """Bag and launch files are names inside the world's own folders, never paths: on a class
        server (and its world workers), and when a lab behind a token listens beyond loopback. A
        single lab on loopback serves its user alone, whose own files it may open."""
        return self.classroom is not None or not self.listen.on_loopback

    @property
    def sandboxes_students(self) -> bool:
        """Students' node processes run in a sandbox: wherever the server serves others, unless
        started with ``--student-code unsandboxed``."""
        return self.confines_paths and self.sandbox.student_code == "sandboxed"


def class_section(settings: Settings) -> ClassroomSettings:
    """The class's section of a class server's or a world worker's settings (ValueError on a
    single lab's, which has no class)."""
    if settings.classroom is None:
        raise ValueError("a class server or world worker needs settings with a classroom section")
    return settings.classroom


def explain(error: ValidationError) -> str:
    """The error's lines as a person reads them: a rule's own message, or a field's path and what
    is wrong with its value."""
    lines = []
    for item in error.errors(include_url=False):
        message = item["msg"].removeprefix("Value error, ")
        where = ".".join(str(part) for part in item["loc"])
        lines.append(f"{where}: {message}" if where and item["type"] != "value_error" else message)
    return "\n".join(lines)


def is_refusal(error: ValidationError) -> bool:
    """The settings are well formed but unsafe: a port beyond loopback with no login."""
    return any(item["type"] == REFUSAL for item in error.errors())
