"""Node starts yield to the worlds' ticks (server/host/processes/start_pacing.py): while the
worlds skip more than ``SKIPPED_OK`` of their timers' calls, the turns after each start move back,
up to ``MAX_STRETCH`` times as far apart; a machine's processes share what they skipped. On a
manual clock: a burst of starts told their turns at once, each back with its ticket at its turn,
as the page's Run does."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import pytest

from node_runtime.bus import ManualClock
from server.host.processes.start_pacing import (
    MAX_STRETCH,
    NEW_TURN,
    SKIPPED_FRESH_S,
    SKIPPED_MOST,
    SKIPPED_OK,
    MachineStartPacer,
    StartPacer,
    stretch,
)

HOLD_S = 0.75


class Share:
    """What the worlds skipped, as a test sets it."""

    def __init__(self, value: float = 0.0) -> None:
        self.value = value

    def __call__(self) -> float:
        return self.value


def burst(pacer: StartPacer, clock: ManualClock, count: int) -> list[float]:
    """``count`` starts of as many worlds asked for at once, each back with its ticket whenever it
    is told to come: when each went."""
    went: list[float] = []
    waiting: list[tuple[float, str | None, str]] = []
    for i in range(count):
        turn = pacer.admit(NEW_TURN, f"w{i}")
        if turn is None:
            went.append(clock.now())
        else:
            waiting.append((clock.now() + turn.wait_s, turn.ticket, f"w{i}"))
    for _ in range(10 * count):  # bounded: each start comes back a few times at most
        if not waiting:
            break
        waiting.sort(key=lambda w: w[0])
        at, ticket, who = waiting.pop(0)
        clock.set(max(clock.now(), at))
        again = pacer.admit(ticket or NEW_TURN, who)
        if again is None:
            went.append(clock.now())
        else:
            waiting.append((clock.now() + again.wait_s, again.ticket, who))
    assert not waiting
    return went


def test_stretch_rises_from_the_share_that_is_fine_to_the_most() -> None:
    assert stretch(0.0) == stretch(SKIPPED_OK) == 1.0
    assert stretch((SKIPPED_OK + SKIPPED_MOST) / 2) == pytest.approx((1.0 + MAX_STRETCH) / 2)
    assert stretch(SKIPPED_MOST) == stretch(1.0) == pytest.approx(MAX_STRETCH)
    assert stretch(math.nan) == 1.0  # a reading that says nothing slows nothing


def test_worlds_that_keep_their_ticks_start_at_the_full_pace() -> None:
    clock = ManualClock(100.0)
    pacer = StartPacer(1, HOLD_S, clock.now, skipped=Share(SKIPPED_OK))
    went = burst(pacer, clock, 20)
    assert went[-1] - went[0] == pytest.approx(19 * HOLD_S)
    assert pacer.stretched == 0


def test_worlds_that_skip_their_ticks_slow_the_starts_down_in_order() -> None:
    clock, skipped = ManualClock(100.0), Share(SKIPPED_MOST)
    pacer = StartPacer(1, HOLD_S, clock.now, skipped=skipped)
    went = burst(pacer, clock, 20)
    gaps = [b - a for a, b in itertools.pairwise(went)]
    # Each start's turn came later by the stretch of every start before it; a start back at its
    # turn a quarter hold early still goes (as one a little late does), so single gaps vary a bit.
    assert went[-1] - went[0] == pytest.approx(19 * HOLD_S * MAX_STRETCH, abs=HOLD_S * 0.25)
    assert min(gaps) >= HOLD_S * 0.75 and max(gaps) <= HOLD_S * MAX_STRETCH + HOLD_S * 0.25
    assert pacer.stretched == 20


def test_the_starts_take_their_full_pace_again_once_the_worlds_keep_up() -> None:
    clock, skipped = ManualClock(100.0), Share(SKIPPED_MOST)
    pacer = StartPacer(1, HOLD_S, clock.now, skipped=skipped)
    first = burst(pacer, clock, 10)
    skipped.value = 0.0
    clock.advance(10.0)
    second = burst(pacer, clock, 10)
    assert first[-1] - first[0] > 9 * HOLD_S * (1.0 + (MAX_STRETCH - 1.0) / 2)
    assert second[-1] - second[0] == pytest.approx(9 * HOLD_S)


def test_a_machines_processes_yield_to_what_any_of_them_skipped(tmp_path: Path) -> None:
    clock, slots = ManualClock(100.0), tmp_path / "start-slots"
    server = MachineStartPacer(slots, 1, HOLD_S, clock.now, skipped=Share(SKIPPED_MOST))
    worker = MachineStartPacer(slots, 1, HOLD_S, clock.now, skipped=Share(0.0))
    assert server.admit(NEW_TURN, "s") is None  # the server's worlds say what they skipped
    said = json.loads(slots.read_text())["skipped"]
    assert [share for _at, share in said.values()] == [SKIPPED_MOST]
    assert server.stretched == 1
    # The worker's worlds keep up, the server's do not: the worker's starts yield to them too.
    clock.advance(HOLD_S / 2)
    first, second = worker.admit(NEW_TURN, "a"), worker.admit(NEW_TURN, "b")
    assert first is not None and second is not None and first.ticket and second.ticket
    second_at = clock.now() + second.wait_s
    clock.advance(first.wait_s)
    assert worker.admit(first.ticket, "a") is None  # the first goes at its turn ...
    assert worker.stretched == 1
    early = worker.admit(second.ticket, "b")  # ... and the second's turn moved back
    assert early is not None and clock.now() + early.wait_s == pytest.approx(
        second_at + (MAX_STRETCH - 1) * HOLD_S
    )
    # What the server said counts for SKIPPED_FRESH_S; it has said nothing since: the full pace.
    clock.set(100.0 + SKIPPED_FRESH_S + HOLD_S * 2)
    went = burst(worker, clock, 5)
    assert went[-1] - went[0] == pytest.approx(4 * HOLD_S)
    assert worker.stretched == 1


def test_a_process_that_says_nothing_leaves_the_pace_alone(tmp_path: Path) -> None:
    """The peer of the tests above: the same burst with no reading paces as it always did."""
    clock = ManualClock(100.0)
    pacer = MachineStartPacer(tmp_path / "start-slots", 1, HOLD_S, clock.now)
    went = burst(pacer, clock, 10)
    assert went[-1] - went[0] == pytest.approx(9 * HOLD_S)
    assert pacer.stretched == 0


@pytest.mark.parametrize("bad", [math.nan, -0.5, 1.5, math.inf])
def test_a_reading_that_is_no_share_leaves_the_pace_alone(tmp_path: Path, bad: float) -> None:
    clock = ManualClock(100.0)
    pacer = MachineStartPacer(tmp_path / "start-slots", 1, HOLD_S, clock.now, skipped=Share(bad))
    went = burst(pacer, clock, 5)
    assert went[-1] - went[0] == pytest.approx(4 * HOLD_S)
    said = json.loads((tmp_path / "start-slots").read_text())["skipped"]
    assert [share for _at, share in said.values()] == [0.0]  # the file stays readable for the others
