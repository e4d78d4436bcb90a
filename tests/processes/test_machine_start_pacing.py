"""A class's node starts take turns at the machine's slots (server/host/processes/start_pacing.py,
``MachineStartPacer``): the class server and the world workers it starts on its own machine keep
the slots in one file they lock, so a start admitted in one process holds a slot the others see.
Two pacers on one file stand for two processes on a manual clock; one test admits in a process of
its own, on the machine's clock."""

from __future__ import annotations

import fcntl
import json
import logging
import os
import subprocess
import sys
from pathlib import Path

import pytest

from server.host.processes.start_pacing import (
    BUSY_WAIT_S,
    MAX_TURNS,
    NEW_TURN,
    MachineStartPacer,
    StartPacer,
    Turn,
)


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_two_processes_share_the_machines_slot_and_turns(tmp_path: Path) -> None:
    clock, slots = Clock(), tmp_path / "start-slots"
    server, worker = (MachineStartPacer(slots, 1, hold_s=1.0, clock=clock) for _ in range(2))
    assert server.admit() is None  # the machine's one slot, held for a second
    first = worker.admit(NEW_TURN)
    assert first is not None and first.wait_s == pytest.approx(1.0)  # another process sees it held
    second = server.admit(NEW_TURN)
    assert second is not None and second.wait_s == pytest.approx(2.0)  # after the turn the other gave
    clock.now += 1.0
    assert worker.admit(NEW_TURN) is not None  # a newcomer: the slot is set aside for the first turn
    assert server.admit(first.ticket) is None  # whose ticket, given by the worker, goes here
    assert (server.admitted, server.deferred, worker.admitted, worker.deferred) == (2, 1, 0, 2)
    clock.now += 1.0
    assert worker.admit(second.ticket) is None


def test_each_process_alone_would_have_let_both_start(tmp_path: Path) -> None:
    """The peer without the file: two pacers of one slot each admit at once, the machine's one
    core taking both starts; what the shared file prevents."""
    clock = Clock()
    server, worker = StartPacer(1, 1.0, clock), StartPacer(1, 1.0, clock)
    assert server.admit() is None and worker.admit() is None


def test_a_start_admitted_in_another_process_holds_the_slot_here(tmp_path: Path) -> None:
    slots = tmp_path / "start-slots"
    code = (
        "import sys; from pathlib import Path; from server.host.processes.start_pacing import MachineStartPacer;"
        "print(MachineStartPacer(Path(sys.argv[1]), 1, hold_s=60.0).admit())"
    )
    other = subprocess.run(
        [sys.executable, "-c", code, str(slots)], capture_output=True, text=True, timeout=60
    )
    assert other.stdout.strip() == "None", other.stderr  # admitted there
    assert MachineStartPacer(slots, 2, hold_s=60.0).admit() is None  # a second slot is free here
    turn = MachineStartPacer(slots, 1, hold_s=60.0).admit()
    assert turn is not None and 50.0 < turn.wait_s <= 60.0  # the first held here, on the same clock


def test_a_lock_held_elsewhere_defers_the_start_briefly_and_never_blocks(tmp_path: Path) -> None:
    slots = tmp_path / "start-slots"
    pacer = MachineStartPacer(slots, 1, hold_s=1.0, clock=Clock())
    held = os.open(slots, os.O_RDWR | os.O_CREAT)  # another open file: its flock conflicts with the pacer's
    try:
        fcntl.flock(held, fcntl.LOCK_EX)
        assert pacer.admit("a ticket") == Turn(BUSY_WAIT_S, "a ticket")  # which it keeps
    finally:
        os.close(held)
    assert pacer.admit() is None  # the lock freed: admitted, the slot was never taken
    assert (pacer.admitted, pacer.deferred) == (1, 1)


