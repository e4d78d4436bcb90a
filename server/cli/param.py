"""``param list | get | set | describe | dump | load``, as ros2 prints them.

Each verb calls the node's own parameter services (``<node>/list_parameters`` ...) through the
lab's service calls (``POST /api/services/...``), as ``ros2lab service call`` does: every node
process serves them, and so does each of the lab's own nodes (``/simulator`` ...), so the answers
and refusals are the node's own. A value and a parameters file are read as a node reads them,
with the reader node processes use (``node_runtime.params_file``), imported only by the verbs that read one.
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from typing import Any

import yaml

from server.cli.client import LabClient

CALL_TIMEOUT_S = 5.0
SERVICE_WAIT_S = 5.0  # ros2param's wait for a node's parameter services
POLL_S = 0.1
# ParameterType's values, in order, with ros2param's words and its labels for ``param get``.
_KINDS = (
    ("not set", None, "Parameter not set."),
    ("boolean", "bool_value", "Boolean value is:"),
    ("integer", "integer_value", "Integer value is:"),
    ("double", "double_value", "Double value is:"),
    ("string", "string_value", "String value is:"),
    ("byte array", "byte_array_value", "Byte values are:"),
    ("boolean array", "bool_array_value", "Boolean values are:"),
    ("integer array", "integer_array_value", "Integer values are:"),
    ("double array", "double_array_value", "Double values are:"),
    ("string array", "string_array_value", "String values are:"),
)


def _absolute(name: str) -> str:
    return "/" + name.lstrip("/")


def python_value(value: dict[str, Any]) -> Any:
    """The value a ParameterValue (as the API gives it) holds, None when not set."""
    field = _KINDS[int(value["type"])][1]
    return None if field is None else value[field]


def parameter_value(value: Any) -> dict[str, Any]:
    """A Python value as a ParameterValue (the API's JSON), typed as rclpy types it."""
    scalars = ((bool, 1), (int, 2), (float, 3), (str, 4))
    for kind, code in scalars:
        if isinstance(value, kind):
            return {"type": code, _KINDS[code][1]: value}  # type: ignore[dict-item]
    items = list(value)
    for kind, code in scalars:
        if all(type(v) is kind for v in items):
            return {"type": code + 5, _KINDS[code + 5][1]: items}  # type: ignore[dict-item]
    return {"type": 4, "string_value": str(value)}


def _parameter_nodes(client: LabClient) -> list[str]:
    return sorted(
        node
        for s in client.get("/api/services")
        if s["name"].endswith("/list_parameters") and s["type"] == "rcl_interfaces/srv/ListParameters"
        for node in s.get("servers", [])
        if s["name"] == f"{node}/list_parameters"
    )


def _wait(check: Any, timeout_s: float) -> bool:
    end = time.monotonic() + timeout_s
    while not check():
        if time.monotonic() >= end:
            return False
        time.sleep(POLL_S)
    return True


def _ready(client: LabClient, node: str, timeout_s: float) -> bool:
    """ros2param's checks: the node exists (within ``--timeout``), then it serves its parameter
    services (within 5 s); says which one failed, as ros2 does."""
    if not _wait(lambda: any(n["name"] == node for n in client.get("/api/nodes")), timeout_s):
        print("Node not found", file=sys.stderr)
        return False
    if not _wait(lambda: node in _parameter_nodes(client), SERVICE_WAIT_S):
        print(f"Wait for service timed out waiting for parameter services for node {node}", file=sys.stderr)
        return False
    return True


def _call(client: LabClient, node: str, service: str, srv_type: str, request: dict[str, Any]) -> Any:
    body = {"request": request, "type": f"rcl_interfaces/srv/{srv_type}", "timeout_s": CALL_TIMEOUT_S}
    answer = client.post(f"/api/services{node}/{service}", body, timeout_s=CALL_TIMEOUT_S + 5.0)
    return answer["response"]


def param_list(args: argparse.Namespace, client: LabClient) -> int:
    nodes = _parameter_nodes(client)
    if args.node_name:
        node = _absolute(args.node_name)
        if not _ready(client, node, 1.0):
            return 1
        nodes = [node]
    pattern = re.compile(args.filter) if args.filter else None
    for node in nodes:
        request = {"prefixes": args.param_prefixes, "depth": 0}
        names = sorted(_call(client, node, "list_parameters", "ListParameters", request)["result"]["names"])
        names = [n for n in names if pattern is None or pattern.match(n)]
        if not args.node_name and names:
            print(f"{node}:")
        types: dict[str, str] = {}
        if args.param_type:
            described = _call(client, node, "describe_parameters", "DescribeParameters", {"names": names})
            types = {d["name"]: _KINDS[int(d["type"])][0] for d in described["descriptors"]}
        for name in names:
            print(f"  {name} (type: {types[name]})" if args.param_type else f"  {name}")
    return 0


def _value_text(value: dict[str, Any]) -> str | None:
    kind = int(value["type"])
    held = python_value(value)
    if kind == 5:  # rclpy's byte array is a list of one-byte bytes
        return str([bytes([b]) for b in held])
    return None if held is None else str(held)


def param_get(args: argparse.Namespace, client: LabClient) -> int:
    node = _absolute(args.node_name)
    if not _ready(client, node, args.timeout):
        return 1
    values = _call(client, node, "get_parameters", "GetParameters", {"names": [args.parameter_name]})[
        "values"
    ]
    if not values:
        print("Parameter not set", file=sys.stderr)
        return 1
    text, label = _value_text(values[0]), _KINDS[int(values[0]["type"])][2]
    if args.hide_type:
        print(text)
    else:
        print(label if text is None else f"{label} {text}")
    return 0


def _report(name: str | None, result: dict[str, Any]) -> None:
    what = f"Set parameter {name}" if name else "Set parameter"
    reason = f": {result['reason']}" if result.get("reason") else ""
    if result["successful"]:
        print(f"{what} successful{reason}")
    else:
        print(f"{what + ' failed' if name else 'Setting parameter failed'}{reason}", file=sys.stderr)


def param_set(args: argparse.Namespace, client: LabClient) -> int:
    node = _absolute(args.node_name)
    if not _ready(client, node, args.timeout):
        return 1
    from node_runtime.params_file import value_from_text

    param = {"name": args.parameter_name, "value": parameter_value(value_from_text(args.value))}
    (result,) = _call(client, node, "set_parameters", "SetParameters", {"parameters": [param]})["results"]
    _report(None, result)
    return 0


def param_describe(args: argparse.Namespace, client: LabClient) -> int:
    node = _absolute(args.node_name)
    if not _ready(client, node, args.timeout):
        return 1
    described = _call(
        client, node, "describe_parameters", "DescribeParameters", {"names": args.parameter_names}
    )
    for d in described["descriptors"]:
        print("Parameter name:", d["name"])
        print("  Type:", _KINDS[int(d["type"])][0])
        if d["description"]:
            print("  Description:", d["description"])
        print("  Constraints:")
        if d["read_only"]:
            print("    Read only: true")
        ranges = d["floating_point_range"] + d["integer_range"]
        if ranges:
            print("    Min value:", ranges[0]["from_value"])
            print("    Max value:", ranges[0]["to_value"])
            if ranges[0]["step"]:
                print("    Step:", ranges[0]["step"])
        if d["additional_constraints"]:
            print("    Additional constraints:", d["additional_constraints"])
    return 0


def _insert(tree: dict[str, Any], name: str, value: Any) -> None:
    head, sep, rest = name.partition(".")
    if sep:
        _insert(tree.setdefault(head, {}), rest, value)
    else:
        tree[name] = value


def param_dump(args: argparse.Namespace, client: LabClient) -> int:
    node = _absolute(args.node_name)
    if not _ready(client, node, args.timeout):
        return 1
    names = sorted(_call(client, node, "list_parameters", "ListParameters", {})["result"]["names"])
    values = _call(client, node, "get_parameters", "GetParameters", {"names": names})["values"]
    params: dict[str, Any] = {}
    for name, value in zip(names, values, strict=False):
        _insert(params, name, python_value(value))
    print(yaml.dump({node: {"ros__parameters": params}}, default_flow_style=False))
    return 0


def param_load(args: argparse.Namespace, client: LabClient) -> int:
    node = _absolute(args.node_name)
    from node_runtime.params_file import ParamsFileError, read_params_file

    try:  # read before anything is sent: a file that does not parse sets nothing
        values = read_params_file(args.parameter_file).every_section(not args.no_use_wildcard)
    except ParamsFileError as exc:
        print(exc, file=sys.stderr)
        return 1
    if not _ready(client, node, args.timeout):
        return 1
    request = {"parameters": [{"name": n, "value": parameter_value(v)} for n, v in values.items()]}
    results = _call(client, node, "set_parameters", "SetParameters", request)["results"]
    for name, result in zip(values, results, strict=False):
        _report(name, result)
    return 0


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("param", help="Various param related sub-commands")
    sub = parser.add_subparsers(dest="param_verb", required=True, metavar="VERB")

    def verb(name: str, help_text: str, handler: Any, node_optional: bool = False) -> argparse.ArgumentParser:
        p: argparse.ArgumentParser = sub.add_parser(name, parents=[common], help=help_text)
        p.add_argument("node_name", nargs="?" if node_optional else None, help="Name of the ROS node")
        if not node_optional:
            p.add_argument(
                "--timeout",
                metavar="N",
                type=float,
                default=1.0,
                help="Wait for N seconds until node becomes available (default 1 sec)",
            )
        p.set_defaults(handler=handler)
        return p

    p = verb("list", "Output a list of available parameters", param_list, node_optional=True)
    p.add_argument("--filter", help="Only parameters matching the regex expression will be showed")
    p.add_argument("--param-prefixes", nargs="+", default=[], help="Only list parameters with these prefixes")
    p.add_argument("--param-type", action="store_true", help="Print parameter types with parameter names")
    p = verb("get", "Get parameter", param_get)
    p.add_argument("parameter_name", help="Name of the parameter")
    p.add_argument("--hide-type", action="store_true", help="Hide the type information")
    p = verb("set", "Set parameter", param_set)
    p.add_argument("parameter_name", help="Name of the parameter")
    p.add_argument("value", help="Value of the parameter")
    p = verb("describe", "Show descriptive information about declared parameters", param_describe)
    p.add_argument("parameter_names", nargs="+", help="Names of the parameters")
    verb("dump", "Show all of the parameters of a node in a YAML file format", param_dump)
    p = verb("load", "Load parameter file for a node", param_load)
    p.add_argument("parameter_file", help="Parameter file")
    p.add_argument(
        "--no-use-wildcard",
        action="store_true",
        help="Do not load parameters in the '/**' namespace into the node",
    )
