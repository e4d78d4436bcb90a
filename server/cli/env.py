"""``ros2lab env``: the environment that joins this lab's ROS graph, as shell exports.

``eval "$(ros2lab env)"`` in a shell with ROS 2 and rmw_zenoh makes ``ros2 topic list``, ``ros2 run``
and the rest join the lab's graph: its router, its ROS domain and, on a class server, the login
(a student's token gives their world; the instructor's, the class's own domain, where every world
shows under its name). The same answer ``ros2lab run`` uses (``GET /api/zenoh/join``), asked
with the same bounded wait (server/cli/join.py).
"""

from __future__ import annotations

import argparse
import shlex
from typing import Any

from server.cli.client import LabClient
from server.cli.join import join_graph

RMW = "rmw_zenoh_cpp"


def env(args: argparse.Namespace, client: LabClient) -> int:
    join = join_graph(client)
    exports = {"RMW_IMPLEMENTATION": RMW, **join["env"]}
    for name, value in exports.items():
        print(f"export {name}={shlex.quote(str(value))}")
    return 0


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    p = verbs.add_parser(
        "env",
        parents=[common],
        help='Print the shell exports that join the lab\'s ROS graph (eval "$(ros2lab env)")',
    )
    p.set_defaults(handler=env)
