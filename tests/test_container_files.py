"""docker-compose.yml (the single lab), compose.class.yml (a class: the class server and world
workers) and the Dockerfile, checked without a container engine: Debian's docker-compose
(scripts/test.sh installs it) resolves each compose file as ``docker-compose config`` does, and the
server's and the world worker's own option parsers take the command each service starts with, so a
renamed option or a volume mounted where the server does not keep its state fails here.
"""

from __future__ import annotations

import functools
import os
import re
import shutil
import subprocess
import tomllib
from pathlib import Path, PurePosixPath
from typing import Any

import pytest
import yaml
from support.app import REPO
from support.deployment import (
    COMPOSE_CLASS,
    image_workdir,
    option,
    server_args,
    server_settings,
    swapped,
    worker_argv,
    worker_settings,
)

from server.classroom.worker_control import TOKEN_ENV

COMPOSE = REPO / "docker-compose.yml"
DOCKERFILE = REPO / "Dockerfile"
# The variables the compose files read: unset, so each resolves with the file's own defaults.
COMPOSE_VARIABLES = (
    "LAUNCH",
    "LAB_TOKEN",
    "CLASS_BIND",
    "CLASS_HOST",
    "MAX_WORLDS",
    "WORKER_MAX_WORLDS",
    "CLASS_SECRET_FILE",
    TOKEN_ENV,
)


def compose_config(path: Path) -> subprocess.CompletedProcess[str]:
    tool = shutil.which("docker-compose")
    if tool is None:
        message = "no docker-compose on this machine (scripts/test.sh installs Debian's)"
        if os.environ.get("CI") == "true":
            pytest.fail(f"{message}; in CI the compose file's check must run")
        pytest.skip(message)
    env = {k: v for k, v in os.environ.items() if k not in COMPOSE_VARIABLES}  # the file's defaults
    return subprocess.run(
        [tool, "--project-directory", str(path.parent), "-f", str(path), "config"],
        capture_output=True, text=True, timeout=60, env=env, check=False,
    )  # fmt: skip


def resolved_lab() -> dict[str, Any]:
    done = compose_config(COMPOSE)
    assert done.returncode == 0, done.stderr
    config: dict[str, Any] = yaml.safe_load(done.stdout)
    service: dict[str, Any] = config["services"]["lab"]
    return service | {"named_volumes": set(config.get("volumes") or {})}


def port_of(port: str | dict[str, Any]) -> tuple[str, int, int]:
    """(host address, published port, container port), from Compose's short form
    (``127.0.0.1:8000:8000/tcp``, as docker-compose 1 prints it) or its long one (Compose 2)."""
    if isinstance(port, dict):
        return port.get("host_ip", ""), int(port["published"]), int(port["target"])
    host, published, target = port.split("/")[0].rsplit(":", 2)
    return host, int(published), int(target)


def volume_of(volume: str | dict[str, Any]) -> tuple[str, str]:
    """(where in the container, what is mounted there) of a volume in either form."""
    if isinstance(volume, dict):
        return volume["target"], volume["source"]
    source, target = volume.split(":")[:2]
    return target, source


def dockerfile_lines() -> list[str]:
    """Its instructions, continuation lines joined."""
    return [line for line in re.sub(r"\\\n", " ", DOCKERFILE.read_text()).splitlines() if line.strip()]


def test_the_compose_file_resolves_and_publishes_on_this_machine_only() -> None:
    lab = resolved_lab()
    published = [port_of(p) for p in lab["ports"]]
    assert {target for _, _, target in published} == {8000, 7447, 8765}
    assert all(host == "127.0.0.1" for host, _, _ in published), published


