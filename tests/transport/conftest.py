"""Two buses joined over real Zenoh sessions on loopback: the app's router and a node process's peer.

Zenoh delivers on its own threads, so these tests wait for what they expect, each wait bounded.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import pytest
from support.app import free_port

from node_runtime.bus import Bus, Executor
from node_runtime.transport.bridge import ZenohBridge
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.session import open_session

WAIT_S = 5.0


@dataclass
class Side:
    bus: Bus
    executor: Executor
    bridge: ZenohBridge
    session: object


@dataclass
class Pair:
    app: Side
    proc: Side
    router_endpoint: str

    def pump(
        self, condition: Callable[[], bool], what: str, timeout_s: float = WAIT_S, *, spin: bool = True
    ) -> None:
        """Run both executors (unless not ``spin``) until ``condition`` holds; fail after ``timeout_s``."""
        deadline = time.monotonic() + timeout_s
        while True:
            if spin:
                self.app.executor.spin_some()
                self.proc.executor.spin_some()
            if condition():
                return
            if time.monotonic() > deadline:
                pytest.fail(f"timed out after {timeout_s} s waiting for {what}")
            time.sleep(0.002)


def _side(settings: ZenohSettings, **bridge: Any) -> Side:
    session = open_session(settings)
    bus = Bus()
    return Side(bus, Executor(bus), ZenohBridge(bus, session, settings.domain_id, **bridge), session)


def _close(side: Side) -> None:
    side.bridge.close()
    side.session.close()  # type: ignore[attr-defined]


@contextmanager
def joined(**proc_bridge: Any) -> Iterator[Pair]:
    """The app's router and a node process's peer; ``proc_bridge`` goes to the process's bridge."""
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    app = _side(ZenohSettings(mode="router", listen=(endpoint,)))
    proc = _side(ZenohSettings(mode="peer", listen=("tcp/127.0.0.1:0",), connect=(endpoint,)), **proc_bridge)
    try:
        yield Pair(app, proc, endpoint)
    finally:
        _close(proc)
        _close(app)


@pytest.fixture
def pair() -> Iterator[Pair]:
    with joined() as both:
        yield both
