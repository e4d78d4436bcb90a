"""Which exceptions out of node code are that node's fault (it crashes, the graph runs on)."""

from __future__ import annotations

import signal
import sys


def is_node_fault(exc: BaseException) -> bool:
    """Every ``Exception``, and ``SystemExit`` (a node's ``sys.exit()`` ends that node, never the
    server). ``KeyboardInterrupt`` is a real Ctrl-C only while Python's own SIGINT handler is
    installed; a server (uvicorn) installs its own, so there one raised in a callback came from
    node code. ``CancelledError`` cannot reach a plain callback from outside either."""
    if isinstance(exc, Exception | SystemExit):
        return True
    asyncio = sys.modules.get("asyncio")  # not imported: no CancelledError exists (a node process)
    if asyncio is not None and isinstance(exc, asyncio.CancelledError):
        return True
    if isinstance(exc, KeyboardInterrupt):
        return signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    return False
