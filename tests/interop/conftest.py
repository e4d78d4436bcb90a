"""Independent peers (zenoh-ros2-sdk) in processes of their own against the real app."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO, App, JsonProcess

# The lab's own definitions, and ROS 2's as the set-up extracted them from its wheels.
FOLDERS = (REPO / "node_runtime" / "msgs" / "interfaces", REPO / "node_runtime" / "msgs" / "ros_interfaces")


def definition_file(pkg: str, kind: str, short: str) -> Path:
    (found,) = [path for f in FOLDERS if (path := f / pkg / kind / f"{short}.{kind}").is_file()]
    return found


def definitions(*types: str) -> dict[str, str]:
    """The .msg texts of ``types`` and what they nest, as files a ROS 2 install would carry."""
    out: dict[str, str] = {}

    def add(name: str) -> None:
        if name in out:
            return
        pkg, kind, short = name.split("/")
        text = definition_file(pkg, kind, short).read_text()
        out[name] = text
        for line in text.splitlines():
            words = line.split("#", 1)[0].split()
            if len(words) >= 2 and "/" in words[0] and "=" not in words[1]:
                dep_pkg, dep = words[0].split("[", 1)[0].split("/")
                add(f"{dep_pkg}/msg/{dep}")
            elif len(words) >= 2 and words[0][:1].isupper() and "=" not in words[1]:
                add(f"{pkg}/msg/{words[0].split('[', 1)[0]}")

    for name in types:
        add(name)
    return out


def service_text(name: str) -> tuple[str, str]:
    pkg, kind, short = name.split("/")
    request, _, response = definition_file(pkg, kind, short).read_text().partition("---")
    strip = "\n".join(line for line in request.splitlines() if not line.startswith("#"))
    return strip, response


@pytest.fixture(scope="module")
def app(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    """The all launch, with time to press "a" before lift-off (10 s start delay, then 10 s of countdown)."""
    lab = App(tmp_path_factory.mktemp("interop"), "--launch", "all", "start_delay:=10")
    try:
        yield lab
    finally:
        lab.stop()


@pytest.fixture
def sdk_peer(app: App) -> Iterator[JsonProcess]:
    peer = JsonProcess(
        [sys.executable, str(REPO / "tests" / "interop" / "sdk_peer.py"), "--router", app.router]
    )
    try:
        peer.expect(lambda e: e.get("event") == "ready", "the peer to start")
        yield peer
    finally:
        peer.stop()