@pytest.mark.parametrize(
    "text",
    [
        "",
        "not json",
        "[]",
        '{"held": [1e308]}',
        '{"boot": "another boot", "held": [150.0], "last_turn": 150.0}',
        '{"boot": "%s", "held": [NaN], "last_turn": null}',
        '{"boot": "%s", "held": ["x"], "last_turn": null}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {"t": [NaN, "", true]}}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {"t": 150.0}}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {"t": [150.0, 3, true]}}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": ["t"]}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {%s}}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {}, "skipped": {"p": [100.0, 1.5]}}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {}, "skipped": {"p": [NaN, 0.1]}}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {}, "skipped": {"p": 0.1}}',
        '{"boot": "%s", "held": [], "last_turn": null, "turns": {}, "skipped": ["p"]}',
    ],
)
def test_a_slots_file_from_another_boot_or_spoilt_is_a_fresh_start(tmp_path: Path, text: str) -> None:
    from server.host.processes.start_pacing import BOOT_ID

    slots = tmp_path / "start-slots"
    too_many = ", ".join(f'"t{i}": [150.0, "", true]' for i in range(MAX_TURNS + 1))  # more than it writes
    slots.write_text(text.replace("{%s}", "{" + too_many + "}").replace("%s", BOOT_ID))
    pacer = MachineStartPacer(slots, 1, hold_s=1.0, clock=Clock())
    assert pacer.admit() is None
    written = json.loads(slots.read_text())
    said = written.pop("skipped")
    assert written == {"boot": BOOT_ID, "held": [101.0], "last_turn": None, "turns": {}}
    assert list(said.values()) == [[100.0, 0.0]]  # what this pacer's worlds skipped (no reading: none)


def test_a_slots_file_from_this_boot_is_kept(tmp_path: Path) -> None:
    """The fresh start above is not the pacer ignoring its file: this boot's held slot defers."""
    from server.host.processes.start_pacing import BOOT_ID

    slots = tmp_path / "start-slots"
    turns = {"t": [99.0, "", True]}
    slots.write_text(json.dumps({"boot": BOOT_ID, "held": [150.0], "last_turn": None, "turns": turns}))
    pacer = MachineStartPacer(slots, 1, hold_s=1.0, clock=Clock())
    turn = pacer.admit()
    assert turn is not None and turn.wait_s == pytest.approx(50.0)
    assert pacer.admit("t") is None  # the turn kept in the file, claimed late (it was at 99)


def test_a_slots_file_that_cannot_be_opened_paces_this_process_alone(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    blocker = tmp_path / "a file"
    blocker.write_text("")
    pacer = MachineStartPacer(blocker / "start-slots", 1, hold_s=1.0, clock=Clock())  # under a file
    with caplog.at_level(logging.WARNING, logger="server.host.processes.start_pacing"):
        assert pacer.admit() is None
        turn = pacer.admit()
        assert turn is not None and turn.wait_s == pytest.approx(1.0)  # still paced, by this process
    assert [r.getMessage() for r in caplog.records if "paced by this process alone" in r.getMessage()]
    assert len(caplog.records) == 1  # said once


def test_a_start_back_at_its_turn_just_before_the_slot_frees_goes_rather_than_to_the_back() -> None:
    """The one ahead of it was admitted 0.1 s late (a busy loop), so its slot frees 0.1 s after
    the next start's turn: that start goes then, where it used to be told a turn after every other
    waiting start (60 paced starts took 104 s where 60 were due)."""
    clock = Clock()
    pacer = StartPacer(1, hold_s=1.0, clock=clock)
    assert pacer.admit() is None  # A, holds until 101
    b, c, d = (pacer.admit(NEW_TURN) for _ in range(3))  # B, C, D wait: turns at 101, 102, 103
    assert b is not None and c is not None and d is not None
    assert [b.wait_s, c.wait_s, d.wait_s] == [pytest.approx(1.0), pytest.approx(2.0), pytest.approx(3.0)]
    clock.now = 101.1  # B comes back 0.1 s late and goes: holds until 102.1
    assert pacer.admit(b.ticket) is None
    clock.now = 102.0  # C back at its turn, 0.1 s before B's slot frees
    assert pacer.admit(c.ticket) is None
    clock.now = 102.5  # a new start, with C's slot held for 0.5 s more, waits
    late = pacer.admit()
    assert late is not None and late.wait_s == pytest.approx(1.5)  # till 104: after D's turn at 103
