"""Worlds that start, or the class's router opening again (class_router.py): never both at once.

A world's graph joins the router as the world starts; if the router were closed for a reopening
at that moment, the world would start off Zenoh. So starting worlds hold the gate together, and a
reopening waits until none does (new ones wait behind it, so a stream of joins cannot hold it off).
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator


class RouterGate:
    """Worlds that start (their sessions must find the router open) or one reopening of the
    router, never both at once; a reopening that waits goes before worlds that come after it."""

    def __init__(self) -> None:
        self._changed = asyncio.Condition()
        self._users = 0
        self._reopening = False
        self._waiting = 0  # reopenings waiting for the worlds that start to be done

    @contextlib.asynccontextmanager
    async def use(self) -> AsyncIterator[None]:
        async with self._changed:
            await self._changed.wait_for(lambda: not self._reopening and not self._waiting)
            self._users += 1
        try:
            yield
        finally:
            async with self._changed:
                self._users -= 1
                self._changed.notify_all()

    @contextlib.asynccontextmanager
    async def reopening(self) -> AsyncIterator[None]:
        async with self._changed:
            self._waiting += 1
            try:
                await self._changed.wait_for(lambda: not self._reopening and not self._users)
            finally:
                self._waiting -= 1
                self._changed.notify_all()  # a reopening given up no longer holds worlds back
            self._reopening = True
        try:
            yield
        finally:
            async with self._changed:
                self._reopening = False
                self._changed.notify_all()
