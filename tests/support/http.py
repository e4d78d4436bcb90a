"""One HTTP client for the tests' calls to the servers they start.

``httpx.get`` and its siblings build a new client for every call, and with it a TLS context: about
55 ms of CPU each, against 4 ms through a client that is kept (2-vCPU AMD EPYC). A test that polls a
server ten times a second that way kept most of a core busy, beside the very server it waits for.

The client keeps connections, never cookies: every call sends only what the test gives it, as a
new client would (a cookie a server sets must not reach the next call, or a test of who may do
what would pass on a cookie it never sent). A connection idle for a second is not used again: a
server (uvicorn) closes an idle one after 5 s, and a call that took one just then would fail.
"""

from __future__ import annotations

import atexit
from http.cookiejar import CookieJar, DefaultCookiePolicy

import httpx

HTTP = httpx.Client(
    cookies=CookieJar(policy=DefaultCookiePolicy(allowed_domains=[])),
    limits=httpx.Limits(keepalive_expiry=1.0),
    timeout=5.0,
)
atexit.register(HTTP.close)
