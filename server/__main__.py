"""``python -m server``: start the lab's app (``--host``, ``--port``, ``--launch``); ``python -m server
topic list`` and the other ros2 verbs run the command-line tools against a running one (server.cli)."""

from __future__ import annotations

import argparse
import secrets
import sys
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from node_runtime.console import LEVELS, setup_logging
from node_runtime.transport.config import DEFAULT_ROUTER_ENDPOINT, ZenohSettings, domain_id_from_env
from server import cli
from server.banner import classroom_banner, print_lab_lines, student_code_line
from server.host.settings import (
    FOXGLOVE_PORT,
    ClassroomSettings,
    JoinLimits,
    LabSettings,
    Listening,
    SandboxSettings,
    Settings,
    choices_of,
    default_of,
    explain,
    is_loopback_host,
    is_refusal,
    shown,
)


def parse_launch_arg(text: str) -> tuple[str, str]:
    name, sep, value = text.partition(":=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"launch arguments are NAME:=VALUE, got {text!r}")
    return name, value


def build_parser() -> argparse.ArgumentParser:
    """The command line. Each option that maps onto a settings field takes its default from the
    model (``default_of``), and a help that names the default shows that value."""
    parser = argparse.ArgumentParser(
        prog="python -m server",
        description="Run the teleop lab app.",
        epilog=f"With a first argument of {', '.join(cli.VERBS)}: ros2's command-line tools against a "
        "running app (python -m server topic --help; also installed as ros2lab).",
    )
    host = default_of(Listening, "host")
    parser.add_argument(
        "--host",
        default=host,
        help=f"address to bind (default {host}{': this machine only' if is_loopback_host(host) else ''})",
    )
    port = default_of(Listening, "port")
    parser.add_argument("--port", type=int, default=port, help=f"port (default {port})")
    launch = default_of(LabSettings, "launch")
    parser.add_argument(
        "--launch", default=launch, help=f"rocket, fly, all or a launch file's path (default {launch})"
    )
    parser.add_argument(
        "launch_args",
        nargs="*",
        type=parse_launch_arg,
        metavar="NAME:=VALUE",
        help="launch arguments, as ros2 launch takes them (e.g. start_delay:=2.0)",
    )
    workspace = default_of(LabSettings, "workspace")
    parser.add_argument(
        "--workspace",
        type=Path,
        default=workspace,
        help=f"folder of your own packages (src/<pkg>/...), default {shown(workspace)}",
    )
    parser.add_argument(
        "--allow-host",
        action="append",
        default=list(default_of(Listening, "allowed_hosts")),
        help="another Host name to accept",
    )
    parser.add_argument(
        "--allow-origin",
        action="append",
        default=list(default_of(Listening, "allowed_origins")),
        help="another page origin to accept",
    )
    parser.add_argument("--log-level", default=default_of(Settings, "log_level"), choices=list(LEVELS))
    loop_priority = default_of(Settings, "loop_priority")
    parser.add_argument(
        "--loop-priority", choices=choices_of(Settings, "loop_priority"), default=loop_priority,
        help="realtime: the worlds' loop thread in the kernel's real-time class, before every other thread, "
             "where the machine allows it (root, CAP_SYS_NICE or ulimit -r 1; else it stays normal); "
             f"normal: in the fair class with the rest (default {loop_priority})",
    )  # fmt: skip
    zenoh = parser.add_argument_group(
        "the graph on Zenoh (rmw_zenoh's wire format; ROS_DOMAIN_ID is read from the environment)"
    )
    zenoh.add_argument(
        "--zenoh-listen", action="append", default=[], metavar="ENDPOINT",
        help=f"where the app's Zenoh router listens (repeatable; default {DEFAULT_ROUTER_ENDPOINT}: this "
             "machine only). An address beyond loopback lets other machines join the graph.",
    )  # fmt: skip
    zenoh.add_argument(
        "--zenoh-connect",
        action="append",
        default=[],
        metavar="ENDPOINT",
        help="join an existing Zenoh router (e.g. rmw_zenohd's, or another lab's) instead of being one",
    )
    zenoh.add_argument(
        "--zenoh-config", type=Path, metavar="FILE", help="a Zenoh JSON5 config (TLS, user/password)"
    )
    zenoh.add_argument("--no-zenoh", action="store_true", help="keep every node in this process (no Zenoh)")
    node_processes = default_of(LabSettings, "node_processes")
    parser.add_argument(
        "--node-processes", choices=choices_of(LabSettings, "node_processes"), default=node_processes,
        help="which nodes run as their own processes: student, your own files; or all, every node but the "
             f"two that drive the page (keyboard, view), so the lesson shows in ps (default {node_processes})",
    )  # fmt: skip
    # -- tools robotics people use --
    parser.add_argument(
        "--foxglove-port",
        type=int,
        default=FOXGLOVE_PORT,
        help=f"Foxglove WebSocket server's port on --host (default {FOXGLOVE_PORT})",
    )
    parser.add_argument(
        "--no-foxglove", action="store_true", help="do not start the Foxglove WebSocket server"
    )
    parser.add_argument(
        "--rosbridge-port", type=int, default=default_of(LabSettings, "rosbridge_port"),
        help="serve rosbridge on this port too, as rosbridge_server does on 9090 (always at /rosbridge)",
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
        "--state-dir",
        type=Path,
        default=state_dir,
        help="what the server keeps across restarts: its report-signing key and each world's checkpoint "
        f"progress (default {shown(state_dir)})",
    )
    # -- a class on one server --
    classroom = parser.add_argument_group("a class on one server")
    classroom.add_argument(
        "--classroom", action="store_true",
        help="a world per student (their own rocket, drone, graph and 3D view) behind signed tokens; "
             "prints the class code and the instructor's link once. Add --host for a LAN.",
    )  # fmt: skip
    classroom.add_argument(
        "--class-code",
        default=default_of(ClassroomSettings, "code"),
        help="the code students type to join (default: a new random one)",
    )
    max_worlds = default_of(ClassroomSettings, "max_worlds")
    classroom.add_argument(
        "--max-worlds", type=int, default=max_worlds, help=f"worlds at most (default {max_worlds})"
    )
    classroom.add_argument(
        "--max-worlds-per-address", type=int, metavar="N",
        default=default_of(JoinLimits, "max_worlds_per_address"),
        help="worlds at most joined from one client address (default: any; a class behind one NAT "
             "address shares one)",
    )  # fmt: skip
    classroom.add_argument(
        "--local-worlds", type=int, metavar="N", default=default_of(ClassroomSettings, "local_worlds"),
        help="worlds this server hosts itself (default: all); the rest go to world workers "
             f"(ros2lab {cli.WORKER_VERB} --connect tcp/HOST:7447, which join this server's Zenoh router)",
    )  # fmt: skip
    workers = default_of(ClassroomSettings, "local_workers")
    classroom.add_argument(
        "--workers", type=workers_arg, default=workers, metavar="N|auto",
        help="world workers on this machine (processes of their own on this server's router, so a class "
             "uses more cores; they stop with it): N at the start, or auto: one each --spread-at worlds as "
             f"the class grows, at most one per spare core; 0: none (default {workers})",
    )  # fmt: skip
    spread_at = default_of(ClassroomSettings, "spread_at")
    classroom.add_argument(
        "--spread-at", type=int, default=spread_at, metavar="N",
        help=f"with --workers auto: another world worker each N worlds (default {spread_at})",
    )  # fmt: skip
    per_core = default_of(ClassroomSettings, "worlds_per_core")
    classroom.add_argument(
        "--worlds-per-core", type=int, default=per_core, metavar="N",
        help="a machine's world budget: N worlds for each of its cores, over the class server and the world "
             "workers on it; a class whose machines all have theirs queues the next join as full (default "
             f"{per_core}, about what a core runs with two nodes a student; 0: no budget)",
    )  # fmt: skip
    world_level = default_of(ClassroomSettings, "world_log_level")
    classroom.add_argument(
        "--world-log-level", default=world_level, choices=list(LEVELS),
        help=f"the lowest level of the worlds' node log lines this console shows (default {world_level}: a "
             "class of 30 rockets at info is 300 lines a second); every line still goes to its world's /rosout",
    )  # fmt: skip
    workspaces_dir = default_of(ClassroomSettings, "workspaces_dir")
    classroom.add_argument(
        "--workspaces-dir", type=Path, default=workspaces_dir, metavar="DIR",
        help=f"the students' workspaces, a folder per world (default {shown(workspaces_dir)}); world workers "
             "on other machines need it mounted as their --workspaces-dir for the code view",
    )  # fmt: skip
    classroom.add_argument(
        "--class-secret-file", type=Path, metavar="FILE", default=default_of(ClassroomSettings, "class_secret_file"),
        help="the class secret, shared with the class's world workers (their --class-secret-file): tokens, the "
             "instructor's too, stay the same when this server starts again, and workers need no token from its "
             "log (default: a new random secret at each start). Make it once: openssl rand -hex 32 > FILE",
    )  # fmt: skip
    worker_timeout = default_of(ClassroomSettings, "worker_timeout_s")
    classroom.add_argument(
        "--worker-timeout", type=float, default=worker_timeout, metavar="S",
        help="a world worker that answers no hello for S seconds is gone: its worlds start again here "
             f"or on another worker, under the same names and tokens (default {shown(worker_timeout)})",
    )  # fmt: skip
    student_code = default_of(SandboxSettings, "student_code")
    classroom.add_argument(
        "--student-code", choices=choices_of(SandboxSettings, "student_code"), default=student_code,
        help="how students' node processes run when this server serves others (--classroom, or --token "
             "beyond loopback): sandboxed, in a bubblewrap sandbox (refused if none can be built), or, at "
             f"your own risk, unsandboxed, as your user with everything it can reach (default {student_code})",
    )  # fmt: skip
    classroom.add_argument(
        "--token", metavar="TOKEN|auto", default=default_of(Listening, "token"),
        help="one lab behind a token: every page, call and bridge port needs it (auto: a new random one, "
             "printed once in the page's link). Needed to listen beyond loopback without --classroom.",
    )  # fmt: skip
    return parser


def zenoh_settings(args: argparse.Namespace) -> ZenohSettings | None:
    """The session the flags ask for; the HTTP --host never widens where Zenoh listens."""
    if args.no_zenoh:
        return None
    domain_id = domain_id_from_env()
    if args.zenoh_connect:
        return ZenohSettings(
            mode="peer", listen=tuple(args.zenoh_listen) or ("tcp/127.0.0.1:0",),
            connect=tuple(args.zenoh_connect), domain_id=domain_id, config_file=args.zenoh_config,
        )  # fmt: skip
    return ZenohSettings(
        mode="router", listen=tuple(args.zenoh_listen) or (DEFAULT_ROUTER_ENDPOINT,), domain_id=domain_id,
        config_file=args.zenoh_config,
    )  # fmt: skip


def check_launch(settings: Settings) -> str | None:
    """Parse the launch file before anything starts, so a mistake is one clear line."""
    from node_runtime.ament.index import PackageIndex
    from server.services.launch.aliases import resolve_launch
    from server.services.launch.description import LaunchFileError
    from server.services.launch.launcher import parse_launch
    from server.services.launch.python_process import OUTSIDE_SANDBOX, sandbox_sees

    lab = settings.lab
    packages = PackageIndex(workspace=lab.workspace)
    path = resolve_launch(lab.launch, packages)
    if settings.sandboxes_students and path.suffix == ".py" and not sandbox_sees(path, None):
        return f"{path}:0: {OUTSIDE_SANDBOX}"  # a world's launch: its own workspace is not known yet
    try:
        parse_launch(path, lab.launch_args, packages)
    except LaunchFileError as exc:
        return str(exc)
    return None


def workers_arg(arg: str) -> int | str:
    """``--workers``: ``auto`` or a count (its range is the settings' rule)."""
    if arg == "auto":
        return arg
    try:
        return int(arg)
    except ValueError:
        raise argparse.ArgumentTypeError(f"N or auto, not {arg!r}") from None


def lab_token(arg: str | None) -> str | None:
    if arg is None:
        return None
    return secrets.token_urlsafe(24) if arg == "auto" else arg


# Options of the class's section: without --classroom there is no class for them to shape.
CLASS_ONLY = {"workers": "--workers", "spread_at": "--spread-at", "local_worlds": "--local-worlds",
              "worlds_per_core": "--worlds-per-core",
              "max_worlds_per_address": "--max-worlds-per-address", "workspaces_dir": "--workspaces-dir",
              "class_secret_file": "--class-secret-file"}  # fmt: skip


def settings_of(args: argparse.Namespace, zenoh: ZenohSettings | None) -> Settings:
    """The command line, mapped onto the settings model (which checks every rule across options).
    ValidationError says what is wrong, each field by its path (``listen.port``)."""
    classroom = None
    if args.classroom:
        classroom = {
            "code": args.class_code, "max_worlds": args.max_worlds, "local_worlds": args.local_worlds,
            "local_workers": args.workers, "spread_at": args.spread_at, "worker_timeout_s": args.worker_timeout,
            "worlds_per_core": args.worlds_per_core,
            "world_log_level": args.world_log_level, "workspaces_dir": args.workspaces_dir,
            "class_secret_file": args.class_secret_file,
            "joins": {"max_worlds_per_address": args.max_worlds_per_address},
        }  # fmt: skip
    listen = {
        "host": args.host, "port": args.port, "token": lab_token(args.token),
        "allowed_hosts": args.allow_host, "allowed_origins": args.allow_origin,
    }  # fmt: skip
    lab = {
        "launch": args.launch, "launch_args": dict(args.launch_args), "workspace": args.workspace,
        "zenoh": zenoh, "node_processes": args.node_processes, "bag_dir": args.bag_dir,
        "state_dir": args.state_dir,
        "foxglove_port": None if args.no_foxglove else args.foxglove_port, "rosbridge_port": args.rosbridge_port,
    }  # fmt: skip
    return Settings.model_validate({
        "listen": listen, "lab": lab, "classroom": classroom, "log_level": args.log_level,
        "loop_priority": args.loop_priority, "sandbox": {"student_code": args.student_code},
    })  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv and (argv[0] in (*cli.VERBS, cli.WORKER_VERB, cli.COLCON_VERB) or argv[0].startswith("--url")):
        return cli.main(argv)  # ros2's verbs, against a running server
    parser = build_parser()
    args = parser.parse_args(argv)
    if not args.classroom:
        for name, flag in CLASS_ONLY.items():
            if getattr(args, name) != parser.get_default(name):
                parser.error(f"{flag} needs --classroom")
    try:
        settings = settings_of(args, zenoh_settings(args))
    except ValidationError as exc:
        if is_refusal(exc):
            print(f"error: {explain(exc)}", file=sys.stderr)
            return 2
        parser.error(explain(exc))
    except ValueError as exc:  # a Zenoh endpoint or ROS_DOMAIN_ID the session cannot take
        parser.error(str(exc))
    classroom = settings.classroom
    if classroom is not None and classroom.class_secret_file is not None:
        from server.classroom.tokens import ClassSecretError, read_class_secret

        try:
            read_class_secret(classroom.class_secret_file)  # read again by the class server
        except ClassSecretError as exc:
            print(f"error: {exc}", file=sys.stderr)
            return 2
    world_level = classroom.world_log_level if classroom is not None else args.world_log_level
    setup_logging(settings.log_level, classroom=classroom is not None, world_level=world_level)
    error = check_launch(settings)
    if error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    print_lab_lines(settings)
    line = student_code_line(settings)
    if line is not None:
        print(line, file=sys.stderr if line.startswith(("warning", "error")) else sys.stdout, flush=True)
    from server.serve import serve

    def announce(app: Any) -> None:
        if app.state.classroom is not None:
            klass = app.state.classroom
            print(classroom_banner(settings, klass.code, klass.instructor_token), flush=True)

    serve(settings, announce=announce)
    return 0


if __name__ == "__main__":
    sys.exit(main())
