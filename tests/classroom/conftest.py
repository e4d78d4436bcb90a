"""Fixtures of the class tests that measure rates."""

from __future__ import annotations

from collections.abc import Iterator

import httpx
import pytest


@pytest.fixture(scope="module")
def reader() -> Iterator[httpx.Client]:
    """One client, its connections kept, for every reading a timing test takes while it measures:
    ``httpx.get`` builds a new client, and with it a TLS context, for every call (about 55 ms of the
    test's own CPU against 4 ms through one client), which the worlds measured would pay for."""
    with httpx.Client(timeout=10) as client:
        yield client
