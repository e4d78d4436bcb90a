"""The one bounded wait of the tests: look again a little later until a condition holds.

For state that another thread or process changes and that offers nothing to await (a server in a
subprocess, an app in TestClient's event-loop thread, a Zenoh callback). Tests of the bus itself
step a ManualClock instead; this is for the real clock only.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TypeVar

import pytest

T = TypeVar("T")
WAIT_S = 10.0  # generous: a loaded 2-core CI machine; a passing wait returns as soon as it can
POLL_S = 0.02


def wait_until(
    check: Callable[[], T],
    what: str,
    timeout_s: float = WAIT_S,
    *,
    poll_s: float = POLL_S,
    detail: Callable[[], str] | None = None,
) -> T:
    """Call ``check`` until it returns something truthy, and return that.

    The test fails after ``timeout_s`` naming ``what``, the last value seen and, when given,
    ``detail()`` (a server's log tail, say)."""
    deadline = time.monotonic() + timeout_s
    while not (value := check()):
        if time.monotonic() > deadline:
            more = f"\n{detail()}" if detail is not None else ""
            pytest.fail(f"gave up after {timeout_s} s waiting for {what} (last: {value!r}){more}")
        time.sleep(poll_s)
    return value
