"""What the CLI reports as one line: its errors, and an error answer of the lab read into one
(from its status, headers and body alone, so an answer read off a plain socket is read the same
as httpx's: server/cli/plain_get.py)."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any, Protocol

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


class Headers(Protocol):
    """An answer's headers, read by name whatever its case (httpx's, or ``plain_get``'s)."""

    def get(self, key: str, /) -> str | None: ...


def api_error(status: int, reason: str, headers: Headers, body: bytes, method: str, path: str) -> ApiError:
    """The lab's error answer as an ``ApiError``: its ``detail``, and the wait and ticket a 429 or
    503 gives (``Retry-After-Ms`` over ``Retry-After``; ``Start-Turn``)."""
    try:
        detail = describe_detail(json.loads(body).get("detail", body.decode(errors="replace")))
    except (ValueError, AttributeError):
        detail = body.decode(errors="replace").strip() or reason
    retry_after = wait_s(headers.get("Retry-After"))  # an HTTP date instead of seconds: none
    precise_ms = wait_s(headers.get("Retry-After-Ms"))  # the lab's own, to the millisecond
    if precise_ms is not None:
        retry_after = precise_ms / 1000
    return ApiError(status, detail, method, path, retry_after, headers.get("Start-Turn"))


def wait_s(header: str | None) -> float | None:
    """A header's number of seconds (or milliseconds) to wait; None where it holds none (not a
    number, NaN, infinite or negative)."""
    try:
        value = float(header or "")
    except ValueError:
        return None
    return value if math.isfinite(value) and value >= 0 else None
