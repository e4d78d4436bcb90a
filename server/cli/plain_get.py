"""A GET to the lab with the standard library alone, as ``ros2lab run`` asks its join and its
workspace: the lab's answer or one of the CLI's errors, as ``LabClient.get`` gives them.

Why not httpx here: a class's "run it now" starts sixty ``ros2lab run`` at once, and each spent
about 0.25 CPU-s before it asked the lab for its turn, 0.15 of them importing httpx (and, through
it, its own command line's rich and click). Sixty of them then imported at once and took their
turns late; ``http.client`` is most of the way in with the interpreter. Only ``http://``: a lab
behind TLS is asked through ``LabClient`` (httpx), with its certificates as before.
"""

from __future__ import annotations

import http.client
import json
import socket
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Protocol
from urllib.parse import urlencode, urlsplit

from server.cli.errors import CliError, NoServerError, api_error

if TYPE_CHECKING:
    from server.cli.client import LabClient

TIMEOUT_S = 10.0  # as LabClient's


class LabGetter(Protocol):
    """What asks the lab a GET: ``LabClient``, or a ``PlainGet`` for an ``http://`` lab."""

    base_url: str

    def get(
        self, path: str, params: Mapping[str, Any] | None = None, timeout_s: float | None = None
    ) -> Any: ...


class PlainGet:
    """GETs to the lab at ``base_url`` (``http://`` only) with ``headers`` (its token)."""

    def __init__(self, base_url: str, headers: Mapping[str, str]) -> None:
        parts = urlsplit(base_url)
        if parts.scheme != "http" or not parts.hostname:
            raise ValueError(f"a plain GET asks an http:// lab, not {base_url!r}")
        self.base_url = base_url.rstrip("/")
        self._host, self._port, self._prefix = parts.hostname, parts.port or 80, parts.path.rstrip("/")
        self._headers = {"Accept": "application/json", **headers}

    def get(self, path: str, params: Mapping[str, Any] | None = None, timeout_s: float | None = None) -> Any:
        target = self._prefix + path + (f"?{urlencode(dict(params))}" if params else "")
        connection = http.client.HTTPConnection(self._host, self._port, timeout=timeout_s or TIMEOUT_S)
        try:
            connection.request("GET", target, headers=self._headers)
            response = connection.getresponse()
            body = response.read()
        except (ConnectionRefusedError, socket.gaierror):
            raise NoServerError(self.base_url) from None
        except TimeoutError:
            raise CliError(f"GET {path}: ReadTimeout: the lab did not answer in time") from None
        except (OSError, http.client.HTTPException) as exc:  # a connection dropped without an answer
            raise CliError(f"GET {path}: {type(exc).__name__}: {exc}") from None
        finally:
            connection.close()
        if 200 <= response.status < 300:
            return json.loads(body) if body else None
        raise api_error(response.status, response.reason, response.headers, body, "GET", path)


def getter_for(client: LabClient) -> LabGetter:
    """A ``PlainGet`` with ``client``'s URL and token for an ``http://`` lab, else ``client``."""
    if urlsplit(client.base_url).scheme == "http":
        return PlainGet(client.base_url, client.headers)
    return client
