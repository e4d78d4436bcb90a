"""``topic pub``: once (``-1``), a fixed number of times (``-t``), or at a rate until Ctrl-C.

Until Ctrl-C, the server's periodic publisher does the work (it shows in ``GET /api/publishers``
like rqt's Message Publisher) and the CLI reports its count. ``-t`` paces one-shot publishes
from here instead: a server-side publisher has no count limit, so stopping it after a poll could
send one message too many, and ros2 sends exactly TIMES.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

from server.cli.client import ApiError, LabClient
from server.cli.message import filled_message, message_repr, parse_message

Sleep = Callable[[float], None]
Clock = Callable[[], float]
POLL_PERIOD_S = 1.0
DEFAULT_RATE_HZ = 1.0  # as ros2 topic pub


def _print_publishing(number: int, type_name: str, msg: dict[str, Any]) -> None:
    print(f"publishing #{number}: {message_repr(type_name, msg)}\n", flush=True)


def _body(args: argparse.Namespace) -> dict[str, Any]:
    topic = args.topic_name if args.topic_name.startswith("/") else "/" + args.topic_name
    return {"topic": topic, "msg": parse_message(args.values), "type": args.message_type}


def publish_times(
    client: LabClient,
    body: dict[str, Any],
    times: int,
    rate_hz: float,
    sleep: Sleep = time.sleep,
    clock: Clock = time.monotonic,
) -> int:
    """Publish ``times`` messages, the first at once and then every 1/rate_hz s."""
    start = clock()
    for number in range(1, times + 1):
        if number > 1:
            sleep(max(0.0, start + (number - 1) / rate_hz - clock()))
        result = client.post("/api/publish", body)
        if number == 1:
            print("publisher: beginning loop", flush=True)
            shown = _as_published(client, result["type"], body["msg"])
        _print_publishing(number, result["type"], shown)
    return 0


def _as_published(client: LabClient, type_name: str, msg: dict[str, Any]) -> dict[str, Any]:
    """The message with the type's defaults filled in, as ros2 prints it; as given if the server
    cannot say (an older one without ``/api/types/{type}/default``)."""
    try:
        return filled_message(client.get(f"/api/types/{type_name}/default"), msg)
    except ApiError:
        return msg


def publish_until_interrupted(
    client: LabClient, body: dict[str, Any], rate_hz: float, sleep: Sleep = time.sleep
) -> int:
    """Start a periodic publisher on the server, report its count every second, stop it on Ctrl-C."""
    info = client.post("/api/publishers", {**body, "rate_hz": rate_hz})
    path = f"/api/publishers/{info['id']}"
    shown = 0
    try:
        print("publisher: beginning loop", flush=True)
        while True:
            for number in range(shown + 1, info["count"] + 1):
                _print_publishing(number, info["type"], info["msg"])
            shown = max(shown, info["count"])
            sleep(POLL_PERIOD_S)
            info = client.get(path)
    except KeyboardInterrupt:
        pass
    try:
        client.delete(path)
    except ApiError as exc:
        if exc.status != 404:  # 404: someone else stopped it already
            raise
    return 0


def topic_pub(args: argparse.Namespace, client: LabClient) -> int:
    body = _body(args)
    if args.once:
        return publish_times(client, body, 1, args.rate)
    if args.times is not None:
        return publish_times(client, body, args.times, args.rate)
    return publish_until_interrupted(client, body, args.rate)


def _positive_rate(text: str) -> float:
    value = float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError("rate must be more than 0 Hz")
    return value


def _positive_int(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("times must be a positive integer")
    return value


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    p = sub.add_parser("pub", parents=[common], help="Publish a message to a topic")
    p.add_argument("topic_name", help="Name of the ROS topic to publish to (e.g. '/chatter')")
    p.add_argument("message_type", help="Type of the ROS message (e.g. 'std_msgs/String')")
    p.add_argument(
        "values",
        nargs="?",
        default="{}",
        help="Values to fill the message with in YAML format (e.g. 'data: Hello World'), "
        "otherwise the message will be published with default values",
    )
    p.add_argument(
        "-r",
        "--rate",
        type=_positive_rate,
        default=DEFAULT_RATE_HZ,
        help="Publishing rate in Hz (default: 1)",
    )
    p.add_argument("-1", "--once", action="store_true", help="Publish one message and exit")
    p.add_argument("-t", "--times", type=_positive_int, help="Publish this number of times and then exit")
    p.set_defaults(handler=topic_pub)