def test_the_compose_command_starts_the_server_with_its_state_and_workspaces_on_named_volumes() -> None:
    lab = resolved_lab()
    settings = server_settings(lab["command"])
    workdir = PurePosixPath(
        next(line.split()[1] for line in dockerfile_lines() if line.startswith("WORKDIR"))
    )
    mounted = dict(volume_of(v) for v in lab["volumes"])
    state = str(workdir / settings.lab.state_dir)
    workspaces = str(workdir / "workspaces")  # a class server's --workspaces-dir default
    assert mounted.get(state) in lab["named_volumes"], (state, mounted)
    assert mounted.get(workspaces) in lab["named_volumes"], (workspaces, mounted)
    assert settings.listen.port == 8000


def test_a_compose_file_with_a_wrong_key_is_refused_naming_it(tmp_path: Path) -> None:
    """The control: the same check fails on a file docker-compose cannot use."""
    broken = tmp_path / "docker-compose.yml"
    broken.write_text(COMPOSE.read_text().replace("    ports:", "    portz:", 1))
    done = compose_config(broken)
    assert done.returncode != 0
    assert "portz" in done.stderr


def test_the_dockerfile_copies_every_package_the_app_installs_and_starts_the_server() -> None:
    lines = dockerfile_lines()
    copied = {source for line in lines if line.startswith("COPY") for source in line.split()[1:-1]}
    find = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]["find"]
    for pattern in find["include"]:  # each package, from the folder setuptools finds it in
        name = pattern.rstrip("*")
        (where,) = [w for w in find["where"] if (REPO / w / name).is_dir()]
        assert (name if where == "." else where) in copied, (name, copied)
    assert {"pyproject.toml", "static", "web"} <= copied, copied  # the install, the page and its build
    (cmd,) = [line for line in lines if line.startswith("CMD")]
    settings = server_settings(yaml.safe_load(cmd.removeprefix("CMD").strip()))
    assert settings.listen.port == 8000


# -- compose.class.yml: a class ---------------------------------------------------------------------
@functools.cache
def resolved_class() -> dict[str, Any]:
    """compose.class.yml as docker-compose resolves it (once: each test reads, none changes it)."""
    done = compose_config(COMPOSE_CLASS)
    assert done.returncode == 0, done.stderr
    config: dict[str, Any] = yaml.safe_load(done.stdout)
    return config


def test_the_class_compose_file_resolves_and_publishes_only_the_class_server_on_this_machine() -> None:
    config = resolved_class()
    assert set(config["services"]) == {"classroom", "worker"}
    classroom, worker = config["services"]["classroom"], config["services"]["worker"]
    published = [port_of(p) for p in classroom["ports"]]
    settings = server_settings(classroom["command"])
    router = settings.lab.zenoh_router
    assert router is not None
    router_port = int(router.listen[0].rsplit(":", 1)[1])
    assert {target for _, _, target in published} == {
        settings.listen.port,
        router_port,
        settings.lab.foxglove_port,
    }
    assert all(host == "127.0.0.1" for host, _, _ in published), published  # CLASS_BIND widens it
    assert "ports" not in worker  # scaled: reached on the compose network alone


def test_the_class_server_listens_in_its_container_as_a_class_with_its_state_on_named_volumes() -> None:
    config = resolved_class()
    classroom = config["services"]["classroom"]
    settings = server_settings(classroom["command"])
    klass = settings.classroom
    assert klass is not None  # --classroom: what lets it listen beyond loopback
    assert settings.listen.host == "0.0.0.0" and settings.lab.zenoh_router is not None
    assert settings.lab.zenoh_router.listen == ("tcp/0.0.0.0:7447",)
    assert klass.local_worlds == 0 and klass.workers_at_start == 0 and not klass.auto_workers
    assert settings.sandboxes_students  # the app's own default, untouched
    workdir = image_workdir()
    mounted = dict(volume_of(v) for v in classroom["volumes"])
    named = set(config.get("volumes") or {})
    for folder in (settings.lab.state_dir, klass.workspaces_dir):
        assert mounted.get(str(workdir / folder)) in named, (folder, mounted)
    assert classroom["restart"] == "unless-stopped"


