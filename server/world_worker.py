"""``ros2lab world-worker --connect tcp/HOST:7447``: host worlds for a class server.

The worker joins the class's Zenoh router (logged in as the class, with a password derived from
the instructor's token: the router lets nobody else in), serves its own HTTP API (loopback by default; every
call needs a token derived from the instructor's), and answers the class server's hello with
where that API is and how many worlds it hosts. Its worlds join the same router in the ROS
domains the class server gives them, so a student's node processes find them as before.

    ROS2LAB_TOKEN=<the instructor's token> ros2lab world-worker --connect tcp/127.0.0.1:7447
    ros2lab world-worker --class-secret-file class-secret --connect tcp/127.0.0.1:7447

The second form reads the class secret its class server was given (``--class-secret-file``) and
derives the instructor's token from it as the class server does (server/classroom/tokens.py), so
it needs nothing from the class server's log and still fits after the class server starts again.
"""

from __future__ import annotations

import argparse
import logging
import os
import signal
import socket
import sys
import threading
import time
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from node_runtime.console import LEVELS, setup_logging
from node_runtime.transport.config import ZenohSettings
from server.classroom.worker_control import TOKEN_ENV
from server.host.settings import (
    LOOPBACK_HOSTS,
    WORKER_MAX_WORLDS,
    WORKER_PORT,
    ClassroomSettings,
    LabSettings,
    Listening,
    Settings,
    WorkerSettings,
    choices_of,
    default_of,
    explain,
    shown,
)

log = logging.getLogger("classroom.worker")
PARENT_CHECK_S = 0.5


def build_parser() -> argparse.ArgumentParser:
    """The command line. Each option that maps onto a settings field takes its default from the
    model (``default_of``, or a worker's own: ``WORKER_PORT``, ``WORKER_MAX_WORLDS``), and a help
    that names the default shows that value."""
    parser = argparse.ArgumentParser(
        prog="ros2lab world-worker",
        description="Host worlds for a class server: join its Zenoh router and serve the worlds it places "
        f"here. The instructor's token comes from ${TOKEN_ENV} (the class server prints it), or is derived "
        "from the class secret its class server was given (--class-secret-file).",
    )
    parser.add_argument(
        "--connect",
        required=True,
        metavar="ENDPOINT",
        help="the class's Zenoh router, e.g. tcp/127.0.0.1:7447",
    )
    host = default_of(Listening, "host")
    parser.add_argument("--host", default=host, help=f"address of this worker's HTTP API (default {host})")
    port = "a free one" if WORKER_PORT == 0 else WORKER_PORT
    parser.add_argument("--port", type=int, default=WORKER_PORT, help=f"its port (default: {port})")
    parser.add_argument(
        "--advertise", metavar="HOST",
        help="the address the class server reaches this worker on (default: --host; needed with 0.0.0.0)",
    )  # fmt: skip
    parser.add_argument(
        "--class-secret-file", type=Path, metavar="FILE",
        help=f"the class secret file its class server was given (instead of ${TOKEN_ENV}): the instructor's "
             "token is derived from it, the same after the class server starts again",
    )  # fmt: skip
    parser.add_argument("--id", dest="worker_id", help="this worker's name (default: HOSTNAME-PID)")
    parser.add_argument(
        "--max-worlds",
        type=int,
        default=WORKER_MAX_WORLDS,
        help=f"worlds at most (default {WORKER_MAX_WORLDS})",
    )
    orphan_timeout = default_of(WorkerSettings, "orphan_timeout_s")
    parser.add_argument(
        "--orphan-timeout", type=float, default=orphan_timeout, metavar="S",
        help="free this worker's worlds when the class server has said no hello for S seconds "
        f"(default {shown(orphan_timeout)}; keep it below the class server's --worker-timeout)",
    )  # fmt: skip
    workspace = default_of(LabSettings, "workspace")
    parser.add_argument(
        "--workspace",
        type=Path,
        default=workspace,
        help=f"folder of students' packages (default {shown(workspace)})",
    )
    workspaces_dir = default_of(ClassroomSettings, "workspaces_dir")
    parser.add_argument(
        "--workspaces-dir", type=Path, default=workspaces_dir, metavar="DIR",
        help=f"the class's students' workspaces, a folder per world (default {shown(workspaces_dir)}): the "
             "class server's own folder (the same path on its machine, or a mount of it); a folder of its "
             "own works too: the class server then hands each world's files over and copies them back",
    )  # fmt: skip
    bag_dir = default_of(LabSettings, "bag_dir")
    parser.add_argument(
        "--bag-dir",
        type=Path,
        default=bag_dir,
        help=f"where recordings are written (default {shown(bag_dir)})",
    )
    state_dir = default_of(LabSettings, "state_dir")
    parser.add_argument(
        "--state-dir", type=Path, default=state_dir,
        help=f"where its worlds' checkpoint progress and the report key are kept (default {shown(state_dir)})",
    )  # fmt: skip
    parser.add_argument("--log-level", default=default_of(Settings, "log_level"), choices=list(LEVELS))
    loop_priority = default_of(Settings, "loop_priority")
    parser.add_argument(
        "--loop-priority", choices=choices_of(Settings, "loop_priority"), default=loop_priority,
        help="realtime: the worlds' loop thread in the kernel's real-time class, before every other thread, "
             "where the machine allows it (root, CAP_SYS_NICE or ulimit -r 1; else it stays normal); "
             f"normal: in the fair class with the rest (default {loop_priority})",
    )  # fmt: skip
    world_level = default_of(ClassroomSettings, "world_log_level")
    parser.add_argument(
        "--world-log-level", default=world_level, choices=list(LEVELS),
        help=f"the lowest level of its worlds' node log lines it prints (default {world_level}); every line "
             "still goes to its world's /rosout",
    )  # fmt: skip
    # Set by a class server that started this worker itself (--workers): end when that process is gone.
    parser.add_argument("--parent-pid", type=int, help=argparse.SUPPRESS)
    # A worker its class server started here: the machine's node-start slots, shared with it.
    parser.add_argument(
        "--start-slots", type=Path, default=default_of(WorkerSettings, "start_slots"), help=argparse.SUPPRESS
    )
    return parser


