"""Who may connect: a Host header that names this machine, no Origin of another site, a bearer
token compared in constant time, a path as sent that no normaliser would change.

The rules of the app's guard (api/middleware/guard.py), of its routes' token checks (api/deps.py) and of
the bridges' guarded fronts (server/services/bridges/front.py) alike, so every door of the lab answers the
same request the same way. Standard library only: both the web layer and the bridges import it.
"""

from __future__ import annotations

import hmac
import re
from collections.abc import Iterable
from urllib.parse import urlsplit


def _host_name(host_header: str) -> str:
    host = host_header.strip().lower()
    if host.startswith("["):  # [::1]:8000
        return host[1:].split("]", 1)[0]
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def host_allowed(host_header: str | None, accepted: Iterable[str]) -> bool:
    return host_header is not None and _host_name(host_header) in set(accepted)


def origin_allowed(origin: str | None, host_header: str | None, allowed_origins: Iterable[str]) -> bool:
    """No Origin (a non-browser client) or the page's own origin; anything else must be listed."""
    if origin is None:
        return True
    if origin in set(allowed_origins):
        return True
    parts = urlsplit(origin)
    if parts.scheme not in ("http", "https") or not parts.netloc or host_header is None:
        return False
    return parts.netloc.lower() == host_header.strip().lower()


def bearer_token(authorization: str | None) -> str | None:
    """The token of an ``Authorization: Bearer TOKEN`` header, else None."""
    auth = authorization or ""
    return auth[7:].strip() if auth[:7].lower() == "bearer " else None


def token_matches(given: str | None, expected: str) -> bool:
    """Compared in constant time, so the answer's timing tells nothing of the token."""
    return given is not None and hmac.compare_digest(given.encode(), expected.encode())


# Percent-encodings a normaliser decodes into something that changes the path's segments:
# %2e '.' (then a dot segment), %2f '/' and %5c '\' (a separator to some servers).
_ENCODED = re.compile(rb"%(2e|2f|5c)", re.IGNORECASE)
_CONTROL = re.compile(rb"[\x00-\x20\x7f]")


def path_problem(raw_path: bytes) -> str | None:
    """What in a request's path (as sent, before decoding) a normaliser would change; None if nothing."""
    if not raw_path.startswith(b"/"):
        return "the path must start with /"
    if b"\\" in raw_path:
        return "a backslash in the path"
    if _CONTROL.search(raw_path):
        return "a space or control character in the path"
    if (encoded := _ENCODED.search(raw_path)) is not None:
        return f"a percent-encoded {encoded.group(0).decode('ascii')!r} in the path"
    segments = raw_path.split(b"/")[1:]
    if any(segment in (b".", b"..") for segment in segments):
        return "a dot segment (. or ..) in the path"
    if any(not segment for segment in segments[:-1]):
        return "an empty segment (//) in the path"
    return None
