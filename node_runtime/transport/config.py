"""What the Zenoh session is to be: mode, endpoints, domain. Plain data; no Zenoh import here."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Literal

if TYPE_CHECKING:
    from node_runtime.transport.acl import Credentials, RouterAccess

DEFAULT_ROUTER_PORT = 7447
DEFAULT_ROUTER_ENDPOINT = f"tcp/127.0.0.1:{DEFAULT_ROUTER_PORT}"
LOOPBACK_HOSTS = frozenset({"127.0.0.1", "localhost", "[::1]", "::1"})
Mode = Literal["router", "peer", "client"]


@dataclass(frozen=True)
class ZenohSettings:
    mode: Mode = "router"
    listen: tuple[str, ...] = (DEFAULT_ROUTER_ENDPOINT,)
    connect: tuple[str, ...] = ()
    domain_id: int = 0
    config_file: Path | None = None  # a Zenoh JSON5 config (TLS, user/password ...), applied first
    extra: dict[str, str] = field(default_factory=dict)  # more config keys: path → JSON5 value
    login: Credentials | None = None  # the user and password the router asks for (a class's)
    router_logins: RouterAccess | None = None  # a router: who may log in, and what each may touch
    samples_hz: float | None = None  # samples a second taken from other processes (None: all)
    # A Unix socket on this machine where the graph's router listens too (a router's own, listed in
    # ``listen``; a client's, its router's): sandboxed node processes reach the graph only there.
    process_socket: Path | None = None

    def __post_init__(self) -> None:
        if not 0 <= self.domain_id <= 232:
            raise ValueError(f"ROS_DOMAIN_ID must be in 0..232, got {self.domain_id}")
        for endpoint in (*self.listen, *self.connect):
            endpoint_host(endpoint)


def domain_id_from_env(default: int = 0) -> int:
    text = os.environ.get("ROS_DOMAIN_ID", "").strip()
    if not text:
        return default
    if not text.isdigit():
        raise ValueError(f"ROS_DOMAIN_ID must be a number, got {text!r}")
    return int(text)


def endpoint_host(endpoint: str) -> tuple[str, str, int | None]:
    """``tcp/127.0.0.1:7447#iface=lo`` → (``tcp``, ``127.0.0.1``, 7447); ValueError if malformed."""
    proto, sep, rest = endpoint.partition("/")
    if not sep or not proto or not rest:
        raise ValueError(
            f"a Zenoh endpoint is PROTOCOL/HOST:PORT (e.g. {DEFAULT_ROUTER_ENDPOINT}), got {endpoint!r}"
        )
    address = rest.split("#", 1)[0].split("?", 1)[0]
    host, colon, port = address.rpartition(":")
    if not colon or not host:
        return proto, address, None
    if not port.isdigit() or not 0 <= int(port) <= 65535:
        raise ValueError(f"bad port in Zenoh endpoint {endpoint!r}")
    return proto, host, int(port)


def is_loopback(endpoint: str) -> bool:
    return endpoint_host(endpoint)[1] in LOOPBACK_HOSTS
