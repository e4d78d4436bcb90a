"""``topic list | info | echo | hz`` (``pub`` is in publish.py), with ros2's options and output."""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from typing import Any

from server.cli import publish
from server.cli.client import ApiError, LabClient, UnknownTopicError
from server.cli.format import DEFAULT_TRUNCATE_LENGTH, echo_text, hz_report, parse_field

Sleep = Callable[[float], None]
HZ_REPORT_PERIOD_S = 1.0


def absolute(topic: str) -> str:
    """ros2 expands a relative name in the root namespace: ``countdown`` → ``/countdown``."""
    return topic if topic.startswith("/") else "/" + topic


def not_published_warning(topic: str) -> str:
    return f"WARNING: topic [{topic}] does not appear to be published yet"


def topic_list(args: argparse.Namespace, client: LabClient) -> int:
    params = {"hidden": "true"} if args.include_hidden_topics else {}
    for topic in client.get("/api/topics", params):
        print(f"{topic['name']} [{topic['type']}]" if args.show_types else topic["name"])
    return 0


def _endpoints(kind: str, names: list[str], depths: list[int], type_name: str) -> list[str]:
    lines = [f"{kind.title()} count: {len(names)}", ""]
    for name, depth in zip(names, depths, strict=True):
        namespace, _, node = name.rpartition("/")
        lines += [
            f"Node name: {node}",
            f"Node namespace: {namespace or '/'}",
            f"Topic type: {type_name}",
            f"Endpoint type: {kind.upper()}",
            "QoS profile:",
            f"  History (Depth): KEEP_LAST ({depth})",
            "",
        ]
    return lines


def topic_info(args: argparse.Namespace, client: LabClient) -> int:
    name = absolute(args.topic_name)
    try:
        info = client.get("/api/topics/" + name.lstrip("/"))
    except ApiError as exc:
        if exc.status == 404 and not exc.no_route:
            print(f"Unknown topic '{name}'", file=sys.stderr)
            return 1
        raise
    if not args.verbose:
        print(
            f"Type: {info['type']}\nPublisher count: {len(info['publishers'])}\n"
            f"Subscription count: {len(info['subscribers'])}"
        )
        return 0
    lines = [f"Type: {info['type']}", ""]
    lines += _endpoints("publisher", info["publishers"], info.get("publisher_depths", []), info["type"])
    lines += _endpoints("subscription", info["subscribers"], info.get("subscriber_depths", []), info["type"])
    print("\n".join(lines).rstrip("\n"))
    return 0


def topic_echo(args: argparse.Namespace, client: LabClient) -> int:
    name = absolute(args.topic_name)
    field = parse_field(args.field)
    truncate = None if args.full_length else args.truncate_length
    params: dict[str, Any] = {}
    if args.qos_depth is not None:
        params["queue_length"] = args.qos_depth
    message_type = args.type or args.message_type
    if message_type:
        params["type"] = message_type
    try:
        for frame in client.subscribe(name, params):
            sys.stdout.write(echo_text(frame["msg"], field, truncate_length=truncate, no_arr=args.no_arr))
            sys.stdout.flush()
            if args.once:
                return 0
    except UnknownTopicError:
        print(not_published_warning(name), file=sys.stderr)
        print("(give its type, e.g. --type std_msgs/msg/String, to wait for it)", file=sys.stderr)
        return 1
    return 0


def topic_hz(args: argparse.Namespace, client: LabClient, sleep: Sleep = time.sleep) -> int:
    name = absolute(args.topic_name)
    params = {"window": args.window} if args.window is not None else {}
    reports, warned = 0, False
    while args.count is None or reports < args.count:
        sleep(HZ_REPORT_PERIOD_S)
        try:
            stats = client.get("/api/hz/" + name.lstrip("/"), params)
        except ApiError as exc:
            if exc.status != 404 or exc.no_route:
                raise
            if not warned:  # ros2 waits for the topic to appear, and says so once
                print(not_published_warning(name), file=sys.stderr, flush=True)
                warned = True
            continue
        if stats.get("rate_hz") is None:
            continue  # fewer than two messages so far: ros2 prints nothing either
        print(hz_report(stats), flush=True)
        reports += 1
    return 0


def _non_negative(text: str) -> int:
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError("value must be a non-negative integer")
    return value


def _positive(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("value must be a positive integer")
    return value


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("topic", help="Various topic related sub-commands")
    sub = parser.add_subparsers(dest="topic_verb", required=True, metavar="VERB")

    p = sub.add_parser("list", parents=[common], help="Output a list of available topics")
    p.add_argument("-t", "--show-types", action="store_true", help="Additionally show the topic type")
    p.add_argument("--include-hidden-topics", action="store_true", help="Consider hidden topics as well")
    p.set_defaults(handler=topic_list)

    p = sub.add_parser("info", parents=[common], help="Print information about a topic")
    p.add_argument("topic_name", help="Name of the ROS topic to get info (e.g. '/chatter')")
    p.add_argument(
        "-v", "--verbose", action="store_true", help="Prints detailed information like the node name"
    )
    p.set_defaults(handler=topic_info)

    p = sub.add_parser("echo", parents=[common], help="Output messages from a topic")
    p.add_argument("topic_name", help="Name of the ROS topic to listen to (e.g. '/chatter')")
    p.add_argument("message_type", nargs="?", help="Type of the ROS message (e.g. 'std_msgs/msg/String')")
    p.add_argument("--type", help="the message type, to wait for a topic nobody publishes yet")
    p.add_argument("--once", action="store_true", help="Print the first message received and then exit")
    p.add_argument("--field", help="Echo a selected field of a message (e.g. 'pose.position')")
    p.add_argument("--no-arr", action="store_true", help="Don't print array fields of messages")
    p.add_argument("--qos-depth", type=_positive, help="Queue size: messages kept for a slow terminal")
    p.add_argument(
        "-l",
        "--truncate-length",
        type=_non_negative,
        default=DEFAULT_TRUNCATE_LENGTH,
        help=f"Length to truncate arrays and strings to (default: {DEFAULT_TRUNCATE_LENGTH})",
    )
    p.add_argument(
        "-f", "--full-length", action="store_true", help="Output all elements of arrays and strings"
    )
    p.set_defaults(handler=topic_echo)

    p = sub.add_parser("hz", parents=[common], help="Print the average publishing rate to screen")
    p.add_argument("topic_name", help="Name of the ROS topic to listen to (e.g. '/chatter')")
    p.add_argument(
        "-w", "--window", type=_positive, help="window size, in # of messages, for calculating rate"
    )
    p.add_argument("--count", type=_positive, help="exit after this many reports")
    p.set_defaults(handler=topic_hz)

    publish.add_parser(sub, common)
