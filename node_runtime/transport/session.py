"""Opening the Zenoh session: router, peer or client; multicast scouting off; explicit endpoints.

The app is a router where rmw_zenoh's nodes look for one (``tcp/127.0.0.1:7447``); a node
process is a peer that connects to it, as rmw_zenoh's nodes do. Nothing listens beyond loopback
unless an endpoint says so.
"""

from __future__ import annotations

import dataclasses
import json
import socket

import zenoh

from node_runtime.transport.acl import RouterLogins
from node_runtime.transport.config import ZenohSettings, endpoint_host
from node_runtime.transport.router_socket import open_to_nodes


class TransportError(RuntimeError):
    """The Zenoh session could not be opened; the message says why and what to do."""


def _check_port_free(endpoint: str) -> None:
    proto, host, port = endpoint_host(endpoint)
    if proto != "tcp" or not port:
        return
    family = socket.AF_INET6 if ":" in host.strip("[]") else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as probe:
        try:
            probe.bind((host.strip("[]"), port))
        except OSError:
            raise TransportError(
                f"Zenoh port {port} is in use (another teleop lab, or rmw_zenohd?): pick another with "
                f"--zenoh-listen tcp/{host}:{port + 1}, join that router with --zenoh-connect {endpoint}, "
                "or run without Zenoh with --no-zenoh"
            ) from None


def build_config(settings: ZenohSettings) -> zenoh.Config:
    config = zenoh.Config.from_file(str(settings.config_file)) if settings.config_file else zenoh.Config()
    config.insert_json5("mode", json.dumps(settings.mode))
    # Python's default config scouts by multicast and listens on every interface: neither, ever.
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("listen/endpoints", json.dumps(list(settings.listen)))
    config.insert_json5("connect/endpoints", json.dumps(list(settings.connect)))
    logins = settings.login.config() if settings.login is not None else {}
    for path, value in {**logins, **settings.extra}.items():
        config.insert_json5(path, value)
    return config


def open_session(settings: ZenohSettings, *, check_port: bool = True) -> zenoh.Session:
    """Open the session; a TransportError (one line, what to do) if it cannot listen or connect.
    ``check_port=False``: a router opening again on the port it just closed (its old connections
    may still hold it in TIME_WAIT, which Zenoh's own listener allows)."""
    if settings.mode == "router" and check_port:
        for endpoint in settings.listen:
            _check_port_free(endpoint)
    try:
        if settings.router_logins is None:
            session = zenoh.open(build_config(settings))
        else:
            # Zenoh reads the login file as the router opens: it exists only for that moment.
            with RouterLogins(settings.router_logins) as logins:
                extra = {**settings.extra, **logins.config}
                session = zenoh.open(build_config(dataclasses.replace(settings, extra=extra)))
    except zenoh.ZError as exc:
        where = ", ".join(settings.listen if settings.mode == "router" else settings.connect) or "nowhere"
        raise TransportError(f"Zenoh could not open a {settings.mode} session on {where}: {exc}") from None
    if settings.mode == "router" and settings.process_socket is not None:
        open_to_nodes(settings.process_socket)
    return session
