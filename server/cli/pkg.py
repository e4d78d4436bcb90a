"""``pkg list|executables|prefix|create``: the lab's packages and the workspace's, as ``ros2 pkg``
prints them.

``list`` and ``executables`` print what ``ros2 run`` can start: the lab's own packages, overlaid
by the workspace's (:mod:`server.cli.workspace` says which workspace). There is no install space
here: a package's prefix is its folder (the lab's own, or the workspace's source folder), which
is also where ``$(find-pkg-share PKG)`` looks for its launch files. A workspace file that cannot
be read (a ``package.xml`` that does not parse, two packages with one name) is one line on stderr
naming it, and exit code 1.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from node_runtime.ament.index import PackageIndex, PackageNotFoundError, WorkspaceError
from server.cli import pkg_create
from server.cli.client import LabClient
from server.cli.workspace import add_workspace_option, workspace_of

PACKAGE_NOT_FOUND = "Package not found"


def _index(args: argparse.Namespace, client: LabClient) -> PackageIndex:
    return PackageIndex(workspace=workspace_of(args, client))


def _problems(index: PackageIndex) -> int:
    problems = index.student_workspace().problems.values()
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0


def list_packages(args: argparse.Namespace, client: LabClient) -> int:
    index = _index(args, client)
    for name in index.names():
        print(name)
    return _problems(index)


def executables(args: argparse.Namespace, client: LabClient) -> int:
    index = _index(args, client)
    names = [args.package_name] if args.package_name else index.names()
    code = 0
    for pkg in names:
        try:
            exes = index.executables_of(pkg)
        except PackageNotFoundError:
            print(f"Package '{pkg}' not found", file=sys.stderr)
            return 1
        except WorkspaceError as exc:
            print(exc, file=sys.stderr)
            code = 1
            continue
        for name, exe in sorted(exes.items()):
            print(exe.file if args.full_path and exe.file is not None else f"{pkg} {name}")
    return max(code, _problems(index) if args.package_name is None else 0)


def prefix(args: argparse.Namespace, client: LabClient) -> int:
    index = _index(args, client)
    try:
        print(index.share_dir(args.package_name))
    except PackageNotFoundError:
        print(PACKAGE_NOT_FOUND, file=sys.stderr)
        return 1
    except WorkspaceError as exc:
        print(exc, file=sys.stderr)
        return 1
    return 0


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    p = verbs.add_parser("pkg", parents=[common], help="Various package related sub-commands")
    sub = p.add_subparsers(dest="pkg_verb", required=True, metavar="COMMAND")
    lst = sub.add_parser("list", parents=[common], help="Output a list of available packages")
    add_workspace_option(lst)
    lst.set_defaults(handler=list_packages)
    exe = sub.add_parser(
        "executables", parents=[common], help="Output a list of package specific executables"
    )
    exe.add_argument("package_name", nargs="?", help="The package name")
    exe.add_argument("--full-path", action="store_true", help="Show full path of each executable")
    add_workspace_option(exe)
    exe.set_defaults(handler=executables)
    pre = sub.add_parser("prefix", parents=[common], help="Output the prefix path of a package")
    pre.add_argument("package_name", help="The package name")
    pre.add_argument(
        "--share", action="store_true", help="Show share directory for the package (the same here)"
    )
    add_workspace_option(pre)
    pre.set_defaults(handler=prefix)
    pkg_create.add_parser(sub, common)
