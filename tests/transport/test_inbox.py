"""The inbox from Zenoh's threads to the executor, on its own: a take bounded in events leaves the
rest queued and the inbox pending, and the executor is woken once per empty-to-queued."""

from __future__ import annotations

from node_runtime.transport.inbox import Inbox


def test_a_bounded_take_leaves_the_rest_for_the_next_pass() -> None:
    wakes: list[None] = []
    inbox = Inbox(lambda: wakes.append(None))
    for i in range(5):
        inbox.post(("token", f"k{i}", True))
    inbox.put_sample("/chatter", b"one", keep=2)
    assert len(wakes) == 1  # woken once, when the inbox went from empty to queued
    events, samples = inbox.take(max_events=2)
    assert [e[1] for e in events] == ["k0", "k1"]
    assert samples == {"/chatter": [b"one"]}  # samples are taken whole: each topic's are bounded
    assert inbox.left() == 3
    inbox.post(("token", "k5", True))
    assert len(wakes) == 1  # still pending: no second wake, the taker asks for its next pass
    events, samples = inbox.take(max_events=2)
    assert [e[1] for e in events] == ["k2", "k3"] and samples == {}
    events, _ = inbox.take()
    assert [e[1] for e in events] == ["k4", "k5"]
    assert inbox.left() == 0 and inbox.take() == ([], {})
    inbox.post(("token", "k6", True))
    assert len(wakes) == 2  # empty, then queued again: woken again
