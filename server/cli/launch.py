"""``launch``: start a launch file's nodes in the server's graph, keep them until Ctrl-C, then stop them."""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from .client import ApiError, CliError, LabClient

Sleep = Callable[[float], None]
CHECK_PERIOD_S = 2.0  # how often to check that the launch still exists on the server


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
    """ros2 launch's lines for each node; returns how many started."""
    started = 0
    for node in group.get("nodes", []):
        what = f"{_node_label(node)} ({node.get('pkg')} {node.get('exec')})"
        if node.get("error"):
            print(f"[ERROR] [launch]: {what} failed: {node['error']}", flush=True)
        else:
            print(f"[INFO] [launch]: process started: {what}", flush=True)
            started += 1
    return started


def hold_until_interrupted(client: LabClient, group: Mapping[str, Any], sleep: Sleep = time.sleep) -> int:
    """Keep the nodes until Ctrl-C, then stop them, as ros2 launch does with its processes."""
    try:
        if report_started(group) == 0 and group.get("nodes"):
            client.delete(f"/api/launches/{group['id']}")
            print("[ERROR] [launch]: no node started", flush=True)
            return 1
        while True:
            sleep(CHECK_PERIOD_S)
            if not any(g.get("id") == group["id"] for g in client.get("/api/launches")):
                print("[INFO] [launch]: the nodes were stopped by someone else", flush=True)
                return 0
    except KeyboardInterrupt:
        print("[WARNING] [launch]: user interrupted with ctrl-c (SIGINT)", flush=True)
    try:
        client.delete(f"/api/launches/{group['id']}")
    except ApiError as exc:
        if exc.status != 404:
            raise
    for node in group.get("nodes", []):
        if not node.get("error"):
            print(f"[INFO] [launch]: process has finished cleanly: {_node_label(node)}", flush=True)
    return 0


def launch(args: argparse.Namespace, client: LabClient) -> int:
    group = client.post("/api/launch", launch_request(args.launch_arguments))
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
