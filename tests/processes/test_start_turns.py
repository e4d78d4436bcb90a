"""A paced start's turn is kept for it (server/host/processes/start_pacing.py): a start told to
wait is given a ticket, and back with it at its turn or late it goes, whatever asked meanwhile;
back early it keeps its turn; a ticket unknown, forged or given up is a new start. Through the
real app the 429 carries the wait to the millisecond and the ticket, and ``ros2lab``'s join
(server/cli/join.py) waits exactly that and asks again with it. On manual clocks."""

from __future__ import annotations

import os
import random
import threading
from collections.abc import Iterator
from dataclasses import dataclass, field

import httpx
import pytest
from fastapi.testclient import TestClient
from support.app import free_port

from node_runtime.transport.config import ZenohSettings
from server.app import create_app
from server.base.loop_priority import SCHEDULINGS, Scheduling, loop_priority
from server.cli.client import LabClient
from server.cli.join import TURN_CHARS, Pacing, join_graph
from server.host.processes.start_pacing import (
    FAIR_LOOP_HOLD_S,
    KEPT_S,
    MAX_TURNS,
    MAX_WAITING,
    NEW_TURN,
    TICKET_CHARS,
    StartPacer,
    Turn,
)
from server.host.processes.start_pacing import HOLD_S as PACER_HOLD_S
from server.host.settings import LabSettings, Listening, Settings

HOLD_S = 1.0


@dataclass
class Clock:
    now: float = 100.0
    sleeps: list[float] = field(default_factory=list)

    def __call__(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.sleeps.append(seconds)
        self.now += seconds


def told(turn: Turn | None) -> Turn:
    assert turn is not None, "admitted where a turn was expected"
    return turn


def test_a_start_back_late_with_its_ticket_goes_and_a_newcomer_meanwhile_waits_behind() -> None:
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN) is None  # A holds the slot till 101
    b = told(pacer.admit(NEW_TURN))
    assert b.wait_s == pytest.approx(1.0) and b.ticket
    clock.now = 101.3  # B is 0.3 s late (Retry-After is whole seconds; a busy client)
    newcomer = told(pacer.admit(NEW_TURN))  # asks first: B's slot is set aside for B
    assert newcomer.wait_s == pytest.approx(0.7)  # its turn at 102, after B's, not before
    assert pacer.admit(b.ticket) is None  # B goes
    assert (pacer.admitted, pacer.deferred) == (2, 2)


def test_without_the_ticket_a_late_start_goes_to_the_back_of_the_line() -> None:
    """What the ticket keeps: the same late start asking as a new one waits behind every turn."""
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN) is None
    told(pacer.admit(NEW_TURN))  # B
    later = [told(pacer.admit(NEW_TURN)) for _ in range(3)]  # C, D, E: turns at 102, 103, 104
    assert [t.wait_s for t in later] == [pytest.approx(2.0), pytest.approx(3.0), pytest.approx(4.0)]
    clock.now = 101.3
    again = told(pacer.admit(NEW_TURN))  # B, no ticket
    assert again.wait_s == pytest.approx(105.0 - 101.3)  # after E's turn


def test_a_start_back_early_keeps_its_turn_and_its_ticket() -> None:
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN) is None
    b = told(pacer.admit(NEW_TURN))
    clock.now = 100.4
    early = told(pacer.admit(b.ticket))
    assert early == Turn(pytest.approx(0.6), b.ticket)  # type: ignore[arg-type]
    clock.now = 100.8  # within a quarter of the hold of its turn: counts as its turn
    assert pacer.admit(b.ticket) is None


def test_an_unknown_ticket_is_a_new_start() -> None:
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN) is None
    b = told(pacer.admit(NEW_TURN))
    clock.now = 101.0
    forged = told(pacer.admit("not-a-ticket"))  # B's slot is set aside: the forger waits behind it
    assert forged.ticket not in (None, b.ticket, "not-a-ticket")
    assert pacer.admit(b.ticket) is None  # B's turn was not taken by the forgery
    assert pacer.admit(b.ticket) is not None  # and a ticket goes once only


