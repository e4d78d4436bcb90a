"""The class's Zenoh router: the logins it lets in, and opening it again to revoke a world's.

A world's Zenoh login belongs to that world alone: when the world is removed, its student's
processes must lose the graph at once, and the domain's next world must not be reachable with it.
eclipse-zenoh (1.10) reads a router's user/password dictionary and access-control list once, as
the router opens; nothing changes them later, and neither its Python API nor its admin space can
close one session of a router (the admin space lists them, read only). So:

- every free world domain has one random login registered ahead (``new_world_login``): a world
  made in that domain is given it, and no other world ever is;
- removing a world gives its domain a fresh login and opens the router again on the same port:
  every session is dropped, the removed world's login is refused from then on, and every other
  session (worlds, workers, the instructor's bridges, students' node processes: Zenoh clients
  connect again by themselves, within about a second, and declare again what they had) comes back
  with its own login;
- the class server gives the domain to nobody until that is done.
"""

from __future__ import annotations

import asyncio
import dataclasses
from collections.abc import Iterable
from typing import Any

from node_runtime.transport.acl import (
    FIRST_WORLD_DOMAIN,
    LAST_DOMAIN,
    Credentials,
    RouterAccess,
    new_world_login,
)
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.session import TransportError, open_session

REOPEN_ATTEMPTS = 5
REOPEN_WAIT_S = 0.2  # between attempts: the port is ours, a moment frees it


class ClassRouter:
    """The router session, opened by ``open`` and again by ``revoke``; ``settings`` are the
    class's (mode router, its listen endpoints and its own ROS domain, which no world takes)."""

    def __init__(self, settings: ZenohSettings, class_login: Credentials) -> None:
        self.settings = settings
        self.class_login = class_login
        self._logins = {
            d: new_world_login(d)
            for d in range(FIRST_WORLD_DOMAIN, LAST_DOMAIN + 1)
            if d != settings.domain_id
        }
        self.session: Any = None  # zenoh.Session (its stubs leave close() untyped)
        self.reopened = 0  # times it opened again to revoke logins

    def login(self, domain_id: int) -> Credentials:
        """The login of the world in ``domain_id`` (the one registered for it now)."""
        login = self._logins.get(domain_id)
        if login is None:
            raise ValueError(f"ROS domain {domain_id} has no world login on this router")
        return login

    def access(self) -> RouterAccess:
        return RouterAccess(self.class_login, dict(self._logins))

    async def open(self) -> Any:
        """Open the router (a TransportError says why it cannot)."""
        self.session = await asyncio.to_thread(open_session, self._settings(), check_port=True)
        return self.session

    async def revoke(self, domain_ids: Iterable[int]) -> Any:
        """Give each domain a fresh login and open the router again with them; the new session.
        Every session of an old login is dropped with the old router and refused by the new one."""
        for domain_id in domain_ids:
            self.login(domain_id)  # a domain of this router's
            self._logins[domain_id] = new_world_login(domain_id)
        old, self.session = self.session, None
        if old is not None:
            await asyncio.to_thread(old.close)
        for attempt in range(1, REOPEN_ATTEMPTS + 1):
            try:
                self.session = await asyncio.to_thread(open_session, self._settings(), check_port=False)
                break
            except TransportError:
                if attempt == REOPEN_ATTEMPTS:
                    raise
                await asyncio.sleep(REOPEN_WAIT_S)
        self.reopened += 1
        return self.session

    def close(self) -> None:
        if self.session is not None:
            self.session.close()
            self.session = None

    def _settings(self) -> ZenohSettings:
        return dataclasses.replace(self.settings, router_logins=self.access())
