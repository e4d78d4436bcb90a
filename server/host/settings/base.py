"""What every section of the settings shares: a frozen model that refuses unknown names, the
loopback names, the class's timing constants, the rules' messages, and the fields' defaults and
choices as the command lines read them."""

from __future__ import annotations

import typing
from pathlib import PurePath
from typing import Any

from pydantic import BaseModel, ConfigDict

from node_runtime.console import LEVELS

LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
ANY_ADDRESS = ("0.0.0.0", "::")
# A class's world workers: the class server takes a worker silent this long as gone and
# starts its worlds again elsewhere; a worker that hears no hello this long frees its worlds first.
WORKER_TIMEOUT_S = 20.0
ORPHAN_TIMEOUT_S = 12.0
MAX_LOCAL_WORKERS = 32  # --workers: world workers a class server starts on its own machine
SPREAD_AT_WORLDS = 10  # --workers auto: another world worker on this machine each this many worlds
# --worlds-per-core: a machine's world budget for each core. 30 students with the handout's two
# nodes each kept every world near 100 Hz on 2 vCPUs; 45 did not (docs/classroom.md, its sizes).
WORLDS_PER_CORE = 15
REFUSAL = "login_required"  # the error type of an app that would listen beyond loopback with no login

WORKERS_RULE = (
    "--workers needs --classroom and this server's own Zenoh router (world workers join it), "
    f"and N in 0..{MAX_LOCAL_WORKERS} or auto"
)
LOCAL_WORLDS_RULE = "--local-worlds needs --classroom and Zenoh (world workers join its router), and N >= 0"


def is_loopback_host(host: str) -> bool:
    return host in LOOPBACK_HOSTS or host.startswith("127.")


class Section(BaseModel):
    """A frozen group of settings that refuses names it does not know (a typo is an error)."""

    model_config = ConfigDict(frozen=True, extra="forbid")


def log_level(value: str) -> str:
    if value not in LEVELS:
        raise ValueError(f"a log level is one of {', '.join(LEVELS)}, got {value!r}")
    return value


def default_of(section: type[BaseModel], name: str) -> Any:
    """The default of the field ``name`` of ``section``. ``python -m server`` and ``ros2lab
    world-worker`` take their options' defaults from here, so each default is written once: in
    the model."""
    return section.model_fields[name].get_default(call_default_factory=True)


def choices_of(section: type[BaseModel], name: str) -> tuple[str, ...]:
    """The values a ``Literal`` field takes, for an option's ``choices``."""
    return typing.get_args(section.model_fields[name].annotation)


def shown(value: object) -> str:
    """A default as a command line's help shows it: ``./bags`` for a folder under the current one,
    ``20`` for 20.0 seconds."""
    if isinstance(value, PurePath) and not value.is_absolute():
        return f"./{value}"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)
