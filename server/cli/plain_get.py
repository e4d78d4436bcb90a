"""A GET to the lab over a plain socket, as ``ros2lab run`` asks its join and its workspace: the
lab's answer or one of the CLI's errors, as ``LabClient.get`` gives them.

Why not an HTTP library here: a class's "run it now" starts sixty ``ros2lab run`` at once, and
until each has asked the lab for its turn, all sixty share the CPU and none has asked. httpx took
0.15 CPU-s to import (its own command line's rich and click with it); the standard library's
``http.client`` 0.02, most of it the email package it parses headers with and ``ssl``, against
0.03 for the whole interpreter. What is asked here is one HTTP/1.0 GET whose answer ends when
the lab closes the connection (no chunks, no keep-alive, no redirects), which a socket does. Only
``http://``: a lab behind TLS is asked through ``LabClient`` (httpx), with its certificates.
"""

from __future__ import annotations

import json
import socket
import time
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Protocol
from urllib.parse import urlencode, urlsplit

from server.cli.errors import CliError, NoServerError, api_error

if TYPE_CHECKING:
    from server.cli.client import LabClient

TIMEOUT_S = 10.0  # as LabClient's
MAX_ANSWER_BYTES = 4 * 1024 * 1024  # a join or a workspace answer is a few hundred bytes
CHUNK_BYTES = 65536


class LabGetter(Protocol):
    """What asks the lab a GET: ``LabClient``, or a ``PlainGet`` for an ``http://`` lab."""

    base_url: str

    def get(
        self, path: str, params: Mapping[str, Any] | None = None, timeout_s: float | None = None
    ) -> Any: ...


class AnswerHeaders:
    """An answer's headers, read by name whatever its case (the last of a repeated one)."""

    def __init__(self, lines: list[str]) -> None:
        self._by_name: dict[str, str] = {}
        for line in lines:
            name, colon, value = line.partition(":")
            if colon:
                self._by_name[name.strip().lower()] = value.strip()

    def get(self, key: str, /) -> str | None:
        return self._by_name.get(key.lower())


class PlainGet:
    """GETs to the lab at ``base_url`` (``http://`` only) with ``headers`` (its token)."""

    def __init__(self, base_url: str, headers: Mapping[str, str]) -> None:
        parts = urlsplit(base_url)
        if parts.scheme != "http" or not parts.hostname:
            raise ValueError(f"a plain GET asks an http:// lab, not {base_url!r}")
        for name, value in headers.items():  # what would end the request's headers early
            if any(c in f"{name}{value}" for c in "\r\n\0") or ":" in name:
                raise CliError(f"the {name} header holds what no HTTP header may (a line break?)")
        self.base_url = base_url.rstrip("/")
        self._host, self._port, self._prefix = parts.hostname, parts.port or 80, parts.path.rstrip("/")
        host = f"[{self._host}]" if ":" in self._host else self._host
        self._head = "".join(
            f"{name}: {value}\r\n"
            for name, value in {
                "Host": f"{host}:{self._port}",
                "Accept": "application/json",
                **headers,
            }.items()
        )

    def get(self, path: str, params: Mapping[str, Any] | None = None, timeout_s: float | None = None) -> Any:
        target = self._prefix + path + (f"?{urlencode(dict(params))}" if params else "")
        request = f"GET {target} HTTP/1.0\r\n{self._head}Connection: close\r\n\r\n".encode()
        deadline = time.monotonic() + (timeout_s or TIMEOUT_S)
        try:
            raw = self._exchange(request, deadline)
        except (ConnectionRefusedError, socket.gaierror):
            raise NoServerError(self.base_url) from None
        except TimeoutError:
            raise CliError(f"GET {path}: ReadTimeout: the lab did not answer in time") from None
        except OSError as exc:  # a connection dropped without an answer
            raise CliError(f"GET {path}: {type(exc).__name__}: {exc}") from None
        status, reason, headers, body = _answer(raw, path)
        if 200 <= status < 300:
            return json.loads(body) if body else None
        raise api_error(status, reason, headers, body, "GET", path)

    def _exchange(self, request: bytes, deadline: float) -> bytes:
        """Send ``request``, then read until the lab closes: the whole answer, by ``deadline``."""
        left = deadline - time.monotonic()
        with socket.create_connection((self._host, self._port), timeout=max(0.001, left)) as sock:
            sock.sendall(request)
            received = bytearray()
            while True:
                left = deadline - time.monotonic()
                if left <= 0:
                    raise TimeoutError
                sock.settimeout(left)
                chunk = sock.recv(CHUNK_BYTES)
                if not chunk:
                    return bytes(received)
                received += chunk
                if len(received) > MAX_ANSWER_BYTES:
                    raise OSError(f"an answer over {MAX_ANSWER_BYTES} bytes")


def _answer(raw: bytes, path: str) -> tuple[int, str, AnswerHeaders, bytes]:
    """Status, reason, headers and body of a whole HTTP/1.x answer; CliError for anything else."""
    head, blank, body = raw.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    version, _, rest = lines[0].partition(" ")
    code, _, reason = rest.partition(" ")
    if not blank or not version.startswith("HTTP/1.") or not (code.isdigit() and len(code) == 3):
        raise CliError(f"GET {path}: RemoteProtocolError: not an HTTP answer")
    return int(code), reason, AnswerHeaders(lines[1:]), body


def getter_for(client: LabClient) -> LabGetter:
    """A ``PlainGet`` with ``client``'s URL and token for an ``http://`` lab, else ``client``."""
    if urlsplit(client.base_url).scheme == "http":
        return PlainGet(client.base_url, client.headers)
    return client
