"""The lab server's HTTP and WebSocket API as the CLI sees it, with its failures as one-line errors."""

from __future__ import annotations

import json
import math
import os
import threading
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self
from urllib.parse import urlencode, urlsplit, urlunsplit

import httpx

from server.cli.environment import TOKEN_ENV

if TYPE_CHECKING:
    from websockets.exceptions import ConnectionClosed

TIMEOUT_S = 10.0
# The app's close code for "not found", here an unknown topic (api.errors.CloseCode.NOT_FOUND; a test keeps them equal).
CLOSE_NOT_FOUND = 4404
# What FastAPI answers for a path no route serves: an older server than this CLI.
NO_ROUTE_DETAIL = "Not Found"


class CliError(Exception):
    """A failure the CLI reports as one line on stderr, then exits with ``exit_code``."""

    exit_code = 1


class NoServerError(CliError):
    """Nothing listens at the URL (connection refused, unknown host)."""

    exit_code = 2

    def __init__(self, url: str) -> None:
        super().__init__(f"no lab server at {url} (start it with: bash scripts/run.sh)")


class ApiError(CliError):
    """The server answered with an error status; ``detail`` is its explanation."""

    def __init__(
        self,
        status: int,
        detail: str,
        method: str,
        path: str,
        retry_after_s: float | None = None,
        turn: str | None = None,
    ) -> None:
        self.status, self.detail, self.method, self.path = status, detail, method, path
        # The server's Retry-After (429, 503), in seconds (from Retry-After-Ms where it gave one).
        self.retry_after_s = retry_after_s
        self.turn = turn  # a paced start's ticket (Start-Turn): asked again with, its turn is kept
        if self.no_route:
            super().__init__(
                f"{method} {path}: HTTP 404: the server has no such endpoint (older than this CLI?)"
            )
        elif status in (404, 409, 422):
            super().__init__(detail)
        else:
            super().__init__(f"{method} {path}: HTTP {status}: {detail}")

    @property
    def no_route(self) -> bool:
        """True when the server has no such endpoint at all (as opposed to no such topic or node)."""
        return self.status == 404 and self.detail == NO_ROUTE_DETAIL


class UnknownTopicError(CliError):
    """The echo channel was closed because the topic does not exist (and no type was given)."""


def describe_detail(detail: Any) -> str:
    """FastAPI's ``detail``: a string, or a list of validation errors with ``loc`` and ``msg``."""
    if isinstance(detail, list):
        parts = []
        for item in detail:
            if isinstance(item, Mapping):
                loc = ".".join(str(p) for p in item.get("loc", ()) if p != "body")
                parts.append(f"{loc}: {item.get('msg', '')}" if loc else str(item.get("msg", "")))
            else:
                parts.append(str(item))
        return "; ".join(parts)
    return str(detail)


class LabClient:
    """A session with one lab server. ``transport`` lets tests answer without a server."""

    def __init__(self, base_url: str, transport: httpx.BaseTransport | None = None) -> None:
        self.base_url = base_url.rstrip("/")
        # A lab behind --token, or a student's world on a class server: ROS2LAB_TOKEN carries it.
        token = os.environ.get(TOKEN_ENV)
        self._headers = {"Authorization": f"Bearer {token}"} if token else {}
        self._http = httpx.Client(
            base_url=self.base_url, timeout=TIMEOUT_S, transport=transport, headers=self._headers
        )

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()

    def close(self) -> None:
        self._http.close()

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
            with connect(url, open_timeout=TIMEOUT_S, max_size=None, additional_headers=self._headers) as ws:
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
    try:
        detail = describe_detail(response.json().get("detail", response.text))
    except (ValueError, AttributeError):
        detail = response.text.strip() or response.reason_phrase
    retry_after = _wait_s(response.headers.get("Retry-After"))  # an HTTP date instead of seconds: none
    precise_ms = _wait_s(response.headers.get("Retry-After-Ms"))  # the lab's own, to the millisecond
    if precise_ms is not None:
        retry_after = precise_ms / 1000
    return ApiError(
        response.status_code, detail, method, path, retry_after, response.headers.get("Start-Turn")
    )


def _wait_s(header: str | None) -> float | None:
    """A header's number of seconds (or milliseconds) to wait; None where it holds none (not a
    number, NaN, infinite or negative)."""
    try:
        value = float(header or "")
    except ValueError:
        return None
    return value if math.isfinite(value) and value >= 0 else None


def _closed_error(exc: ConnectionClosed, topic: str) -> CliError:
    if exc.rcvd is None:
        return CliError("lost the connection to the lab server")
    if exc.rcvd.code == CLOSE_NOT_FOUND:
        return UnknownTopicError(exc.rcvd.reason or f"unknown topic {topic}")
    return CliError(f"the lab server closed the echo channel: {exc.rcvd.reason or exc.rcvd.code}")
