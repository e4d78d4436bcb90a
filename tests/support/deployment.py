"""The class's deployment files as the tests read them: compose.class.yml with each
``${NAME:-default}`` at its default, a world worker's command out of its ``sh -c`` wrapper, and a
command's options given other values (a test's loopback addresses, free ports, folders)."""

from __future__ import annotations

import re
import shlex
from pathlib import PurePosixPath
from typing import Any

import yaml

from support.app import REPO

COMPOSE_CLASS = REPO / "compose.class.yml"
KUBERNETES_CLASS = REPO / "deploy" / "kubernetes" / "class.yaml"

_DEFAULTED = re.compile(r"\$\{(\w+):-([^}]*)\}")
# The worker's container names itself to the class server by its own address (hostname -i).
_WORKER_SHELL = re.compile(r"set -- \$\(hostname -i\) && exec (.+)", re.DOTALL)


def at_defaults(value: Any) -> Any:
    """``value`` (a loaded compose file or any part of it) with every ``${NAME:-default}`` at its
    default and ``$$`` as the ``$`` the container sees, as Compose interpolates with none set."""
    if isinstance(value, str):
        return _DEFAULTED.sub(lambda m: m.group(2), value).replace("$$", "$")
    if isinstance(value, list):
        return [at_defaults(item) for item in value]
    if isinstance(value, dict):
        return {key: at_defaults(item) for key, item in value.items()}
    return value


def class_compose() -> dict[str, Any]:
    """compose.class.yml's services, read as the file is (no container engine needed)."""
    loaded: dict[str, Any] = yaml.safe_load(COMPOSE_CLASS.read_text())
    services: dict[str, Any] = at_defaults(loaded["services"])
    return services


def worker_argv(command: list[str]) -> list[str]:
    """The ``python -m server world-worker ...`` a worker's ``sh -c`` command execs (``$$`` read as
    ``$``, as in docker-compose's printed config)."""
    assert command[:2] == ["sh", "-c"] and len(command) == 3, command
    found = _WORKER_SHELL.fullmatch(command[2].replace("$$", "$"))
    assert found is not None, command[2]
    return shlex.split(found.group(1))


def server_args(argv: list[str]) -> list[str]:
    """The arguments after ``python -m server``."""
    assert argv[:3] == ["python", "-m", "server"], argv
    return argv[3:]


def swapped(args: list[str], values: dict[str, str]) -> list[str]:
    """``args`` with each option in ``values`` given that value instead (every time it appears);
    each must appear, so a file that stops setting one fails here rather than running with
    another default."""
    out = list(args)
    for option, value in values.items():
        where = [i for i, arg in enumerate(out) if arg == option]
        assert where, f"{option} is not in {args}"
        for i in where:
            out[i + 1] = value
    return out


def option(args: list[str], name: str) -> str:
    """The value of option ``name`` (its last, as argparse takes it)."""
    where = [i for i, arg in enumerate(args) if arg == name]
    assert where, f"{name} is not in {args}"
    return args[where[-1] + 1]


def server_settings(command: list[str]) -> Any:
    """The settings ``python -m server ARGS`` would start with: the server's parser and checks."""
    from server.__main__ import build_parser, check_launch, settings_of, zenoh_settings

    args = build_parser().parse_args(server_args(command))
    settings = settings_of(args, zenoh_settings(args))
    assert check_launch(settings) is None
    return settings


def worker_settings(argv: list[str], class_token: str = "the-instructors-token") -> Any:
    """The settings ``python -m server world-worker ARGS`` would serve with (its port as given):
    the worker's parser and every rule of the settings model."""
    from server.world_worker import build_parser, worker_settings

    args = server_args(argv)
    assert args[0] == "world-worker", argv
    parsed = build_parser().parse_args(args[1:])
    return worker_settings(parsed, class_token, parsed.port)


def image_workdir() -> PurePosixPath:
    """The Dockerfile's WORKDIR, where the app runs and its relative folders are."""
    text = (REPO / "Dockerfile").read_text()
    return PurePosixPath(next(line.split()[1] for line in text.splitlines() if line.startswith("WORKDIR")))