def test_a_turn_not_claimed_in_time_is_given_up() -> None:
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN) is None
    b = told(pacer.admit(NEW_TURN))  # turn at 101
    clock.now = 101.0 + HOLD_S + 0.01  # its slot is no longer set aside: a newcomer goes
    assert pacer.admit(NEW_TURN) is None
    clock.now = 101.0 + KEPT_S + 0.01  # its start never came: the turn is given up
    assert pacer.admit(NEW_TURN) is None  # (another start holds the slot now)
    again = told(pacer.admit(b.ticket))  # so its ticket is a new start's now
    assert again.ticket != b.ticket


def test_past_the_turns_kept_a_start_is_told_its_wait_with_no_ticket() -> None:
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN) is None
    turns = [told(pacer.admit(NEW_TURN, f"world{i}")) for i in range(MAX_TURNS + 1)]
    assert all(t.ticket for t in turns[:MAX_TURNS]) and turns[-1].ticket is None
    assert turns[-1].wait_s == pytest.approx(MAX_TURNS + 1.0)  # still in line


def burst(
    pacer: StartPacer, clock: Clock, starts: int, late_s: list[float], tickets: bool
) -> tuple[float, int]:
    """``starts`` asking at once, each back ``late_s[i]`` after the time it is told (with its
    ticket or as a new start); when the last went, and how many times they asked in all."""
    pending = [(clock.now, i, None) for i in range(starts)]  # when it asks, which, its ticket
    asked = 0
    last = clock.now
    while pending:
        pending.sort(key=lambda p: (p[0], p[1]))
        at, i, ticket = pending.pop(0)
        clock.now = at
        asked += 1
        turn = pacer.admit(ticket or NEW_TURN if tickets else None, f"world{i // 2}")  # two each
        if turn is None:
            last = at
            continue
        pending.append((at + turn.wait_s + late_s[i], i, turn.ticket))
    return last, asked


def test_sixty_starts_back_late_go_at_their_turns_with_tickets_and_far_later_without() -> None:
    """A class's "run it now" through ``ros2lab run``: each start comes back up to 0.6 s after its
    turn (a timer, an HTTP round trip, a busy loop). With their tickets they are all gone at about
    their turns and each asked twice at most; as new starts, the late ones kept going to the back."""
    rng = random.Random(7)
    lateness = [rng.uniform(0.0, 0.6) for _ in range(60)]
    kept_clock, new_clock = Clock(), Clock()
    kept_last, kept_asks = burst(StartPacer(1, HOLD_S, kept_clock), kept_clock, 60, lateness, tickets=True)
    new_last, new_asks = burst(StartPacer(1, HOLD_S, new_clock), new_clock, 60, lateness, tickets=False)
    assert kept_last - 100.0 <= 59 * HOLD_S + 0.6 and kept_asks <= 2 * 60 - 1
    assert new_last - 100.0 > 59 * HOLD_S + 5.0 and new_asks > kept_asks


# Through the real app and ros2lab's join.


@pytest.fixture
def app() -> Iterator[tuple[TestClient, Clock]]:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="rocket",
            launch_args={"start_delay": "3600"},
            viewer=False,
            zenoh=ZenohSettings(listen=(f"tcp/127.0.0.1:{free_port()}",)),
        ),
    )
    clock = Clock()
    with TestClient(create_app(settings)) as client:
        client.app.state.lab.start_pacer = StartPacer(1, 0.75, clock)  # type: ignore[attr-defined]
        yield client, clock


def join(client: TestClient, turn: str | None = NEW_TURN) -> httpx.Response:
    params = {"start": "true", **({"turn": turn} if turn is not None else {})}
    return client.get("/api/zenoh/join", params=params)


def test_the_join_tells_the_wait_to_the_millisecond_and_the_ticket_that_keeps_the_turn(
    app: tuple[TestClient, Clock],
) -> None:
    client, clock = app
    assert join(client).status_code == 200
    waiting = join(client)
    assert waiting.status_code == 429, waiting.text
    assert (waiting.headers["Retry-After"], waiting.headers["Retry-After-Ms"]) == ("1", "750")
    ticket = waiting.headers["Start-Turn"]
    assert 0 < len(ticket) <= TICKET_CHARS and "0.8 s" in waiting.json()["detail"]
    clock.now += 0.9  # back 0.15 s late
    assert join(client).status_code == 429  # a newcomer meanwhile waits behind it
    assert join(client, ticket).status_code == 200


