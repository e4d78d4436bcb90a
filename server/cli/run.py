"""``run PKG EXEC [--ros-args ...]``: the executable as a child process, as ``ros2 run`` starts it.

Its output streams to this terminal as it comes, each Ctrl-C is passed on to it (the child has a
session of its own, so the terminal's Ctrl-C reaches only this command; one that still runs
``STOP_GRACE_S`` after the first is killed), and its exit code is this command's. A class server
asks for its node processes to run below its worlds (``nice`` in the join's answer): the child
then takes that niceness, and so does its session's scheduling group
(node_runtime/process/priority.py), wherever the command runs. It joins the graph of the lab the
command talks to (``--url``): the lab tells where its Zenoh router listens, its ROS domain and its
login (server/cli/join.py: asked again with a bounded backoff while the lab does not answer, and
after the time it gives while it paces a class's node starts). A lab that does not answer within
``--join-timeout`` is one line and a non-zero exit, and no node starts: nothing falls back to
another router or domain.
"""

from __future__ import annotations

import argparse
import signal
import sys
import time
from typing import TYPE_CHECKING, Any

from server.cli.errors import CliError
from server.cli.join import WAIT_S, Pacing, join_graph
from server.cli.plain_get import LabGetter, getter_for
from server.cli.priority import take_the_labs_nice
from server.cli.workspace import add_workspace_option, workspace_of

if TYPE_CHECKING:
    from pathlib import Path

    from node_runtime.ament.index import Executable
    from node_runtime.transport.acl import Credentials
    from server.cli.client import LabClient

# A class's sixty ``ros2lab run`` at once share the CPU until each has asked the lab for its turn,
# and none has asked before all are nearly done: the command asks with little imported, finds
# its file (the package index) while it waits for its turn, and imports what the node's command
# needs (its login, the runner's command line, subprocess) once it has the turn.

STOP_GRACE_S = 10.0


def graph_of(join: dict[str, Any], url: str) -> tuple[str, int, Credentials | None]:
    """The router endpoint, ROS domain and login of the lab's join answer (on a class server with
    ROS2LAB_TOKEN: the student's world's); ROS_DOMAIN_ID, if set, wins."""
    endpoint = join.get("router")
    if not isinstance(endpoint, str) or not endpoint:
        raise CliError(f"the lab at {url} named no Zenoh router to join; the node was not started")
    domain = join.get("domain_id")
    from node_runtime.transport.acl import Credentials
    from node_runtime.transport.config import domain_id_from_env

    user, password = join.get("user"), join.get("password")
    login = Credentials(user, password) if isinstance(user, str) and isinstance(password, str) else None
    return endpoint, domain_id_from_env(default=domain if isinstance(domain, int) else 0), login


class NotFound(Exception):
    """The package or its executable is not in the workspace: said as ``ros2 run`` says it."""


def find(args: argparse.Namespace, lab: LabGetter) -> tuple[Executable, Path]:
    """The executable ``args`` names, in the workspace it runs from."""
    from node_runtime.ament.index import (
        ExecutableNotFoundError,
        PackageIndex,
        PackageNotFoundError,
        WorkspaceError,
    )

    workspace = workspace_of(args, lab)
    try:
        return PackageIndex(workspace=workspace).resolve(args.package_name, args.executable_name), workspace
    except PackageNotFoundError:
        raise NotFound(f"Package '{args.package_name}' not found") from None
    except ExecutableNotFoundError as exc:
        raise NotFound(f"No executable found: {exc}") from None
    except WorkspaceError as exc:
        raise NotFound(str(exc)) from None


def run(args: argparse.Namespace, client: LabClient) -> int:
    pacing = Pacing(wait_s=args.join_timeout)
    lab = getter_for(client)  # no HTTP library to import for an http:// lab
    found: list[tuple[Executable, Path]] = []
    try:  # the file is found while the start waits for its turn, or after the lab's first answer
        join = join_graph(lab, pacing, start=True, meanwhile=lambda: found.append(find(args, lab)))
        exe, workspace = found[0] if found else find(args, lab)
    except NotFound as exc:
        print(exc, file=sys.stderr)
        return 1
    router, domain_id, login = graph_of(join, client.base_url)
    import subprocess

    from node_runtime.process.priority import set_session_group_nice
    from server.host.processes.command import node_command

    command = node_command(
        exe.target, list(args.argv), router=router, domain_id=domain_id, login=login, workspace=workspace
    )
    nice = join.get("nice")
    if isinstance(nice, int) and nice > 0:
        take_the_labs_nice(nice)  # the child inherits it; this command only waits
    child = subprocess.Popen(command.argv, env=command.env, start_new_session=True)
    if isinstance(nice, int) and nice > 0:
        set_session_group_nice(child.pid, nice)
    deadline: float | None = None  # STOP_GRACE_S after the first Ctrl-C
    while True:
        try:
            return child.wait(timeout=None if deadline is None else max(0.0, deadline - time.monotonic()))
        except KeyboardInterrupt:
            # Every Ctrl-C reaches the node, as each one typed in a terminal reaches a node ``ros2
            # run`` started: a second one still stops a node that caught the first, or whose main
            # thread sat in a lock when the first came (Python may then never run its handler).
            child.send_signal(signal.SIGINT)
            if deadline is None:
                deadline = time.monotonic() + STOP_GRACE_S
        except subprocess.TimeoutExpired:
            child.kill()  # it ignored Ctrl-C for STOP_GRACE_S
            return child.wait()


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    p = verbs.add_parser("run", parents=[common], help="Run a package specific executable")
    p.add_argument("package_name", help="Name of the ROS package")
    p.add_argument("executable_name", help="Name of the executable")
    add_workspace_option(p)
    p.add_argument(
        "--join-timeout",
        type=float,
        default=WAIT_S,
        metavar="S",
        help=f"seconds to keep asking a lab that does not answer before giving up (default {WAIT_S:.0f})",
    )
    p.add_argument("argv", nargs=argparse.REMAINDER, help="--ros-args -p NAME:=VALUE -r FROM:=TO")
    p.set_defaults(handler=run)
