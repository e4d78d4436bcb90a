"""Python's full garbage collections kept short in a server that runs for hours.

A full collection (generation 2) walks every object Python tracks. A class server's worlds hold
hundreds of thousands of them, so one took 100 to 450 ms of the loop thread, and every world's
timers waited behind it: 15 fly worlds on one process lost about 2 % of their 100 Hz dynamics ticks
that way (2-vCPU AMD EPYC; with collections off they kept 99.95 Hz).

What survives a full collection is nearly all long-lived (the worlds, their nodes, the messages a
topic keeps), so it is frozen right after one (``gc.freeze``): the next full collections walk only
what came since, and take a few milliseconds. A frozen object is never collected, so what dies
after it was frozen (a world removed, a node ended, a closed socket's state) would stay if it is part
of a cycle. So the frozen objects are given back (``gc.unfreeze``) once they have been frozen for
``thaw_after_s``: the next full collection takes whatever of them died and freezes the rest again.
One long walk every ``thaw_after_s`` instead of one every few seconds to minutes.
"""

from __future__ import annotations

import gc
import time
from collections.abc import Callable
from typing import Any

THAW_AFTER_S = 600.0


class FreezeAfterFullCollections:
    """A ``gc.callbacks`` entry: freezes after each full collection, gives the frozen objects back
    on the first collection after ``thaw_after_s``; ``clock`` is monotonic seconds."""

    def __init__(
        self, thaw_after_s: float = THAW_AFTER_S, clock: Callable[[], float] = time.monotonic
    ) -> None:
        if not thaw_after_s > 0:
            raise ValueError(f"thaw_after_s must be positive, got {thaw_after_s!r}")
        self.thaw_after_s = thaw_after_s
        self.clock = clock
        self.frozen_at: float | None = None

    def __call__(self, phase: str, info: dict[str, Any]) -> None:
        if phase != "stop":
            return
        if info.get("generation") == 2:
            gc.freeze()  # what survived a full collection: long-lived, or garbage no walk can find
            self.frozen_at = self.clock()
        elif self.frozen_at is not None and self.clock() - self.frozen_at >= self.thaw_after_s:
            gc.unfreeze()  # the next full collection takes what of it died since
            self.frozen_at = None


def keep_full_collections_short(
    policy: FreezeAfterFullCollections | None = None,
) -> FreezeAfterFullCollections:
    """Install ``policy`` (a new one by default) in this process, once; returns the one installed."""
    for callback in gc.callbacks:
        if isinstance(callback, FreezeAfterFullCollections):
            return callback
    installed = policy if policy is not None else FreezeAfterFullCollections()
    gc.callbacks.append(installed)
    return installed
