"""``node list | info``, laid out as ros2 prints them, plus the lab's timers and crash state."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Mapping
from typing import Any

from server.cli.client import ApiError, LabClient


def node_list(args: argparse.Namespace, client: LabClient) -> int:
    params = {"hidden": "true"} if args.all else {}
    for node in client.get("/api/nodes", params):
        print(node["name"] + (" (crashed)" if node.get("state") == "crashed" else ""))
    return 0


def _endpoint_lines(title: str, endpoints: list[Mapping[str, Any]]) -> list[str]:
    """``  Subscribers:`` then ``    /topic: type``, sorted and without repeats, as ros2 lists them."""
    pairs = sorted({(e["topic"], e["type"]) for e in endpoints})
    return [f"  {title}:"] + [f"    {topic}: {type_name}" for topic, type_name in pairs]


def _ms(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f} ms"


def _timer_line(timer: Mapping[str, Any]) -> str:
    return (
        f"    every {timer['period_s']:.3f} s: {timer['calls']} calls, lateness "
        f"p50 {_ms(timer.get('lateness_p50_ms'))}, p99 {_ms(timer.get('lateness_p99_ms'))}"
    )


def format_node_info(info: Mapping[str, Any]) -> str:
    """ros2's layout (name, Subscribers, Publishers), then Timers and, if it crashed, its state."""
    lines = [info["name"]]
    lines += _endpoint_lines("Subscribers", info.get("subscribers", []))
    lines += _endpoint_lines("Publishers", info.get("publishers", []))
    lines += ["  Timers:"] + [_timer_line(t) for t in info.get("timers", [])]
    if info.get("state") == "crashed":
        lines.append(f"  State: crashed ({info.get('crash_reason') or 'no reason given'})")
    return "\n".join(lines)


def node_info(args: argparse.Namespace, client: LabClient) -> int:
    name = args.node_name if args.node_name.startswith("/") else "/" + args.node_name
    try:
        info = client.get("/api/nodes/" + name.lstrip("/"))
    except ApiError as exc:
        if exc.status == 404 and not exc.no_route:
            print(f"Unable to find node '{name}'", file=sys.stderr)
            return 1
        raise
    print(format_node_info(info))
    return 0


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("node", help="Various node related sub-commands")
    sub = parser.add_subparsers(dest="node_verb", required=True, metavar="VERB")

    p = sub.add_parser("list", parents=[common], help="Output a list of available nodes")
    p.add_argument("-a", "--all", action="store_true", help="Display all nodes even hidden ones")
    p.set_defaults(handler=node_list)

    p = sub.add_parser("info", parents=[common], help="Output information about a node")
    p.add_argument("node_name", help="Fully qualified node name to request information with (e.g. /talker)")
    p.set_defaults(handler=node_info)
