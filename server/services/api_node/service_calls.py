"""``ros2 service call`` for the API and the CLI: the lab's hidden node calls, the caller awaits.

A service is found on the bus (served or called in this process) or in the graph other
processes declare on Zenoh; its type comes from there unless the caller names one.
"""

from __future__ import annotations

import asyncio
from typing import Any

from node_runtime.bus import (
    Future,
    Node,
    ServiceClient,
    ServiceTimeoutError,
    TopicTypeError,
    UnknownServiceError,
    validate_topic_name,
)
from node_runtime.msgs import Message, Service, UnknownTypeError, get_service_type
from node_runtime.transport.keys import EntityKind
from node_runtime.transport.remote_graph import RemoteGraph

MAX_CLIENTS = 64  # services the API keeps a client for; the oldest is dropped beyond that
DEFAULT_TIMEOUT_S = 5.0


def remote_service_types(remote: RemoteGraph | None, name: str) -> set[str]:
    if remote is None:
        return set()
    return {e.type_name for e in remote.endpoints([EntityKind.SERVICE]) if e.name == name}


class ServiceCaller:
    def __init__(self, node: Node) -> None:
        self.node = node
        self._clients: dict[str, ServiceClient] = {}

    def service_type(self, name: str, type_name: str | None, remote: RemoteGraph | None) -> type[Service]:
        """The type to call ``name`` with. A service nobody serves (here or in another process) is
        unknown, even with a type given: the call could only time out."""
        channel = self.node.bus.services.get(name)
        served_here = channel is not None and any(server.active for server in channel.servers)
        known = {channel.srv_type.TYPE} if served_here and channel else remote_service_types(remote, name)
        if not known:
            raise UnknownServiceError(name)
        if type_name is not None:
            wanted = get_service_type(type_name)
            if known and wanted.TYPE not in known:
                raise TopicTypeError(f"service {name} is a {', '.join(sorted(known))}, not {wanted.TYPE}")
            return wanted
        if len(known) > 1:
            raise TopicTypeError(f"service {name} is served with several types ({', '.join(sorted(known))})")
        (only,) = known
        try:
            return get_service_type(only)
        except UnknownTypeError:
            raise UnknownTypeError(only, "service") from None

    def _client(self, name: str, srv_type: type[Service]) -> ServiceClient:
        client = self._clients.get(name)
        if client is not None and client.srv_type is srv_type and not client.destroyed:
            return client
        if client is not None:
            client.destroy()
        if len(self._clients) >= MAX_CLIENTS:
            oldest = next(iter(self._clients))
            self._clients.pop(oldest).destroy()
        client = self._clients[name] = self.node.create_client(srv_type, name)
        return client

    def prepare(
        self, service: str, request: dict[str, Any], type_name: str | None, remote: RemoteGraph | None
    ) -> tuple[str, type[Service], Message]:
        """Resolve the name and type and build the request: everything that can be refused, before
        anything is sent."""
        name = self.node.resolve_topic_name(validate_topic_name(service))
        srv_type = self.service_type(name, type_name, remote)
        return name, srv_type, srv_type.Request.from_dict(request)

    async def call(self, name: str, srv_type: type[Service], request: Message, timeout_s: float) -> Message:
        client = self._client(name, srv_type)
        done: asyncio.Future[Message] = asyncio.get_running_loop().create_future()

        def settle(future: Future[Message]) -> None:
            if done.done():
                return
            if future.exception() is not None:
                done.set_exception(future.exception())  # type: ignore[arg-type]
            else:
                done.set_result(future.result())  # type: ignore[arg-type]

        client.call_async(request).add_done_callback(settle)
        try:
            return await asyncio.wait_for(done, timeout_s)
        except TimeoutError:
            raise ServiceTimeoutError(name, timeout_s) from None