def test_a_class_worker_joins_the_class_router_by_the_services_name() -> None:
    config = resolved_class()
    classroom, worker = config["services"]["classroom"], config["services"]["worker"]
    argv = worker_argv(worker["command"])
    # Its own address, which the shell wrapper reads (hostname -i), names it to the class server.
    assert option(argv, "--advertise") == "$1"
    settings = worker_settings(swapped(argv, {"--advertise": "172.18.0.5"}))
    router = server_settings(classroom["command"]).lab.zenoh_router
    assert settings.lab.zenoh.connect == (router.listen[0].replace("0.0.0.0", "classroom"),)
    assert (
        settings.listen.host == "0.0.0.0"
        and settings.worker.url == f"http://172.18.0.5:{settings.listen.port}"
    )
    assert TOKEN_ENV not in (worker.get("environment") or {})  # nothing from the class server's log
    assert TOKEN_ENV not in " ".join(worker["command"])
    assert worker["depends_on"] == {"classroom": {"condition": "service_healthy"}}
    assert worker["restart"] == "unless-stopped"


def test_both_class_services_read_the_class_secret_from_the_file_the_operator_made() -> None:
    config = resolved_class()
    (secret,) = config["secrets"].values()
    name = next(iter(config["secrets"]))
    # The operator's file beside compose.class.yml, never in the image's build context or in git.
    assert Path(secret["file"]) == COMPOSE_CLASS.parent / "class-secret", secret
    for ignored in (".dockerignore", ".gitignore"):
        assert "class-secret" in (REPO / ignored).read_text().split(), ignored
    services = config["services"]
    server = server_settings(services["classroom"]["command"])
    read = {
        "classroom": server.classroom.class_secret_file,
        "worker": Path(option(worker_argv(services["worker"]["command"]), "--class-secret-file")),
    }
    for service, path in read.items():
        (mounted,) = services[service]["secrets"]
        assert mounted["source"] == name and "target" not in mounted, mounted  # at /run/secrets/<name>
        assert path == Path("/run/secrets") / name, (service, path)


def test_each_class_services_health_check_asks_its_own_port() -> None:
    services = resolved_class()["services"]
    ports = {
        "classroom": server_settings(services["classroom"]["command"]).listen.port,
        "worker": int(option(server_args(worker_argv(services["worker"]["command"])), "--port")),
    }
    for name, port in ports.items():
        check = services[name]["healthcheck"]
        assert check["test"][:2] == ["CMD", "python"], check
        assert f"http://127.0.0.1:{port}/api/health" in check["test"][-1], (name, check)


def test_every_service_may_put_its_loop_in_the_real_time_class_as_the_images_user() -> None:
    """The image runs as an ordinary user (``USER lab``), who may take the real-time class only up to
    its RLIMIT_RTPRIO (server/base/loop_priority.py): each service is given 1, and leaves
    ``--loop-priority`` at realtime."""
    assert "USER lab" in dockerfile_lines()
    lab, services = resolved_lab(), resolved_class()["services"]
    for name, service in (("lab", lab), *services.items()):
        assert (service.get("ulimits") or {}).get("rtprio") == 1, (name, service.get("ulimits"))
    worker = worker_settings(
        swapped(worker_argv(services["worker"]["command"]), {"--advertise": "172.18.0.5"})
    )
    for settings in (
        server_settings(lab["command"]),
        server_settings(services["classroom"]["command"]),
        worker,
    ):
        assert settings.loop_priority == "realtime"


def test_a_class_compose_file_with_a_wrong_key_is_refused_naming_it(tmp_path: Path) -> None:
    """The control: the same check fails on a class file docker-compose cannot use."""
    broken = tmp_path / "compose.class.yml"
    text = COMPOSE_CLASS.read_text()
    assert "    depends_on:" in text
    broken.write_text(text.replace("    depends_on:", "    depends_onn:", 1))
    done = compose_config(broken)
    assert done.returncode != 0
    assert "depends_onn" in done.stderr
