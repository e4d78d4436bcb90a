"""Checkpoint 1's check on synthetic events, its clock stepped by hand."""

from __future__ import annotations

from server.world.checkpoints.events import Abort, CmdVel, Countdown, KeyDown, Source
from server.world.checkpoints.keyboard_abort import KEY_A, KeyboardAbortCheck

KEYBOARD = Source("/keyboard")
STUDENT = Source("/KeyboardManager", "process 4242", student=True)
LAB_MANAGER = Source("/KeyboardManager")
BY_HAND = Source("/_rest_api")


def countdown(check: KeyboardAbortCheck, start_s: float = 0.0, counts: range = range(10, 5, -1)) -> float:
    t = start_s
    for value in counts:
        assert check.feed(Countdown(t, value)) is None
        t += 1.0
    return t


def test_keyboard_abort_student_process_aborts_within_a_second_is_done_once_the_rocket_stays() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    assert check.feed(KeyDown(t, KEY_A, KEYBOARD)) is None
    assert check.feed(Abort(t + 0.3, True, STUDENT)) is None  # not yet: does the rocket stay?
    assert check.tick(t + 0.9) is None
    evidence = check.tick(t + 1.4)
    assert evidence is not None
    assert evidence["student_node"] == "/KeyboardManager" and evidence["student_process"] == "process 4242"
    assert evidence["key_to_abort_s"] == 0.3
    whats = [e["what"] for e in evidence["timeline"]]
    assert whats.count("countdown") == 5 and "key" in whats and "abort" in whats
    assert check.tick(t + 5) is None  # met once


def test_keyboard_abort_published_by_hand_is_not_done() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    check.feed(Abort(t + 0.2, True, BY_HAND))
    assert check.tick(t + 3) is None
    assert "not from a keyboard manager of your workspace" in check.progress(t + 3)


def test_keyboard_abort_by_the_labs_own_manager_is_not_done() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    check.feed(Abort(t + 0.1, True, LAB_MANAGER))
    assert check.tick(t + 3) is None


def test_keyboard_abort_after_lift_off_is_not_done() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check, counts=range(3, 0, -1))
    check.feed(Countdown(t, 0))
    check.feed(CmdVel(t + 0.1, 2.0))  # lift-off
    check.feed(KeyDown(t + 1, KEY_A, KEYBOARD))
    check.feed(Abort(t + 1.2, True, STUDENT))
    assert check.tick(t + 4) is None
    assert "lifted off" in check.progress(t + 4)


def test_keyboard_abort_lift_off_right_after_the_abort_is_not_done() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    check.feed(Abort(t + 0.2, True, STUDENT))
    assert check.feed(CmdVel(t + 0.5, 1.0)) is None
    assert check.tick(t + 3) is None


def test_keyboard_abort_later_than_a_second_after_the_key_is_not_done() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    check.feed(Abort(t + 1.5, True, STUDENT))
    assert check.tick(t + 4) is None


def test_keyboard_abort_a_key_published_by_hand_counts_for_nothing() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, BY_HAND))
    check.feed(Abort(t + 0.2, True, STUDENT))
    assert check.tick(t + 3) is None


def test_keyboard_abort_false_is_no_abort() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    check.feed(Abort(t + 0.2, False, STUDENT))
    assert check.tick(t + 3) is None


def test_keyboard_abort_a_new_countdown_after_lift_off_allows_it_again() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check, counts=range(2, 0, -1))
    check.feed(CmdVel(t, 3.0))
    t = countdown(check, start_s=t + 5, counts=range(10, 7, -1))  # the rocket was reset
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    check.feed(Abort(t + 0.1, True, STUDENT))
    assert check.tick(t + 1.2) is not None


def test_keyboard_abort_before_any_countdown_is_not_done() -> None:
    check = KeyboardAbortCheck()
    check.feed(KeyDown(0.0, KEY_A, KEYBOARD))
    check.feed(Abort(0.1, True, STUDENT))
    assert check.tick(3.0) is None
    assert "no countdown running" in check.progress(3.0)


def test_keyboard_abort_a_countdown_alone_is_not_started_a_key_is() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    assert not check.started  # the lab counts down by itself
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    assert check.started


def test_keyboard_abort_what_went_wrong_stays_said_while_the_countdown_goes_on() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    check.feed(Abort(t + 0.2, True, BY_HAND))
    countdown(check, start_s=t + 1, counts=range(4, 0, -1))
    assert "/_rest_api" in check.progress(t + 5)
    countdown(check, start_s=t + 10, counts=range(10, 8, -1))  # a new countdown: a new line
    assert check.progress(t + 12) == "the countdown is on: press a"


def test_keyboard_abort_repeated_by_the_labs_manager_past_the_countdown_keeps_its_reason() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check, counts=range(3, 0, -1))
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    for i in range(40):  # the lab's manager republishes its abort at 10 Hz, past the countdown's end
        check.feed(Abort(t + 0.1 * i, True, LAB_MANAGER))
        if i == 5:
            check.feed(Countdown(t + 0.5, 0))
    assert "not from a keyboard manager of your workspace" in check.progress(t + 4)
    assert sum(1 for e in check.timeline.entries() if e["what"] == "abort") == 1


def _manager_at_10_hz(check: KeyboardAbortCheck, key_s: float, until_s: float) -> tuple[list[str], int]:
    """The handout's manager (and the lab's) publishing /abort_takeoff at 10 Hz, true from the
    "a" at ``key_s`` on, while the countdown goes on once a second: the line after each message,
    and how many times the check was met."""
    lines, met = [], 0
    for i in range(round((until_s - key_s) * 10)):
        t = round(key_s + 0.05 + 0.1 * i, 3)
        if i % 10 == 5:
            check.feed(Countdown(t, max(0, 5 - i // 10)))
        met += check.feed(Abort(t, True, STUDENT)) is not None
        met += check.feed(Abort(t + 0.01, True, LAB_MANAGER)) is not None
        met += check.tick(t + 0.02) is not None
        lines.append(check.progress(t + 0.02))
    return lines, met


def test_keyboard_abort_a_manager_at_10_hz_after_the_a_that_met_it_leaves_the_done_line() -> None:
    check = KeyboardAbortCheck()
    t = countdown(check)
    check.feed(KeyDown(t, KEY_A, KEYBOARD))
    lines, met = _manager_at_10_hz(check, t, t + 6.2)  # the 5 s after the met tick and more
    assert check.progress(t + 6.2) == "done: the rocket stayed on the pad"
    assert not any("without an a pressed" in line for line in lines)
    after = lines[lines.index("done: the rocket stayed on the pad") :]
    assert set(after) == {"done: the rocket stayed on the pad"}  # nothing changed: nor did the line
    assert met == 1
    assert sum(1 for e in check.timeline.entries() if e["what"] == "abort") == 2  # one per node


def test_keyboard_abort_two_rockets_counting_at_once_do_not_flip_the_line() -> None:
    check = KeyboardAbortCheck()
    other = Source("/CountDownNode", "process 77")
    for i in range(6):  # the lab's rocket and a second one launched by hand, 0.5 s apart
        check.feed(Countdown(float(i), 10 - i))
        check.feed(Countdown(i + 0.5, 7 - i, other))
    check.feed(Abort(6.0, True, BY_HAND))
    said = check.progress(6.0)
    for i in range(6, 9):
        check.feed(Countdown(float(i), 10 - i))
        check.feed(Countdown(i + 0.5, max(0, 7 - i), other))
        assert check.progress(i + 0.6) == said