def test_a_turn_longer_than_a_ticket_is_refused_and_changes_nothing(app: tuple[TestClient, Clock]) -> None:
    client, _ = app
    pacer: StartPacer = client.app.state.lab.start_pacer  # type: ignore[attr-defined]
    refused = join(client, "x" * (TICKET_CHARS + 1))
    assert refused.status_code == 422 and "turn" in refused.text, refused.text
    assert (pacer.admitted, pacer.deferred) == (0, 0)
    assert join(client, "x" * TICKET_CHARS).status_code == 200  # the longest a ticket may be: asked
    assert TURN_CHARS == TICKET_CHARS  # ros2lab sends no longer one


def test_ros2lab_join_waits_exactly_its_turn_and_asks_again_with_the_ticket(
    app: tuple[TestClient, Clock],
) -> None:
    """The CLI's own join against the app: told 0.75 s, it sleeps 0.75 s (no jitter: its turn is
    its own), and though it is late and a newcomer asked in between, its ticket lets it go."""
    client, clock = app
    assert join(client).status_code == 200  # another start holds the slot
    asked: list[str] = []

    def through_the_app(request: httpx.Request) -> httpx.Response:
        asked.append(str(request.url.query.decode()))
        response = client.send(request)
        response.read()
        return response

    def sleep(seconds: float) -> None:
        clock.sleep(seconds + 0.2)  # its process ran 0.2 s late
        assert join(client).status_code == 429  # someone else asked first

    lab_client = LabClient("http://testserver", transport=httpx.MockTransport(through_the_app))
    pacing = Pacing(clock=clock, sleep=sleep, jitter=lambda: 1.0, say=lambda line: None)
    answer = join_graph(lab_client, pacing, start=True)
    assert answer["router"].startswith("tcp/127.0.0.1:")
    assert clock.sleeps == [pytest.approx(0.95)]  # 0.75 s told, the 0.2 s late its own
    assert asked[0] == "start=true&turn=new" and len(asked) == 2
    assert asked[1].startswith("start=true&turn=") and asked[1] != asked[0]


@pytest.mark.parametrize(
    ("headers", "slept", "sent_turn"),
    [
        ({"Retry-After": "2", "Retry-After-Ms": "nan", "Start-Turn": "t"}, 2.0, True),
        ({"Retry-After": "2", "Retry-After-Ms": "-5"}, 2.25, False),
        ({"Retry-After": "2", "Retry-After-Ms": "1500", "Start-Turn": "t" * (TURN_CHARS + 1)}, 1.75, False),
        ({"Retry-After": "inf"}, None, False),
    ],
)
def test_ros2lab_join_takes_only_a_wait_and_a_ticket_that_are_ones(
    headers: dict[str, str], slept: float | None, sent_turn: bool
) -> None:
    """A hostile or broken lab: a wait that is no number, negative or infinite is not taken (the
    whole seconds are, or the join has no wait to go by); a ticket too long is not sent back. A
    start with no ticket is spread as before (a quarter second at most)."""
    clock = Clock()
    asked: list[str] = []

    def lab(request: httpx.Request) -> httpx.Response:
        asked.append(request.url.query.decode())
        if len(asked) == 1:
            return httpx.Response(429, json={"detail": "not yet"}, headers=headers)
        return httpx.Response(200, json={"router": "tcp/127.0.0.1:7447", "domain_id": 0})

    pacing = Pacing(clock=clock, sleep=clock.sleep, jitter=lambda: 1.0, say=lambda line: None, wait_s=1.0)
    client = LabClient("http://lab.test", transport=httpx.MockTransport(lab))
    if slept is None:  # no usable wait: a 429 without one is an error retrying cannot mend
        with pytest.raises(Exception, match="not yet"):
            join_graph(client, pacing, start=True)
        return
    join_graph(client, pacing, start=True)
    assert clock.sleeps == [pytest.approx(slept)]
    assert asked[1] == ("start=true&turn=t" if sent_turn else "start=true&turn=new")


