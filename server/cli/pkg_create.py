"""``pkg create``: a new package with ``ros2 pkg create``'s options, files and messages.

The files are server.packages.templates', written by server.services.workspace.package_create; ``ros2lab run PKG NODE`` runs the new node at once
(no ``colcon build`` here). The license text itself is not written (ros2 copies it from
ament_copyright): the package.xml names the license, as ros2 does for one it does not know.
"""

from __future__ import annotations

import argparse
import getpass
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

from server.cli.client import LabClient
from server.packages.templates import PackageSpec
from server.services.workspace.package_create import package_refusal, write_package

GIT_TIMEOUT_S = 5.0


def _maintainer_email(name: str, given: str | None) -> str:
    """As ros2 does: the option, else ``git config user.email``, else ``NAME@todo.todo``."""
    if given:
        return given
    git = shutil.which("git")
    if git is not None:
        try:
            found = subprocess.run(
                [git, "config", "user.email"],
                capture_output=True,
                text=True,
                timeout=GIT_TIMEOUT_S,
                check=False,
            ).stdout.strip()
        except (OSError, subprocess.TimeoutExpired):
            found = ""
        if found:
            return found
    return f"{name}@todo.todo"


def _refusal(args: argparse.Namespace) -> str | None:
    return package_refusal(args.package_name, args.build_type, args.node_name)


def create(args: argparse.Namespace, _client: LabClient) -> int:
    refusal = _refusal(args)
    if refusal is not None:
        print(refusal, file=sys.stderr)
        return 1
    spec = PackageSpec(
        name=args.package_name,
        build_type=args.build_type,
        description=args.description,
        license=args.license,
        maintainer_name=args.maintainer_name,
        maintainer_email=_maintainer_email(args.maintainer_name, args.maintainer_email),
        dependencies=list(args.dependencies),
        node_name=args.node_name,
    )
    destination = Path(args.destination_directory)
    package_dir = destination / spec.name
    if package_dir.exists():
        print(
            f"\nAborted!\nThe directory already exists: {package_dir}\nEither remove the directory or choose a "
            "different destination directory or package name",
            file=sys.stderr,
        )
        return 1
    print("going to create a new package")
    print("package name:", spec.name)
    print("destination directory:", destination.resolve())
    print("package format: 3")
    print("version: 0.0.0")
    print("description:", spec.description)
    print("maintainer:", [f"{spec.maintainer_name} <{spec.maintainer_email}>"])
    print("licenses:", [spec.license])
    print("build type:", spec.build_type)
    print("dependencies:", spec.dependencies)
    if spec.node_name:
        print("node_name:", spec.node_name)
    write_package(package_dir, spec, lambda what, path: print(what, path))
    print(f"\n[WARNING]: no LICENSE file has been created; '{spec.license}' is set in the package.xml.")
    return 0


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    p = sub.add_parser("create", parents=[common], help="Create a new ROS 2 package")
    p.add_argument("package_name", help="The package name")
    p.add_argument(
        "--package-format",
        "--package_format",
        type=int,
        default=3,
        choices=[3],
        help="The package.xml format.",
    )
    p.add_argument(
        "--description", default="TODO: Package description", help="The description given in the package.xml"
    )
    p.add_argument(
        "--license", default="TODO: License declaration", help="The license attached to this package"
    )
    p.add_argument(
        "--destination-directory", default=".", help="Directory where to create the package directory"
    )
    p.add_argument(
        "--build-type",
        default="ament_cmake",
        choices=["ament_cmake", "ament_python"],
        help="The build type to process the package with",
    )
    p.add_argument("--dependencies", nargs="+", default=[], help="list of dependencies")
    p.add_argument("--maintainer-email", help="email address of the maintainer of this package")
    p.add_argument(
        "--maintainer-name", default=getpass.getuser(), help="name of the maintainer of this package"
    )
    p.add_argument("--node-name", help="name of the empty executable")
    p.set_defaults(handler=create)
