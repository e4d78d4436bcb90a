"""``action list | info | send_goal``, as ros2 prints them.

An action is the services and topics under ``<action>/_action/``; the graph's services say which
actions there are (their ``send_goal`` services) and who serves and calls them. ``send_goal``
calls the action's services through the lab's service API and echoes its feedback topic.
"""

from __future__ import annotations

import argparse
import queue
import sys
import threading
import time
import uuid
from typing import Any

from server.cli.client import ApiError, LabClient
from server.cli.format import message_to_yaml
from server.cli.message import filled_message, parse_message

SEND_GOAL = "/_action/send_goal"
STATUS_NAMES = {1: "ACCEPTED", 2: "EXECUTING", 3: "CANCELING", 4: "SUCCEEDED", 5: "CANCELED", 6: "ABORTED"}
SERVER_POLL_S = 0.1  # how often send_goal looks for the server
RESULT_WAIT_S = 60.0  # one get_result call's wait (the lab's most); send_goal asks again after it
FEEDBACK_READY_S = 10.0  # how long send_goal waits for its feedback subscription to open


def _visible(nodes: list[str]) -> list[str]:
    """Nodes but hidden ones (a name starting with ``_``: the lab's own REST node that calls for
    ``send_goal``, as ros2's own CLI node, which is gone once its command is)."""
    return [n for n in nodes if not n.rsplit("/", 1)[-1].startswith("_")]


def _actions(client: LabClient) -> dict[str, dict[str, Any]]:
    """Each action's name → its types and the nodes serving and calling it."""
    found: dict[str, dict[str, Any]] = {}
    for service in client.get("/api/services"):
        name, type_name = service["name"], service["type"]
        servers, clients = _visible(service["servers"]), _visible(service["clients"])
        if name.endswith(SEND_GOAL) and type_name.endswith("_SendGoal") and (servers or clients):
            entry = found.setdefault(name[: -len(SEND_GOAL)], {"types": set(), "servers": [], "clients": []})
            entry["types"].add(type_name[: -len("_SendGoal")])
            entry["servers"] += servers
            entry["clients"] += clients
    return found


def action_list(args: argparse.Namespace, client: LabClient) -> int:
    actions = _actions(client)
    if args.count_actions:
        print(len(actions))
        return 0
    for name in sorted(actions):
        print(name + (f" [{', '.join(sorted(actions[name]['types']))}]" if args.show_types else ""))
    return 0


def action_info(args: argparse.Namespace, client: LabClient) -> int:
    name = "/" + args.action_name.lstrip("/")
    entry = _actions(client).get(name, {"types": set(), "servers": [], "clients": []})
    types = ", ".join(sorted(entry["types"]))
    print(f"Action: {args.action_name}")
    for title, nodes in (("clients", entry["clients"]), ("servers", entry["servers"])):
        unique = sorted(set(nodes))
        print(f"Action {title}: {len(unique)}")
        if not args.count:
            for node in unique:
                print(f"    {node} [{types}]" if args.show_types else f"    {node}")
    return 0


def _call(client: LabClient, service: str, srv_type: str, request: dict[str, Any], timeout_s: float) -> Any:
    body = {"request": request, "type": srv_type, "timeout_s": timeout_s}
    return client.post("/api/services/" + service.lstrip("/"), body, timeout_s=timeout_s + 5.0)["response"]


def _echo_feedback(
    client: LabClient,
    topic: str,
    type_name: str,
    goal_id: list[int],
    opened: threading.Event,
    out: queue.Queue[str],
) -> None:
    """Each feedback message of this goal, as ros2 prints it, into ``out`` (a thread's work)."""
    try:
        for frame in client.subscribe(topic, {"type": type_name}, opened):
            msg = frame["msg"]
            if msg["goal_id"]["uuid"] == goal_id:
                out.put(f"Feedback:\n    {message_to_yaml(msg['feedback'], truncate_length=None)}")
    except Exception as exc:  # the main thread says what went wrong; this one only reports it
        out.put(f"error: feedback: {exc}")
        opened.set()


def _wait_for_server(client: LabClient, name: str) -> None:
    while not _actions(client).get(name, {}).get("servers"):
        time.sleep(SERVER_POLL_S)


def _flush(out: queue.Queue[str]) -> None:
    while not out.empty():
        print(out.get(), flush=True)


