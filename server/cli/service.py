"""``service list | type | call``, as ros2 prints them."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from server.cli.client import ApiError, LabClient
from server.cli.message import message_repr, parse_message


def service_list(args: argparse.Namespace, client: LabClient) -> int:
    for service in client.get("/api/services"):
        print(service["name"] + (f" [{service['type']}]" if args.show_types else ""))
    return 0


def service_type(args: argparse.Namespace, client: LabClient) -> int:
    name = "/" + args.service_name.lstrip("/")
    types = sorted({s["type"] for s in client.get("/api/services") if s["name"] == name})
    if not types:
        print(f"Unknown service '{name}'", file=sys.stderr)
        return 1
    print("\n".join(types))
    return 0


def service_call(args: argparse.Namespace, client: LabClient) -> int:
    request = parse_message(args.values)
    name = "/" + args.service_name.lstrip("/")
    srv_type = args.service_type.replace("/srv/", "/").replace("/", "/srv/", 1)
    print(f"requester: making request: {message_repr(srv_type + '_Request', request)}\n")
    body: dict[str, Any] = {"request": request, "type": srv_type, "timeout_s": args.timeout}
    try:
        answer = client.post("/api/services/" + name.lstrip("/"), body, timeout_s=args.timeout + 5.0)
    except ApiError as exc:
        if exc.status in (404, 409, 422, 504) and not exc.no_route:
            print(f"error: {exc.detail}", file=sys.stderr)
            return 1
        raise
    print(f"response:\n{message_repr(answer['type'] + '_Response', answer['response'])}\n")
    return 0


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("service", help="Various service related sub-commands")
    sub = parser.add_subparsers(dest="service_verb", required=True, metavar="VERB")

    p = sub.add_parser("list", parents=[common], help="Output a list of available services")
    p.add_argument("-t", "--show-types", action="store_true", help="Additionally show the service type")
    p.set_defaults(handler=service_list)

    p = sub.add_parser("type", parents=[common], help="Output a service's type")
    p.add_argument("service_name", help="Name of the ROS service to get type (e.g. '/rocket/reset')")
    p.set_defaults(handler=service_type)

    p = sub.add_parser("call", parents=[common], help="Call a service")
    p.add_argument("service_name", help="Name of the ROS service to call to (e.g. '/rocket/reset')")
    p.add_argument("service_type", help="Type of the ROS service (e.g. 'std_srvs/srv/Trigger')")
    p.add_argument("values", nargs="?", default="{}", help="Values to fill the request with in YAML format")
    p.add_argument("--timeout", type=float, default=5.0, help="seconds to wait for the answer (default 5)")
    p.set_defaults(handler=service_call)
