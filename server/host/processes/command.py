"""The command line and environment of a node process, for the app's launcher and ``ros2lab run``."""

from __future__ import annotations

import dataclasses
import json
import os
import secrets
import sys
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from node_runtime.ament.entry_points import EntryPoint
from node_runtime.ament.workspace import WORKSPACE_ENV
from node_runtime.process.runner import LAUNCH_MODE, PARENT_ENV
from node_runtime.transport.acl import Credentials, process_config
from node_runtime.transport.config import DEFAULT_ROUTER_ENDPOINT

CLIENT_DIR = Path(__file__).resolve().parents[3] / "client"
RUNNER_MODULE = "node_runtime.process.runner"


@dataclass(frozen=True)
class PreparedStart:
    """What a node's start needs at the moment it starts, made then (a sandboxed node's control
    group and seccomp filter: server/host/processes/sandbox.py)."""

    argv: list[str]
    pass_fds: tuple[int, ...] = ()  # descriptors the new process gets; closed here once it started
    # Called once the process has ended, with its exit code: a line to add to its output, or None.
    finish: Callable[[int], str | None] = lambda _code: None


@dataclass(frozen=True)
class NodeCommand:
    argv: list[str]
    env: dict[str, str]
    zid: str  # the Zenoh session id the process will have, so the graph can tell which process it is
    sandboxed: bool = False  # argv is bwrap's: the node is its child (server/host/processes/sandbox.py)
    # Makes what the start needs when it starts (None: argv as it is, nothing to pass or clean up).
    prepare: Callable[[list[str], str], PreparedStart] | None = None


def ros_args(
    name: str | None,
    namespace: str | None,
    parameters: Iterable[tuple[str, Any]],
    remappings: Iterable[tuple[str, str]],
    params_files: Iterable[str] = (),
) -> list[str]:
    """``--ros-args`` as ``ros2 launch`` passes a ``<node>``'s name, namespace, params and remaps
    (its parameters files first: the node's ``-p`` win over them)."""
    out: list[str] = []
    if name:
        out += ["-r", f"__node:={name}"]
    if namespace:
        out += ["-r", f"__ns:={namespace}"]
    for path in params_files:
        out += ["--params-file", path]
    for key, value in parameters:
        out += ["-p", f"{key}:={json.dumps(value) if not isinstance(value, str) else value}"]
    for source, target in remappings:
        out += ["-r", f"{source}:={target}"]
    return ["--ros-args", *out] if out else []


def new_zid() -> str:
    """A Zenoh session id: 128 bits in lowercase hex, no leading zero (Zenoh refuses those)."""
    digits = secrets.token_hex(16)
    return ("1" + digits[1:]) if digits[0] == "0" else digits


def graph_overrides(router: str, login: Credentials | None) -> list[str]:
    """``ZENOH_CONFIG_OVERRIDE`` entries that join a lab's graph: its router and, if the router asks
    for one, the login (a class's node process is then a client of the router only)."""
    entries = [f"connect/endpoints={json.dumps([router])}"]
    if login is not None:
        entries += [f"{path}={value}" for path, value in process_config(login).items()]
    return entries


def node_command(
    target: Path | str | EntryPoint,
    args: list[str],
    *,
    router: str | None = None,
    domain_id: int = 0,
    login: Credentials | None = None,
    env: Mapping[str, str] | None = None,
    workspace: Path | None = None,
) -> NodeCommand:
    """Run ``target`` (a student's file or console script, or ``module:Class`` of a built-in node) in
    its own process, joined to the router at ``router`` (``tcp/HOST:PORT``); the interface packages
    of ``workspace`` import in it."""
    # -P: neither the current folder nor a script's folder goes first on sys.path (a student's
    # ``server/`` package there would replace the runner).
    runner = [sys.executable, "-P", "-u", "-m", RUNNER_MODULE]
    # Absolute: a sandboxed node starts in its workspace, not in the server's folder.
    if isinstance(target, Path):
        target = target.resolve()
    elif isinstance(target, EntryPoint):
        target = dataclasses.replace(target, root=target.root.resolve())
    if isinstance(target, EntryPoint):
        argv = [*runner, *target.argv(), *args]
    else:
        argv = (
            [*runner, str(target), *args]
            if isinstance(target, Path)
            else [*runner, "--builtin", target, *args]
        )
    zid = new_zid()
    overrides = [*graph_overrides(router or DEFAULT_ROUTER_ENDPOINT, login), f'id="{zid}"']
    base = dict(os.environ if env is None else env)
    inherited = base.get("ZENOH_CONFIG_OVERRIDE", "")
    child_env = {
        **base,
        "PYTHONUNBUFFERED": "1",
        # A node imports the student's own modules from the workspace: their compiled copies
        # (__pycache__) would appear beside them, in the page's tree and the workspace's zip.
        "PYTHONDONTWRITEBYTECODE": "1",
        "ROS_DOMAIN_ID": str(domain_id),
        "ZENOH_CONFIG_OVERRIDE": ";".join(filter(None, [inherited, *overrides])),
        PARENT_ENV: str(os.getpid()),
    }
    if workspace is not None:
        child_env[WORKSPACE_ENV] = str(workspace.resolve())
    return NodeCommand(argv, child_env, zid)


def launch_command(
    file: Path,
    request: str,
    *,
    domain_id: int = 0,
    env: Mapping[str, str] | None = None,
    workspace: Path | None = None,
) -> NodeCommand:
    """Evaluate the Python launch file ``file`` with ``request`` (its arguments, as JSON) in a
    process of its own, as a node process runs (node_runtime.process.runner's ``--launch-description``);
    it joins no graph."""
    base = dict(os.environ if env is None else env)
    child_env = {
        **base,
        "PYTHONUNBUFFERED": "1",
        "PYTHONDONTWRITEBYTECODE": "1",
        "ROS_DOMAIN_ID": str(domain_id),
        PARENT_ENV: str(os.getpid()),
    }
    if workspace is not None:
        child_env[WORKSPACE_ENV] = str(workspace.resolve())
    argv = [sys.executable, "-P", "-u", "-m", RUNNER_MODULE, LAUNCH_MODE, str(file.resolve()), request]
    return NodeCommand(argv, child_env, new_zid())
