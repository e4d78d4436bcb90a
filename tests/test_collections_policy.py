"""server/base/collections_policy.py: what survives a full collection is frozen, so later ones skip it;
what dies while frozen is collected once the frozen objects are given back."""

from __future__ import annotations

import gc
import weakref
from collections.abc import Iterator

import pytest

from server.base.collections_policy import FreezeAfterFullCollections, keep_full_collections_short


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


class Linked:
    """An object in a reference cycle: only a garbage collection frees it, never its refcount."""

    def __init__(self) -> None:
        self.me = self


@pytest.fixture
def policy() -> Iterator[tuple[FreezeAfterFullCollections, Clock]]:
    clock = Clock()
    installed = FreezeAfterFullCollections(thaw_after_s=60.0, clock=clock)
    gc.callbacks.append(installed)
    try:
        yield installed, clock
    finally:
        gc.callbacks.remove(installed)
        gc.unfreeze()  # what the test froze goes back to the collector


def test_a_full_collection_freezes_what_survived_it(policy: tuple[FreezeAfterFullCollections, Clock]) -> None:
    installed, _clock = policy
    assert installed.frozen_at is None
    kept = Linked()
    gc.collect()  # a full collection: what is alive now is frozen after it
    assert gc.get_freeze_count() > 0
    assert installed.frozen_at == 0.0
    # The collector's walks skip it now: nothing frozen is searched for its referrers, its own
    # cycle included; given back, its cycle is found again.
    assert not gc.get_referrers(kept)
    gc.unfreeze()
    assert gc.get_referrers(kept)


def test_a_cycle_that_dies_while_frozen_is_collected_once_thawed(
    policy: tuple[FreezeAfterFullCollections, Clock],
) -> None:
    installed, clock = policy
    doomed = Linked()
    alive = weakref.ref(doomed)
    gc.collect()  # frozen with everything else alive
    del doomed
    gc.collect()  # frozen: no collection reaches it, though nothing refers to it but itself
    assert alive() is not None

    clock.now = 59.0
    gc.collect(0)  # a young collection before the thaw time gives nothing back
    assert installed.frozen_at is not None and gc.get_freeze_count() > 0
    gc.collect()
    assert alive() is not None

    clock.now = installed.frozen_at + 60.0
    gc.collect(0)  # the first collection after thaw_after_s gives the frozen objects back
    assert installed.frozen_at is None and gc.get_freeze_count() == 0
    gc.collect()  # the next full collection takes it, and freezes what still lives
    assert alive() is None
    assert gc.get_freeze_count() > 0


def test_the_policy_is_installed_once_and_refuses_a_thaw_time_of_zero() -> None:
    with pytest.raises(ValueError, match="thaw_after_s"):
        FreezeAfterFullCollections(thaw_after_s=0.0)
    before = list(gc.callbacks)
    try:
        first = keep_full_collections_short()
        assert keep_full_collections_short() is first
        assert [c for c in gc.callbacks if isinstance(c, FreezeAfterFullCollections)] == [first]
    finally:
        gc.callbacks[:] = before
        gc.unfreeze()