def action_send_goal(args: argparse.Namespace, client: LabClient) -> int:
    name = "/" + args.action_name.lstrip("/")
    action_type = args.action_type.replace("/action/", "/").replace("/", "/action/", 1)
    given = parse_message(sys.stdin.read() if args.stdin else args.goal)
    try:
        default = client.get(f"/api/types/{action_type}_Goal/default")
    except ApiError as exc:
        if exc.status != 404 or exc.no_route:
            raise
        print(f"The passed action type is invalid: {args.action_type}", file=sys.stderr)
        return 1
    goal = filled_message(default, given)
    print("Waiting for an action server to become available...", flush=True)
    _wait_for_server(client, name)
    print(f"Sending goal:\n     {message_to_yaml(goal, truncate_length=None)}", flush=True)
    goal_id = list(uuid.uuid4().bytes)
    out: queue.Queue[str] = queue.Queue()
    if args.feedback:
        opened = threading.Event()
        topic, feedback_type = name + "/_action/feedback", action_type + "_FeedbackMessage"
        threading.Thread(
            target=_echo_feedback, args=(client, topic, feedback_type, goal_id, opened, out), daemon=True
        ).start()
        opened.wait(FEEDBACK_READY_S)
    request = {"goal_id": {"uuid": goal_id}, "goal": goal}
    answer = _call(client, name + SEND_GOAL, action_type + "_SendGoal", request, args.timeout)
    if not answer["accepted"]:
        print("Goal was rejected.")
        return 0
    print(f"Goal accepted with ID: {bytes(goal_id).hex()}\n", flush=True)
    result = _result(client, name, action_type, goal_id, out)
    _flush(out)
    print(f"Result:\n    {message_to_yaml(result['result'], truncate_length=None)}")
    print(f"Goal finished with status: {STATUS_NAMES.get(result['status'], 'UNKNOWN')}")
    return 0


def _result(client: LabClient, name: str, action_type: str, goal_id: list[int], out: queue.Queue[str]) -> Any:
    """The goal's result, asked again each time the lab's longest wait passes; feedback printed
    as it comes meanwhile."""
    box: queue.Queue[Any] = queue.Queue()

    def ask() -> None:
        while True:
            try:
                request = {"goal_id": {"uuid": goal_id}}
                answer = _call(
                    client, name + "/_action/get_result", action_type + "_GetResult", request, RESULT_WAIT_S
                )
                box.put(answer)
                return
            except ApiError as exc:
                if exc.status != 504:
                    box.put(exc)
                    return

    threading.Thread(target=ask, daemon=True).start()
    while True:
        _flush(out)
        try:
            result = box.get(timeout=0.05)
        except queue.Empty:
            continue
        if isinstance(result, ApiError):
            raise result
        return result


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("action", help="Various action related sub-commands")
    sub = parser.add_subparsers(dest="action_verb", required=True, metavar="VERB")

    p = sub.add_parser("list", parents=[common], help="Output a list of action names")
    p.add_argument("-t", "--show-types", action="store_true", help="Additionally show the action type")
    p.add_argument("-c", "--count-actions", action="store_true", help="Only display the number of actions")
    p.set_defaults(handler=action_list)

    p = sub.add_parser("info", parents=[common], help="Print information about an action")
    p.add_argument("action_name", help="Name of the ROS action to get info (e.g. '/fibonacci')")
    p.add_argument("-t", "--show-types", action="store_true", help="Additionally show the action type")
    p.add_argument(
        "-c",
        "--count",
        action="store_true",
        help="Only display the number of action clients and action servers",
    )
    p.set_defaults(handler=action_info)

    p = sub.add_parser("send_goal", parents=[common], help="Send an action goal")
    p.add_argument("action_name", help="Name of the ROS action (e.g. '/fibonacci')")
    p.add_argument("action_type", help="Type of the ROS action (e.g. 'example_interfaces/action/Fibonacci')")
    group = p.add_mutually_exclusive_group()
    group.add_argument(
        "goal", nargs="?", default="{}", help="Goal request values in YAML format (e.g. '{order: 10}')"
    )
    group.add_argument("--stdin", action="store_true", help="Read goal from standard input")
    p.add_argument("-f", "--feedback", action="store_true", help="Echo feedback messages for the goal")
    p.add_argument(
        "--timeout", type=float, default=5.0, help="seconds to wait for the goal's answer (default 5)"
    )
    p.set_defaults(handler=action_send_goal)