def _end_with_parent(parent_pid: int) -> None:
    """Stop this worker (as a Ctrl-C would: its worlds end) once ``parent_pid`` is no longer its
    parent, so a class server that was killed leaves no worker of its own behind."""

    def watch() -> None:
        while os.getppid() == parent_pid:
            time.sleep(PARENT_CHECK_S)
        log.warning("the class server that started this worker is gone: stopping")
        os.kill(os.getpid(), signal.SIGTERM)

    threading.Thread(target=watch, name="parent watch", daemon=True).start()


def _worker_id(asked: str | None) -> str:
    wid = asked or f"{socket.gethostname()}-{os.getpid()}"
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in wid)[:64] or f"worker-{os.getpid()}"


def _router_refuses(endpoint: str, class_token: str, source: str) -> str | None:
    """Why the class's router would not let this worker in (None: it does), before anything starts."""
    from node_runtime.transport.acl import ClassAuth
    from node_runtime.transport.session import TransportError, open_session

    settings = ZenohSettings(
        mode="client", listen=(), connect=(endpoint,), login=ClassAuth(class_token).class_credentials()
    )
    try:
        session: Any = open_session(settings)  # zenoh's stubs leave close() untyped
        session.close()
    except TransportError as exc:
        return (
            f"{exc}. Is the class server running there, and {source}? Its router lets in only the "
            "class's own workers."
        )
    return None


