"""``launch``: start a launch file's nodes in the server's graph, keep them until Ctrl-C, then stop them.

As ``ros2 launch`` shows its processes' output, this prints the lines of the nodes it launched:
those of nodes that run in the server from the graph's ``/rosout`` (``[countdown-1] [INFO]
[1700000000.123456789] [CountDownNode]: ...``), what node processes print (tracebacks too) from
the server, and once when a node crashes or its process dies. On a class server that is the only place a
student sees them: the server's console keeps to the class.
"""

from __future__ import annotations

import argparse
import os
import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from server.cli.client import ApiError, CliError, LabClient

Sleep = Callable[[float], None]
CHECK_PERIOD_S = 1.0  # how often to ask for the launch's output (and whether it still exists)
LOG_TYPE = "rcl_interfaces/msg/Log"
SEVERITY = {10: "DEBUG", 20: "INFO", 30: "WARN", 40: "ERROR", 50: "FATAL"}
OPEN_WAIT_S = 5.0  # how long a launch waits for /rosout before it starts without it
EARLY_LINES = 1000  # /rosout lines kept while the server has not yet said which nodes are ours
_print_lock = threading.Lock()


def say(line: str) -> None:
    """One whole line on stdout (the /rosout thread prints too)."""
    with _print_lock:
        sys.stdout.write(line + "\n")
        sys.stdout.flush()


def _log_name(node: Mapping[str, Any]) -> str:
    """A launched node's name as /rosout gives it, rcl's logger name: no leading slash, the namespace
    and name dotted (``turtlesim2.sim``)."""
    return str(node.get("name") or node.get("exec")).lstrip("/").replace("/", ".")


def node_labels(group: Mapping[str, Any]) -> dict[str, str]:
    """Each started node's name (as /rosout names it, no leading slash) → its label: a node
    process's own (``keyboard_manager.py-3``), else numbered in launch order as ros2 launch
    numbers its processes (``countdown-1``, ``main_controller-2``)."""
    labels: dict[str, str] = {}
    for node in group.get("nodes", []):
        if not node.get("error"):
            labels[_log_name(node)] = str(node.get("process") or f"{node.get('exec')}-{len(labels) + 1}")
    return labels


def in_process_labels(group: Mapping[str, Any]) -> dict[str, str]:
    """``node_labels`` of the nodes that run in the server: a node process prints its own lines."""
    processes = {_log_name(node) for node in group.get("nodes", []) if node.get("process")}
    return {name: label for name, label in node_labels(group).items() if name not in processes}


def log_line(label: str, msg: Mapping[str, Any]) -> str:
    """A /rosout message as ROS 2's console prints it, behind ros2 launch's process label."""
    stamp = msg.get("stamp") or {}
    level = SEVERITY.get(int(msg.get("level", 20)), str(msg.get("level")))
    when = f"{int(stamp.get('sec', 0))}.{int(stamp.get('nanosec', 0)):09d}"
    return f"[{label}] [{level}] [{when}] [{msg.get('name')}]: {msg.get('msg')}"


class NodeLines:
    """Follows /rosout from before the launch (a node's first lines come as it starts) and prints
    the lines of the launch's own nodes once the server has named them."""

    def __init__(self, client: LabClient) -> None:
        self._client = client
        self._labels: dict[str, str] | None = None
        self._early: deque[Mapping[str, Any]] = deque(maxlen=EARLY_LINES)
        self._lock = threading.Lock()  # held while a line is sorted and printed: they keep their order
        self._settled = threading.Event()  # following /rosout now, or never will

    def start(self) -> None:
        threading.Thread(target=self._follow, name="rosout", daemon=True).start()
        self._settled.wait(OPEN_WAIT_S)

    def ours(self, group: Mapping[str, Any]) -> None:
        with self._lock:
            self._labels = in_process_labels(group)
            for msg in self._early:
                self._print(msg)
            self._early.clear()

    def _follow(self) -> None:
        try:
            for frame in self._client.subscribe(
                "/rosout", {"type": LOG_TYPE, "queue_length": 1000}, self._settled
            ):
                with self._lock:
                    msg = frame.get("msg") or {}
                    if self._labels is None:
                        self._early.append(msg)
                    else:
                        self._print(msg)
        except (CliError, ValueError, TypeError):
            pass  # the launch goes on without its nodes' lines (an older server, or it stopped)
        self._settled.set()

    def _print(self, msg: Mapping[str, Any]) -> None:
        label = (self._labels or {}).get(str(msg.get("name")))
        if label is not None:
            say(log_line(label, msg))


def report_faults(group: Mapping[str, Any], labels: Mapping[str, str], reported: set[str]) -> None:
    """ros2 launch's line for each node of ``group`` that crashed or whose process died, once;
    ``labels`` are the launch's as it started (a node that died since carries an error)."""
    for node in group.get("nodes", []):
        name = _log_name(node)
        if node.get("state") not in ("crashed", "died") or name in reported or name not in labels:
            continue
        reported.add(name)
        if node["state"] == "died":
            say(f"[ERROR] [{labels[name]}]: process has died [exit code {node.get('exit_code')}]")
        else:
            say(f"[ERROR] [{labels[name]}]: node crashed (its last line says why)")


