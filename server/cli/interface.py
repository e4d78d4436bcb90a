"""``interface list | packages | package PKG | show TYPE``, as ``ros2 interface`` prints them.

Like ros2's, this reads the definitions where they are, not the graph: the lab's own interfaces
and the interface packages of the workspace (:mod:`server.cli.workspace` says which), read from
their ``.msg``/``.srv``/``.action`` files with no build step. ``show`` prints the definition with its comments
and constants, each nested type's definition indented one tab under the field that uses it. A
workspace definition that cannot load is one line on stderr naming its file and line, and exit
code 1; everything else is still listed.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from node_runtime.ament.index import PackageIndex
from node_runtime.ament.interfaces import WorkspaceInterfaces
from node_runtime.msgs import catalog
from node_runtime.msgs.registry import normalize_type_name
from node_runtime.msgs.schema import interface_text
from server.cli.client import LabClient
from server.cli.workspace import add_workspace_option, workspace_of

KIND_TITLES = {"msg": "Messages", "srv": "Services", "action": "Actions"}


def _load(args: argparse.Namespace, client: LabClient) -> WorkspaceInterfaces | None:
    return PackageIndex(workspace=workspace_of(args, client)).interfaces()


def _report(problems: list[str]) -> int:
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0


def _names(kind: str) -> list[str]:
    """The types of one kind (an action's own messages and services are not listed, as in ROS)."""
    definitions = catalog.definitions()
    found: dict[str, list[str]] = {
        "msg": list(definitions.messages),
        "srv": list(definitions.services),
        "action": list(definitions.actions),
    }
    return sorted(n for n in found[kind] if f"/{kind}/" in n)


def interface_list(args: argparse.Namespace, client: LabClient) -> int:
    reader = _load(args, client)
    kinds = (
        ["msg"]
        if args.only_msgs
        else ["srv"]
        if args.only_srvs
        else ["action"]
        if args.only_actions
        else list(KIND_TITLES)
    )
    for kind in kinds:
        print(f"{KIND_TITLES[kind]}:")
        for name in _names(kind):
            print(f"    {name}")
    return _report(reader.problems if reader is not None else [])


def _packages() -> list[str]:
    return sorted({n.split("/")[0] for kind in KIND_TITLES for n in _names(kind)})


def interface_packages(args: argparse.Namespace, client: LabClient) -> int:
    reader = _load(args, client)
    for name in _packages():
        print(name)
    return _report(reader.problems if reader is not None else [])


def interface_package(args: argparse.Namespace, client: LabClient) -> int:
    reader = _load(args, client)
    problems = reader.package_problems(args.package_name) if reader is not None else []
    names = [n for kind in KIND_TITLES for n in _names(kind) if n.split("/")[0] == args.package_name]
    if not names and not problems:
        print(f"Unknown package '{args.package_name}'", file=sys.stderr)
        return 1
    for name in names:
        print(name)
    return _report(problems)


def interface_show(args: argparse.Namespace, client: LabClient) -> int:
    reader = _load(args, client)
    wanted = args.type.strip().strip("/")
    definitions = catalog.definitions()
    candidates = [normalize_type_name(wanted, kind) for kind in KIND_TITLES] + [wanted]
    known = (definitions.messages, definitions.services, definitions.actions)
    name = next((n for n in candidates if any(n in kind for kind in known)), None)
    if name is None:
        problem = next(filter(None, (reader.problem_of(n) for n in candidates)), None) if reader else None
        print(problem or f"Unknown interface '{args.type}': no such message or service type", file=sys.stderr)
        return 1
    sys.stdout.write(interface_text(name))
    return 0


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("interface", help="Show information about ROS interfaces")
    sub = parser.add_subparsers(dest="interface_verb", required=True, metavar="VERB")

    p = sub.add_parser("list", parents=[common], help="List all interface types available")
    only = p.add_mutually_exclusive_group()
    only.add_argument("-m", "--only-msgs", action="store_true", help="Print out only the messages")
    only.add_argument("-s", "--only-srvs", action="store_true", help="Print out only the services")
    only.add_argument("-a", "--only-actions", action="store_true", help="Print out only the actions")
    add_workspace_option(p)
    p.set_defaults(handler=interface_list)

    p = sub.add_parser("packages", parents=[common], help="Output a list of packages that provide interfaces")
    add_workspace_option(p)
    p.set_defaults(handler=interface_packages)

    p = sub.add_parser(
        "package", parents=[common], help="Output a list of available interface types within one package"
    )
    p.add_argument("package_name", help="Name of the ROS package")
    add_workspace_option(p)
    p.set_defaults(handler=interface_package)

    p = sub.add_parser("show", parents=[common], help="Output the interface definition")
    p.add_argument("type", help="Show an interface definition (e.g. 'std_msgs/msg/String')")
    add_workspace_option(p)
    p.set_defaults(handler=interface_show)
