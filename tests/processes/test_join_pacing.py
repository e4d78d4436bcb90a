"""Node starts paced on the server (server/host/processes/start_pacing.py) and ``ros2lab``'s join asked with a bounded
wait (server/cli/join.py), on a manual clock: a lab that never answers is given up after the
bound, one that answers late is joined, a lab's "not yet" is waited out for as long as it says,
and an error that retrying cannot mend (no Zenoh graph) ends at once."""

from __future__ import annotations

from collections.abc import Callable

import httpx
import pytest

from api.routes.lab import retry_after
from server.cli.client import ApiError, LabClient
from server.cli.join import JoinError, Pacing, join_graph
from server.host.processes.start_pacing import NEW_TURN, StartPacer, Turn

URL = "http://lab.test"
JOIN = {"router": "tcp/127.0.0.1:7447", "domain_id": 3, "user": None, "password": None, "env": {}}


class ManualClock:
    def __init__(self) -> None:
        self.now = 0.0
        self.sleeps: list[float] = []

    def __call__(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.sleeps.append(seconds)
        self.now += seconds


def lab(answers: list[Callable[[httpx.Request], httpx.Response]], clock: ManualClock) -> LabClient:
    """A client whose requests get ``answers`` in turn (the last repeats); each records the clock."""
    asked: list[float] = []

    def handle(request: httpx.Request) -> httpx.Response:
        asked.append(clock.now)
        return answers[min(len(asked) - 1, len(answers) - 1)](request)

    client = LabClient(URL, transport=httpx.MockTransport(handle))
    client.asked = asked  # type: ignore[attr-defined]
    return client


def refused(request: httpx.Request) -> httpx.Response:
    raise httpx.ConnectError("connection refused", request=request)


def silent(clock: ManualClock) -> Callable[[httpx.Request], httpx.Response]:
    def answer(request: httpx.Request) -> httpx.Response:
        clock.now += request.extensions["timeout"]["read"]  # the attempt's own timeout runs out
        raise httpx.ReadTimeout("timed out", request=request)

    return answer


def slow(clock: ManualClock, after_s: float) -> Callable[[httpx.Request], httpx.Response]:
    def answer(request: httpx.Request) -> httpx.Response:
        assert request.extensions["timeout"]["read"] > after_s  # the request waits long enough
        clock.now += after_s
        return ok(request)

    return answer


def ok(request: httpx.Request) -> httpx.Response:
    return httpx.Response(200, json=JOIN)


def not_yet(after_s: str) -> Callable[[httpx.Request], httpx.Response]:
    return lambda request: httpx.Response(429, json={"detail": "too many"}, headers={"Retry-After": after_s})


def pacing(clock: ManualClock, **kw: float) -> Pacing:
    return Pacing(clock=clock, sleep=clock.sleep, jitter=lambda: 0.0, say=lambda line: None, **kw)


def wait_of(turn: Turn | None) -> float | None:
    return None if turn is None else turn.wait_s


def test_pacer_admits_up_to_its_slots_then_says_when_one_frees() -> None:
    now = [100.0]
    pacer = StartPacer(2, hold_s=1.0, clock=lambda: now[0])
    assert [pacer.admit(), pacer.admit()] == [None, None]
    now[0] += 0.25
    assert wait_of(pacer.admit()) == pytest.approx(0.75)
    now[0] += 2.0  # both slots free, and the turn it was told is past
    assert [wait_of(pacer.admit()) for _ in range(3)] == [None, None, pytest.approx(1.0)]
    assert (pacer.admitted, pacer.deferred) == (4, 2)
    assert (retry_after(0.2), retry_after(1.2)) == ("1", "2")


def test_pacer_gives_each_waiting_start_a_turn_of_its_own() -> None:
    """Starts that wait are told to come back one slot's share of the hold apart, in the order they
    asked, so each asks again about once; a start admitted meanwhile takes nothing from them."""
    now = [0.0]
    pacer = StartPacer(1, hold_s=1.0, clock=lambda: now[0])
    assert pacer.admit() is None
    turns = [pacer.admit(NEW_TURN) for _ in range(3)]
    assert [wait_of(t) for t in turns] == [pytest.approx(1.0), pytest.approx(2.0), pytest.approx(3.0)]
    assert all(t is not None and t.ticket for t in turns) and len({t.ticket for t in turns if t}) == 3
    now[0] = 1.0  # the first comes back at its turn with its ticket: the slot is free
    assert pacer.admit(turns[0].ticket if turns[0] else None) is None
    assert wait_of(pacer.admit()) == pytest.approx(3.0)  # a newcomer waits behind the two told before it
    now[0] = 20.0  # long after: the turns are given up, the next waits only for the held slot
    assert pacer.admit() is None
    assert wait_of(pacer.admit()) == pytest.approx(1.0)


def test_pacer_refuses_no_slots() -> None:
    with pytest.raises(ValueError, match="slots >= 1"):
        StartPacer(0)


def test_join_gives_up_on_a_lab_that_never_answers_within_the_bound() -> None:
    clock = ManualClock()
    client = lab([silent(clock)], clock)
    with pytest.raises(JoinError, match=r"did not tell how to join its graph within 12 s \(GET"):
        join_graph(client, pacing(clock, wait_s=12.0))
    assert clock.now == 12.0  # the one request waited for all of the bound, and no longer
    assert len(client.asked) == 1  # type: ignore[attr-defined]


def test_join_gives_up_on_a_refused_connection_with_growing_pauses() -> None:
    clock = ManualClock()
    client = lab([refused], clock)
    with pytest.raises(JoinError, match=r"within 10 s \(connection refused\)"):
        join_graph(client, pacing(clock, wait_s=10.0))
    assert clock.sleeps[:4] == [0.25, 0.5, 1.0, 2.0] and max(clock.sleeps) == 4.0
    assert clock.now <= 10.0


def test_join_joins_a_lab_that_answers_late() -> None:
    clock = ManualClock()
    client = lab([refused, refused, lambda r: httpx.Response(503), slow(clock, 15.0)], clock)
    assert join_graph(client, pacing(clock, wait_s=20.0)) == JOIN  # a slow answer is an answer
    assert len(client.asked) == 4 and clock.now > 15.0  # type: ignore[attr-defined]


def test_join_waits_out_the_labs_pacing_without_counting_it_as_silence() -> None:
    clock = ManualClock()
    client = lab([not_yet("3")] * 10 + [ok], clock)  # 30 s of "not yet", beyond the 5 s bound
    assert join_graph(client, pacing(clock, wait_s=5.0)) == JOIN
    assert clock.sleeps == [3.0] * 10


def test_join_pacing_too_long_is_one_clear_error() -> None:
    clock = ManualClock()
    client = lab([not_yet("30")], clock)
    with pytest.raises(JoinError, match="still pacing node starts after 60 s"):
        join_graph(client, pacing(clock, wait_s=5.0, queue_s=60.0))
    assert clock.now <= 60.0


def test_join_ends_at_once_on_an_error_retrying_cannot_mend() -> None:
    clock = ManualClock()
    no_graph = httpx.Response(
        404, json={"detail": "this lab's graph is not on Zenoh (started with --no-zenoh)"}
    )
    client = lab([lambda r: no_graph], clock)
    with pytest.raises(ApiError, match="not on Zenoh"):
        join_graph(client, pacing(clock))
    assert clock.sleeps == [] and len(client.asked) == 1  # type: ignore[attr-defined]


def test_join_does_what_it_was_given_meanwhile_once_at_the_first_not_yet_and_off_the_wait() -> None:
    """``ros2lab run`` finds its file while its start waits for its turn: once, at the first "not
    yet", and the time that took is waited less."""
    clock = ManualClock()
    client = lab([not_yet("3"), not_yet("3"), ok], clock)
    done: list[float] = []

    def find() -> None:
        done.append(clock.now)
        clock.now += 0.5  # the package index read

    assert join_graph(client, pacing(clock), start=True, meanwhile=find) == JOIN
    assert done == [0.0] and clock.sleeps == [2.5, 3.0]
    assert client.asked == [0.0, 3.0, 6.0]  # type: ignore[attr-defined]  # its turns, as without

    admitted = lab([ok], ManualClock())  # a start that goes at once has nothing to do meanwhile
    assert join_graph(admitted, pacing(ManualClock()), start=True, meanwhile=find) == JOIN
    assert done == [0.0]


def test_join_ends_without_its_turn_when_what_it_did_meanwhile_failed() -> None:
    clock = ManualClock()
    client = lab([not_yet("30"), ok], clock)

    def find() -> None:
        raise LookupError("Package 'nope' not found")

    with pytest.raises(LookupError, match="nope"):
        join_graph(client, pacing(clock), start=True, meanwhile=find)
    assert clock.sleeps == [] and len(client.asked) == 1  # type: ignore[attr-defined]
