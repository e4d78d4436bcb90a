"""rclpy's context for a node process: one bus, one executor and one Zenoh session, as rmw_zenoh's.

The session is a peer that connects to the lab's router (``tcp/127.0.0.1:7447`` unless
``ZENOH_CONFIG_OVERRIDE`` or ``ZENOH_SESSION_CONFIG_URI`` says otherwise, as with rmw_zenoh),
listens on loopback only and never scouts by multicast.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

from node_runtime.bus import Bus, NodeOverrides, SystemClock
from node_runtime.bus.blocking import BlockingExecutor
from node_runtime.bus.graph import set_process_bus
from node_runtime.transport.bridge import ZenohBridge
from node_runtime.transport.config import DEFAULT_ROUTER_ENDPOINT, domain_id_from_env
from rclpy._console import console_line, set_threshold
from rclpy._ros_args import RosArgs, parse_ros_args
from rclpy._wait_set import WaitSet

ROUTER_WAIT_NOTE_S = 1.0  # say once that the lab's router is not there yet, then keep waiting


class RCLError(RuntimeError):
    """Misuse of the client library (rclpy's ``RCLError``): calls out of order, a context shut down."""


def _apply_override(config: Any, text: str) -> None:
    """``key=value;key=value`` (values JSON5), as rmw_zenoh reads ``ZENOH_CONFIG_OVERRIDE``."""
    for part in filter(None, (p.strip() for p in text.split(";"))):
        key, sep, value = part.partition("=")
        if not sep or not key.strip():
            raise RCLError(f"ZENOH_CONFIG_OVERRIDE: expected key=value, got {part!r}")
        config.insert_json5(key.strip(), value.strip())


def open_peer_session(domain_id: int) -> Any:
    import zenoh

    uri = os.environ.get("ZENOH_SESSION_CONFIG_URI", "").strip()
    config = zenoh.Config.from_file(uri) if uri else zenoh.Config()
    config.insert_json5("mode", json.dumps("peer"))
    config.insert_json5("scouting/multicast/enabled", "false")
    # As rmw_zenoh's session: timestamps on samples (transient-local publishers' caches need them).
    config.insert_json5("timestamping/enabled", '{"router": true, "peer": true, "client": true}')
    if not uri:
        config.insert_json5("listen/endpoints", json.dumps(["tcp/127.0.0.1:0"]))
        config.insert_json5("connect/endpoints", json.dumps([DEFAULT_ROUTER_ENDPOINT]))
    _apply_override(config, os.environ.get("ZENOH_CONFIG_OVERRIDE", ""))
    return zenoh.open(config)


def _router_endpoints(_session: Any) -> str:
    """Where the session looks for the router (for a message): the override's, or the default."""
    for part in os.environ.get("ZENOH_CONFIG_OVERRIDE", "").split(";"):
        key, sep, value = part.partition("=")
        if sep and key.strip() == "connect/endpoints":
            with contextlib.suppress(ValueError):
                return ", ".join(json.loads(value))
    return DEFAULT_ROUTER_ENDPOINT


def wait_for_router(session: Any) -> None:
    """Wait for the lab's router, as rmw_zenoh waits for rmw_zenohd; ``ZENOH_ROUTER_CHECK_ATTEMPTS``
    (seconds, here) bounds the wait, 0 or unset waits for ever."""
    attempts = int(os.environ.get("ZENOH_ROUTER_CHECK_ATTEMPTS", "0") or 0)
    started = time.monotonic()
    noted = False
    while not list(session.info.routers_zid()):
        waited = time.monotonic() - started
        if attempts > 0 and waited >= attempts:
            raise RCLError(
                f"no Zenoh router at {_router_endpoints(session)} after {attempts} s: is the lab running?"
            )
        if not noted and waited >= ROUTER_WAIT_NOTE_S:
            print(
                f"[WARN] [{time.time():.9f}] [rclpy]: Unable to connect to the lab's Zenoh router at "
                f"{_router_endpoints(session)}. Is the lab running (bash scripts/run.sh)? Waiting for it ...",
                file=sys.stderr,
                flush=True,
            )
            noted = True
        time.sleep(0.02)


class Context:
    """What ``rclpy.init()`` makes and ``rclpy.shutdown()`` ends."""

    def __init__(self) -> None:
        self.bus: Bus | None = None
        self.executor: BlockingExecutor | None = None
        self.bridge: ZenohBridge | None = None
        self.session: Any = None
        self.args = RosArgs()
        self._ok = False
        self._lock = threading.Lock()

    def ok(self) -> bool:
        return self._ok

    def init(self, args: Sequence[str] | None = None, domain_id: int | None = None) -> None:
        with self._lock:
            if self._ok:
                raise RCLError("rclpy.init() was already called for this context")
            self.args = parse_ros_args(list(sys.argv if args is None else args))
            if self.args.log_level is not None:
                set_threshold(self.args.log_level)
            bus = Bus(SystemClock())
            bus.lock = threading.RLock()
            bus.console = console_line
            self.executor = WaitSet(bus)
            domain = domain_id if domain_id is not None else domain_id_from_env()
            if os.environ.get("ROS2LAB_NO_ZENOH") != "1":
                self.session = open_peer_session(domain)
                wait_for_router(self.session)
                self.bridge = ZenohBridge(bus, self.session, domain)
                self.bridge.settle_graph()
            overrides = NodeOverrides(
                name=self.args.node_name,
                namespace=self.args.namespace,
                parameters=dict(self.args.parameters),
                remappings=dict(self.args.remappings),
                files=tuple(self.args.params_files),
            )
            set_process_bus(bus, overrides)
            self.bus = bus
            self._ok = True
            _install_sigterm()
            _before_thread_join(self._close_at_exit)

    def require(self) -> tuple[Bus, BlockingExecutor]:
        if not self._ok or self.bus is None or self.executor is None:
            raise RCLError("rclpy.init() has not been called, or rclpy.shutdown() already was")
        return self.bus, self.executor

    def _close_at_exit(self) -> None:
        if self._ok:
            with contextlib.suppress(Exception):  # the interpreter is going away; nobody to tell
                self.shutdown()

    def shutdown(self) -> None:
        with self._lock:
            if not self._ok:
                raise RCLError("rclpy.shutdown() was already called, or rclpy.init() never was")
            self._ok = False
            bus, executor = self.bus, self.executor
            if executor is not None:
                executor.stop()
            if bus is not None:
                for node in list(bus.nodes):
                    node.destroy_node()
            if self.bridge is not None:
                self.bridge.close()
            if self.session is not None:
                self.session.close()
            set_process_bus(None)
            self.bridge = self.session = None
        _forget_nested_interrupt()


def _forget_nested_interrupt() -> None:
    """CPython marks the interpreter "ended by Ctrl-C" (exit status -SIGINT, no traceback) when a
    KeyboardInterrupt leaves any ``exec`` of a string, even one nested in a library (rosbags builds
    its CDR code that way) whose exception the node's own ``except KeyboardInterrupt`` then
    catches. Shutting down means the node handled it; a KeyboardInterrupt that still leaves the
    script sets the mark again when the script ends. CPython 3.11 keeps the mark in this symbol."""
    import ctypes

    with contextlib.suppress(ValueError, AttributeError):
        ctypes.c_int.in_dll(ctypes.pythonapi, "_Py_UnhandledKeyboardInterrupt").value = 0


def _before_thread_join(hook: Callable[[], None]) -> None:
    """Run ``hook`` when the interpreter starts to exit, before it waits for non-daemon threads.

    Zenoh runs Python callbacks on threads of its own that are not daemons, so a script that ends
    (or dies of an exception) without ``rclpy.shutdown()`` would wait for them for ever; rclpy's
    scripts simply exit. ``atexit`` runs too late (after that wait): threading's own exit hooks run
    first, as concurrent.futures uses them.
    """
    register = getattr(threading, "_register_atexit", None)
    if register is not None:
        register(hook)
    else:  # a Python without the hook: at least close at exit
        import atexit

        atexit.register(hook)


def _install_sigterm() -> None:
    """SIGTERM (``ros2 launch`` stopping a node, the lab shutting down) ends ``spin`` as Ctrl-C does."""
    if threading.current_thread() is not threading.main_thread():
        return

    def interrupt(_signum: int, _frame: object) -> None:
        raise KeyboardInterrupt

    if signal.getsignal(signal.SIGTERM) in (signal.SIG_DFL, None):
        signal.signal(signal.SIGTERM, interrupt)


default_context = Context()