def _class_token(secret_file: Path | None) -> tuple[str | None, str]:
    """The instructor's token, from exactly one of $ROS2LAB_TOKEN and the class secret file, and
    where it came from (for the router's refusal); else None and why not."""
    from server.classroom.tokens import ClassSecretError, instructor_token, read_class_secret

    from_env = os.environ.get(TOKEN_ENV, "").strip()
    if secret_file is None:
        if not from_env:
            return None, (
                f"set {TOKEN_ENV} to the instructor's token (in the link the class server printed), or give "
                "--class-secret-file with the class server's class secret: a worker serves only its own class"
            )
        return from_env, f"{TOKEN_ENV} the instructor's token"
    if from_env:
        return None, (
            f"both {TOKEN_ENV} and --class-secret-file are given: use one (the class secret file, "
            f"when the class server has one; unset {TOKEN_ENV})"
        )
    try:
        secret = read_class_secret(secret_file)
    except ClassSecretError as exc:
        return None, str(exc)
    return instructor_token(secret), f"the class secret file {secret_file} the class server's own"


def worker_settings(args: argparse.Namespace, class_token: str, port: int) -> Settings:
    """The command line (and the port this worker listens on), mapped onto the settings model.
    ValidationError says what is wrong, each field by its path (``listen.port``)."""
    advertise = args.advertise or args.host
    shown = f"[{advertise}]" if ":" in advertise else advertise
    worker = {
        "id": _worker_id(args.worker_id), "url": f"http://{shown}:{port}", "class_token": class_token,
        "orphan_timeout_s": args.orphan_timeout, "start_slots": args.start_slots,
    }  # fmt: skip
    listen = {
        "host": args.host,
        "port": port,
        "allowed_hosts": () if args.host in LOOPBACK_HOSTS else (advertise,),
    }
    lab = {
        "workspace": args.workspace, "bag_dir": args.bag_dir, "state_dir": args.state_dir,
        "zenoh": ZenohSettings(mode="client", listen=(), connect=(args.connect,)),
    }  # fmt: skip
    classroom = {"max_worlds": args.max_worlds, "world_log_level": args.world_log_level,
                 "workspaces_dir": args.workspaces_dir}  # fmt: skip
    return Settings.model_validate(
        {
            "listen": listen, "lab": lab, "classroom": classroom, "worker": worker, "log_level": args.log_level,
            "loop_priority": args.loop_priority,
        }
    )  # fmt: skip


def listening_socket(host: str, port: int) -> socket.socket:
    """The worker's API socket, bound before the app starts (to say where it listens). Made as a
    TCP socket by name (``IPPROTO_TCP``), as asyncio's own servers make theirs: asyncio turns
    Nagle's algorithm off only on connections of such a socket, and with it on, the end of every
    answer to a call the class server passed on over a kept-alive connection waited about 40 ms
    for the class server's delayed acknowledgement."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((host, port))
    except OSError:
        sock.close()
        raise
    return sock


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    class_token, source = _class_token(args.class_secret_file)
    if class_token is None:
        print(f"error: {source}", file=sys.stderr)
        return 2
    try:
        worker_settings(args, class_token, args.port)  # every rule, before anything is bound
    except ValidationError as exc:
        parser.error(explain(exc))
    except ValueError as exc:  # a Zenoh endpoint the session cannot take
        parser.error(str(exc))
    if args.parent_pid is not None and os.getppid() != args.parent_pid:
        print("error: the class server that started this worker is gone", file=sys.stderr)
        return 2
    try:
        sock = listening_socket(args.host, args.port)
    except OSError as exc:
        print(f"error: cannot listen on {args.host}:{args.port}: {exc.strerror}", file=sys.stderr)
        return 2
    refused = _router_refuses(args.connect, class_token, source)
    if refused:
        sock.close()
        print(f"error: {refused}", file=sys.stderr)
        return 2
    settings = worker_settings(args, class_token, int(sock.getsockname()[1]))
    worker = settings.worker
    assert worker is not None and settings.classroom is not None
    setup_logging(
        settings.log_level, classroom=True, world_level=settings.classroom.world_log_level, who=worker.id
    )
    from server.serve import serve

    def announce(_app: Any) -> None:
        print(f"World worker {worker.id}: API at {worker.url}, class router {args.connect}, "
              f"up to {args.max_worlds} worlds (Ctrl-C stops it and its worlds)", flush=True)  # fmt: skip
        if args.parent_pid is not None:
            _end_with_parent(args.parent_pid)

    serve(settings, sock=sock, announce=announce)
    return 0
