"""The lab server's HTTP and WebSocket API as the CLI sees it, with its failures as one-line errors
(server/cli/errors.py).

httpx is imported at the first request, not with this module: ``ros2lab run`` asks the lab for
its turn over a plain socket (server/cli/plain_get.py), and httpx's import was most
of what it spent before it asked.
"""

from __future__ import annotations

import json
import os
import threading
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self
from urllib.parse import urlencode, urlsplit, urlunsplit

from server.cli.environment import TOKEN_ENV
from server.cli.errors import ApiError, CliError, NoServerError, UnknownTopicError, api_error, describe_detail

if TYPE_CHECKING:
    import httpx
    from websockets.exceptions import ConnectionClosed

__all__ = [
    "ApiError",
    "CliError",
    "LabClient",
    "NoServerError",
    "UnknownTopicError",
    "describe_detail",
]

TIMEOUT_S = 10.0
# The app's close code for "not found", here an unknown topic (api.errors.CloseCode.NOT_FOUND; a test keeps them equal).
CLOSE_NOT_FOUND = 4404


class LabClient:
    """A session with one lab server. ``transport`` lets tests answer without a server."""

    def __init__(self, base_url: str, transport: httpx.BaseTransport | None = None) -> None:
        self.base_url = base_url.rstrip("/")
        # A lab behind --token, or a student's world on a class server: ROS2LAB_TOKEN carries it.
        token = os.environ.get(TOKEN_ENV)
        self.headers = {"Authorization": f"Bearer {token}"} if token else {}
        self._transport = transport
        self._client: httpx.Client | None = None

    @property
    def _http(self) -> httpx.Client:
        if self._client is None:
            import httpx

            self._client = httpx.Client(
                base_url=self.base_url, timeout=TIMEOUT_S, transport=self._transport, headers=self.headers
            )
        return self._client

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()

    def close(self) -> None:
        if self._client is not None:
            self._client.close()

    def get(self, path: str, params: Mapping[str, Any] | None = None, timeout_s: float | None = None) -> Any:
        extra = {"timeout": timeout_s} if timeout_s is not None else {}
        return self._request("GET", path, params=dict(params or {}), **extra)

    def post(self, path: str, body: Mapping[str, Any], timeout_s: float | None = None) -> Any:
        """``timeout_s`` for a request the server itself may take a while to answer (a service call)."""
        extra = {"timeout": timeout_s} if timeout_s is not None else {}
        return self._request("POST", path, json=dict(body), **extra)

    def post_file(self, path: str, data: bytes) -> Any:
        """POST ``data`` as it is (a file's bytes, not JSON)."""
        return self._request("POST", path, content=data, headers={"content-type": "application/octet-stream"})

    def delete(self, path: str) -> Any:
        return self._request("DELETE", path)

    def download(self, path: str, dest: Path) -> int:
        """GET ``path`` into the file ``dest``, streamed; returns the bytes written."""
        import httpx

        written = 0
        try:
            with self._http.stream("GET", path) as response:
                if not response.is_success:
                    response.read()
                    raise _api_error(response, "GET", path)
                with dest.open("wb") as out:
                    for chunk in response.iter_bytes():
                        written += out.write(chunk)
        except httpx.ConnectError:
            raise NoServerError(self.base_url) from None
        except httpx.HTTPError as exc:
            raise CliError(f"GET {path}: {type(exc).__name__}: {exc}") from None
        return written

    def _request(self, method: str, path: str, **kwargs: Any) -> Any:
        import httpx

        try:
            response = self._http.request(method, path, **kwargs)
        except httpx.ConnectError:
            raise NoServerError(self.base_url) from None
        except httpx.HTTPError as exc:
            raise CliError(f"{method} {path}: {type(exc).__name__}: {exc}") from None
        if response.is_success:
            return response.json() if response.content else None
        raise _api_error(response, method, path)

    def ws_url(self, path: str, params: Mapping[str, Any]) -> str:
        parts = urlsplit(self.base_url)
        scheme = "wss" if parts.scheme == "https" else "ws"
        return urlunsplit((scheme, parts.netloc, parts.path + path, urlencode(params), ""))

    def subscribe(
        self, topic: str, params: Mapping[str, Any], opened: threading.Event | None = None
    ) -> Iterator[dict[str, Any]]:
        """Frames ``{topic, type, msg, received}`` of ``WS /ws/topics/{topic}``, as they come;
        ``opened`` is set once the server accepted the socket (it subscribes as it accepts)."""
        # Only the echo verbs open a socket: the others (a node's start among them) skip the import.
        from websockets.exceptions import ConnectionClosed, InvalidHandshake, InvalidStatus
        from websockets.sync.client import connect

        url = self.ws_url("/ws/topics/" + topic.lstrip("/"), params)
        try:
            with connect(url, open_timeout=TIMEOUT_S, max_size=None, additional_headers=self.headers) as ws:
                if opened is not None:
                    opened.set()
                for frame in ws:
                    yield json.loads(frame)
        except ConnectionClosed as exc:
            raise _closed_error(exc, topic) from None
        except InvalidStatus as exc:
            raise CliError(
                f"the lab server refused the echo channel: HTTP {exc.response.status_code}"
            ) from None
        except InvalidHandshake as exc:
            raise CliError(f"the lab server refused the echo channel: {exc}") from None
        except OSError:
            raise NoServerError(self.base_url) from None
        raise CliError("the lab server closed the echo channel (is it shutting down?)")


def _api_error(response: httpx.Response, method: str, path: str) -> ApiError:
    return api_error(
        response.status_code, response.reason_phrase, response.headers, response.content, method, path
    )


def _closed_error(exc: ConnectionClosed, topic: str) -> CliError:
    if exc.rcvd is None:
        return CliError("lost the connection to the lab server")
    if exc.rcvd.code == CLOSE_NOT_FOUND:
        return UnknownTopicError(exc.rcvd.reason or f"unknown topic {topic}")
    return CliError(f"the lab server closed the echo channel: {exc.rcvd.reason or exc.rcvd.code}")
