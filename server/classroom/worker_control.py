"""A world worker's side of the class server's hello: it answers on the class's router with where
its API is and how full it is, sealed with the class's token (server/classroom/workers.py)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from server.classroom.workers import control_key, genuine_hello, seal
from server.host.settings import WorkerSettings

TOKEN_ENV = "ROS2LAB_TOKEN"  # where a world worker finds the instructor's token (never on its command line)


class WorkerControl:
    """Answers hellos on the router: sealed with the class's token, so only its server trusts them."""

    def __init__(
        self,
        session: Any,
        settings: WorkerSettings,
        describe: Callable[[], dict[str, Any]],
        on_hello: Callable[[], None],
    ) -> None:
        self._describe = describe
        self._on_hello = on_hello
        self._settings = settings
        self._queryable = session.declare_queryable(control_key(settings.id), self._on_query, complete=True)

    def _on_query(self, query: Any) -> None:  # Zenoh's thread: answer at once, block nothing
        try:
            raw = query.payload.to_bytes() if query.payload is not None else b""
            nonce = genuine_hello(self._settings.class_token, raw)
            if nonce is None:
                return  # not this class's server: no answer (the querier's timeout ends it)
            self._on_hello()
            body = {**self._describe(), "id": self._settings.id, "url": self._settings.url, "nonce": nonce}
            query.reply(control_key(self._settings.id), seal(self._settings.class_token, body))
        finally:
            query.drop()

    def close(self) -> None:
        self._queryable.undeclare()
