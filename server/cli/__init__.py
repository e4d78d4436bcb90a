"""``ros2lab``: ros2's command-line verbs against a running lab server (``topic``, ``node``, ``service``,
``param``, ``launch``, ``run``, ``pkg``, ``interface``, ``bag``, and the lab's own ``env``), with ros2's options and output, over the server's HTTP/WebSocket API.

It imports nothing of the server: everything goes over the wire, so it works against any lab
server it can reach (``--url``, or ``TELEOP_URL``).
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys
from types import FrameType

from server.cli.environment import DEFAULT_URL, TOKEN_ENV, URL_ENV
from server.cli.priority import start_below_the_worlds

VERBS = (
    "topic",
    "node",
    "service",
    "param",
    "action",
    "launch",
    "run",
    "pkg",
    "interface",
    "bag",
    "env",
    "report",
)
COLCON_VERB = "colcon"  # not a verb: a student used to ROS types it, and is told it is not needed
COLCON_HINT = (
    "colcon build and `source install/setup.bash` are not needed here: `ros2lab run PKG EXEC` runs a "
    "workspace's packages from their source folders, and edits take effect at the next start"
)
WORKER_VERB = "world-worker"  # ros2lab world-worker: host a class server's worlds (server/world_worker.py)

__all__ = ["VERBS", "build_parser", "main"]


# The module that adds each verb's parser (``launch`` adds ``launch``'s verbs).
VERB_MODULES = {
    "topic": "topic",
    "node": "node",
    "service": "service",
    "param": "param",
    "action": "action",
    "launch": "launch",
    "run": "run",
    "pkg": "pkg",
    "interface": "interface",
    "bag": "bag",
    "env": "env",
    "report": "report",
}


def verb_of(argv: list[str]) -> str | None:
    """The verb ``argv`` names (after ``--url URL``, if given), or None (``--help``, nothing)."""
    args = iter(argv)
    for arg in args:
        if arg == "--url":
            next(args, None)
        elif not arg.startswith("--url="):
            return None if arg.startswith("-") else arg
    return None


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The whole command line, or with ``only`` (a verb) that verb's alone: a command then imports
    none of the other verbs' modules (bag's MCAP, the interfaces, package creation), a third of a
    CPU second at every start, and at a class's "run it now" twenty ``ros2lab run`` at once would
    import them beside the worlds. ``ros2lab --help`` and an unknown verb get every verb."""
    parser = argparse.ArgumentParser(
        prog="ros2lab",
        description="ros2's command-line tools for the teleop lab's running server.",
        epilog=f"ros2lab {WORKER_VERB} --connect tcp/HOST:7447 hosts worlds for a class server "
        f"(ros2lab {WORKER_VERB} --help).",
    )
    url_help = f"the lab server (default: ${URL_ENV}, else {DEFAULT_URL})"
    parser.add_argument("--url", default=None, help=url_help)
    # --url is accepted after the verb too; SUPPRESS keeps it from overwriting one given before.
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--url", default=argparse.SUPPRESS, help=url_help)
    verbs = parser.add_subparsers(dest="verb", required=True, metavar="VERB")
    chosen = [only] if only in VERB_MODULES else list(VERB_MODULES)
    for verb in chosen:
        module = importlib.import_module(f"{__name__}.{VERB_MODULES[verb]}")
        (module.add_parsers if verb == "launch" else module.add_parser)(verbs, common)
    return parser


def _interrupt(_signum: int, _frame: FrameType | None) -> None:
    raise KeyboardInterrupt


def main(argv: list[str] | None = None) -> int:
    """Run one command; 0 on success or Ctrl-C, 1 when it failed, 2 on bad usage or no server."""
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == WORKER_VERB:  # not a client verb: this process hosts worlds itself
        from server.cli.world_worker import main as worker_main

        return worker_main(argv[1:])
    if argv and argv[0] == COLCON_VERB:
        print(COLCON_HINT)
        return 0
    verb = verb_of(argv)
    if verb == "run" and os.environ.get(TOKEN_ENV):
        start_below_the_worlds()  # before its imports: see server/cli/priority.py
    args = build_parser(verb).parse_args(argv)
    url = args.url or os.environ.get(URL_ENV) or DEFAULT_URL
    from server.cli.client import CliError, LabClient  # its HTTP client, once the command has its priority

    # SIGTERM cleans up as Ctrl-C does: a launch's nodes and a periodic publisher are stopped.
    signal.signal(signal.SIGTERM, _interrupt)
    try:
        with LabClient(url) as client:
            return int(args.handler(args, client))
    except KeyboardInterrupt:
        return 0
    except CliError as exc:
        sys.stdout.flush()
        print(f"error: {exc}", file=sys.stderr)
        return exc.exit_code
    except BrokenPipeError:  # the output went to `head` or the like, which has seen enough
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