def split_assignment(text: str, what: str) -> tuple[str, str]:
    name, sep, value = text.partition(":=")
    if not sep or not name:
        raise CliError(f"{what} are NAME:=VALUE, got {text!r}")
    return name, value


def launch_request(tokens: Sequence[str], cwd: str | None = None) -> dict[str, Any]:
    """``FILE [a:=b ...]`` or ``PKG FILE [a:=b ...]`` → the body of ``POST /api/launch``."""
    args = dict(split_assignment(t, "launch arguments") for t in tokens if ":=" in t)
    positional = [t for t in tokens if ":=" not in t]
    if len(positional) == 1:
        return {"file": os.path.abspath(os.path.join(cwd or os.getcwd(), positional[0])), "args": args}
    if len(positional) == 2:
        return {"package": positional[0], "file": positional[1], "args": args}
    raise CliError("launch takes FILE or PACKAGE FILE, then NAME:=VALUE arguments")


def _node_label(node: Mapping[str, Any]) -> str:
    name = str(node.get("name") or node.get("exec"))
    return name if name.startswith("/") else "/" + name


def report_started(group: Mapping[str, Any]) -> int:
    """What the launch file said as it was read (a Python file's LogInfo), then ros2 launch's lines
    for each node; returns how many started."""
    for message in group.get("messages") or []:
        say(str(message))
    started = 0
    for node in group.get("nodes", []):
        what = f"{_node_label(node)} ({node.get('pkg')} {node.get('exec')})"
        if node.get("error"):
            say(f"[ERROR] [launch]: {what} failed: {node['error']}")
        else:
            say(f"[INFO] [launch]: process started: {what}")
            started += 1
    return started


class ProcessLines:
    """What the launch's node processes print (their log lines and ``print``, a traceback), new
    lines only, each behind its process's label: a process's log lines come this way, not from
    /rosout, so ros2 launch's screen shows each once."""

    def __init__(self) -> None:
        self._printed: dict[str, int] = {}

    def show(self, processes: Sequence[Mapping[str, Any]]) -> None:
        for process in processes:
            label, lines = str(process.get("label")), list(process.get("lines", []))
            printed = int(process.get("printed", 0))
            new = printed - self._printed.get(label, 0)
            self._printed[label] = printed
            if new > len(lines):
                say(f"[{label}] ... ({new - len(lines)} lines not shown)")
            for line in lines[len(lines) - min(new, len(lines)) :]:
                say(f"[{label}] {line}")


def _still_there(client: LabClient, group_id: str) -> Mapping[str, Any] | None:
    """The launch's output as the server has it now; None once it is gone."""
    try:
        answer: Mapping[str, Any] = client.get(f"/api/launches/{group_id}/output")
    except ApiError as exc:
        if exc.status != 404 or exc.no_route:
            raise
        return None
    return answer


def hold_until_interrupted(client: LabClient, group: Mapping[str, Any], sleep: Sleep = time.sleep) -> int:
    """Keep the nodes until Ctrl-C, then stop them, as ros2 launch does with its processes; in
    between, print what their processes print and say when one crashes or dies."""
    try:
        if report_started(group) == 0 and group.get("nodes"):
            client.delete(f"/api/launches/{group['id']}")
            say("[ERROR] [launch]: no node started")
            return 1
        reported: set[str] = set()
        labels = node_labels(group)
        printed = ProcessLines()
        while True:
            now = _still_there(client, group["id"])
            if now is None:
                say("[INFO] [launch]: the nodes were stopped by someone else")
                return 0
            printed.show(now.get("processes", []))
            report_faults(now.get("group", {}), labels, reported)
            sleep(CHECK_PERIOD_S)
    except KeyboardInterrupt:
        say("[WARNING] [launch]: user interrupted with ctrl-c (SIGINT)")
    try:
        client.delete(f"/api/launches/{group['id']}")
    except ApiError as exc:
        if exc.status != 404:
            raise
    for node in group.get("nodes", []):
        if not node.get("error"):
            say(f"[INFO] [launch]: process has finished cleanly: {_node_label(node)}")
    return 0


def launch(args: argparse.Namespace, client: LabClient) -> int:
    request = launch_request(args.launch_arguments)
    lines = NodeLines(client)
    lines.start()  # before the launch: its nodes log as they start
    group = client.post("/api/launch", request)
    lines.ours(group)
    return hold_until_interrupted(client, group)


def add_parsers(verbs: Any, common: argparse.ArgumentParser) -> None:
    p = verbs.add_parser("launch", parents=[common], help="Run a launch file")
    p.add_argument(
        "launch_arguments",
        nargs="+",
        metavar="ARG",
        help="FILE, or PACKAGE FILE, then launch arguments as NAME:=VALUE",
    )
    p.set_defaults(handler=launch)
