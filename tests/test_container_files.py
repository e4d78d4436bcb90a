"""docker-compose.yml and the Dockerfile, checked without a container engine: Debian's
docker-compose (scripts/test.sh installs it) resolves the compose file as ``docker-compose config``
does, and the server's own option parser takes the command each file starts it with, so a renamed
option or a volume mounted where the server does not keep its state fails here.
"""

from __future__ import annotations

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

from server.__main__ import build_parser, check_launch, settings_of, zenoh_settings

COMPOSE = REPO / "docker-compose.yml"
DOCKERFILE = REPO / "Dockerfile"


def compose_config(path: Path) -> subprocess.CompletedProcess[str]:
    tool = shutil.which("docker-compose")
    if tool is None:
        message = "no docker-compose on this machine (scripts/test.sh installs Debian's)"
        if os.environ.get("CI") == "true":
            pytest.fail(f"{message}; in CI the compose file's check must run")
        pytest.skip(message)
    env = {k: v for k, v in os.environ.items() if k not in ("LAUNCH", "LAB_TOKEN")}  # the file's defaults
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


def server_settings(command: list[str]) -> Any:
    """The settings ``python -m server ARGS`` would start with: the server's parser and checks."""
    assert command[:3] == ["python", "-m", "server"], command
    args = build_parser().parse_args(command[3:])
    settings = settings_of(args, zenoh_settings(args))
    assert check_launch(settings) is None
    return settings


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