def test_a_start_that_keeps_no_ticket_is_not_kept_out_by_the_turns_kept() -> None:
    """A client that asks without ``turn`` (as before there were tickets) is told its wait with
    no ticket and no turn kept for it; back at that time it goes, the kept turns' slots around it
    notwithstanding (were a turn kept for it, that turn would be in its own way every time)."""
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(None) is None  # A
    b = told(pacer.admit(NEW_TURN))  # turn at 101, kept
    c = told(pacer.admit(None))  # turn at 102, not kept
    d = told(pacer.admit(NEW_TURN))  # turn at 103, kept
    assert (c.ticket, c.wait_s) == (None, pytest.approx(2.0)) and b.ticket and d.ticket
    clock.now = 101.1
    assert pacer.admit(b.ticket) is None
    clock.now = 102.05  # C, 0.05 s after its time
    assert pacer.admit(None) is None
    clock.now = 103.2
    assert pacer.admit(d.ticket) is None


def test_a_world_asking_in_a_loop_waits_behind_its_own_few_turns_and_moves_no_one_else() -> None:
    """A student asking to start again and again (with or without ``turn=new``) is given at most
    ``MAX_WAITING`` turns at once; past them each ask is told the end of the line and moves it
    not at all, so another world's start is told the turn it would have had anyway."""
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN, "ada") is None  # holds the slot till 101
    given = [told(pacer.admit(NEW_TURN, "mallory")) for _ in range(MAX_WAITING)]
    assert all(t.ticket for t in given)
    flood = [told(pacer.admit(kind, "mallory")) for kind in (NEW_TURN, None) * 50]
    assert all(t.ticket is None for t in flood)
    end_of_line = 101.0 + MAX_WAITING * HOLD_S - clock.now
    assert all(t.wait_s == pytest.approx(end_of_line) for t in flood)
    bob = told(pacer.admit(NEW_TURN, "bob"))
    assert bob.wait_s == pytest.approx(end_of_line) and bob.ticket  # behind mallory's few, not the flood
    clock.now = 101.0
    assert pacer.admit(given[0].ticket, "bob") is not None  # a ticket goes for the world it was given to


def test_without_the_cap_the_same_flood_would_push_the_others_back() -> None:
    """What the cap keeps: each of a flood's asks, were it given a turn, would put another world's
    start one turn later (the line as every ask from distinct worlds builds it)."""
    clock = Clock()
    pacer = StartPacer(1, HOLD_S, clock)
    assert pacer.admit(NEW_TURN, "ada") is None
    for i in range(MAX_WAITING + 100):
        told(pacer.admit(NEW_TURN, f"world{i}"))  # as many worlds as asks: none over its cap
    bob = told(pacer.admit(NEW_TURN, "bob"))
    assert bob.wait_s == pytest.approx(1.0 + (MAX_WAITING + 100) * HOLD_S)


def test_a_pacer_the_worlds_loop_builds_holds_a_slot_shorter_when_that_loop_is_real_time() -> None:
    """Built on a thread in the real-time class (as the worlds' loop is where the machine allows it)
    a pacer holds each slot the pacer's ``HOLD_S``; on a thread in the fair class,
    ``FAIR_LOOP_HOLD_S``: there the starts beside the loop slow the worlds."""
    if os.geteuid() != 0:
        pytest.skip("the real-time class needs root or an RLIMIT_RTPRIO here; the suite runs as root")
    built: dict[str, float] = {}

    def build(scheduling: Scheduling) -> None:
        with loop_priority(scheduling) as priority:
            assert priority.scheduling == scheduling, priority.why
            built[scheduling] = StartPacer(1).hold_s

    for scheduling in SCHEDULINGS:
        thread = threading.Thread(target=build, args=(scheduling,))
        thread.start()
        thread.join(timeout=30)
    assert built == {"realtime": PACER_HOLD_S, "normal": FAIR_LOOP_HOLD_S}
    assert PACER_HOLD_S < FAIR_LOOP_HOLD_S
