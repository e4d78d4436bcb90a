"""A lab's budget of WebSocket frames (node_runtime/limits.py ``RateLimit``), spent frame by frame.

A socket over its lab's budget waits for its turn instead of sending (or reading) more, so
however many sockets a class world opens, together they cost the shared event loop no more than
the world's budget; what waits meanwhile is bounded by each socket's own queue. The sockets
waiting on one budget queue behind one lock, so only one of them at a time sleeps until the next
frame is due: waiting costs a wake-up per frame, not one per socket.
"""

from __future__ import annotations

import asyncio
import weakref

from node_runtime.limits import RateLimit

MIN_WAIT_S = 0.001
_turns: weakref.WeakKeyDictionary[RateLimit, asyncio.Lock] = weakref.WeakKeyDictionary()


async def spend(budget: RateLimit | None) -> None:
    """One frame's place in ``budget``, waiting for it if needed (at once without a budget)."""
    if budget is None or budget.take():
        return
    turn = _turns.get(budget)
    if turn is None:
        turn = _turns[budget] = asyncio.Lock()
    async with turn:
        # A bucket refills with time, not on an event: the wait is until its next token is due.
        while not budget.take():  # noqa: ASYNC110
            await asyncio.sleep(max(budget.retry_after_s(), MIN_WAIT_S))
